// Rig normalisation: units found from the standing height (a centimetre rig, a CMU-unit rig),
// axes from the skeleton (a Z-up rig, a rig facing +X), exactness of the change for clips and
// skins (M'_j = G M_j C_j for a posed rig with glTF-style rest rotations), and the cases that must
// not pass silently (a humanoid 1.7 cm or 170 m tall, a given scale making one 170 m tall).
#include "engine/assets/rig_normalise.hpp"
#include "tests/common/rig_fixtures.hpp"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

namespace aloha {
namespace {

constexpr float kPi = 3.14159265f;

std::map<std::string, std::string> cmu_names() {
    std::map<std::string, std::string> names;
    for (const CanonicalJoint& c : canonical_humanoid()) names[c.name] = c.name;
    return names;
}

struct Loaded {
    Skeleton original;
    HumanoidMap map;
    Result<RigFrame> frame = Error{};
};

Loaded load(const test::RigStyle& style, RigFormat format, float scale = 0.0f) {
    Loaded l;
    l.original = build_skeleton(test::styled(test::renamed_humanoid(cmu_names()), style), "fixture").value();
    l.map = map_humanoid(l.original).value();
    l.frame = detect_rig_frame(l.original, l.map, format, scale, "fixture");
    return l;
}

// Rest model positions of the normalised skeleton against the built-in humanoid's (1.75 m).
float worst_position_error(const Loaded& l) {
    const RigNormalisation n = normalise_rig(l.original, l.frame.value());
    const Skeleton out = build_skeleton(n.skeleton, "normalised").value();
    const Skeleton ref = test::humanoid_skeleton_for();
    const auto a = skeleton_rest_model(out), b = skeleton_rest_model(ref);
    float worst = 0.0f;
    for (int j = 0; j < ref.joint_count(); ++j)
        worst = std::max(worst, glm::length(glm::vec3(a[static_cast<size_t>(out.find(ref.names()[static_cast<size_t>(j)]))][3]) -
                                            glm::vec3(b[static_cast<size_t>(j)][3])));
    return worst;
}

TEST(RigNormalise, CentimetreBvhIsFoundFromItsHeight) {
    test::RigStyle cm;
    cm.units_per_metre = 100.0f;
    const Loaded l = load(cm, RigFormat::Bvh);
    ASSERT_TRUE(l.frame.ok()) << l.frame.error().to_string();
    EXPECT_EQ(l.frame.value().units, "centimetres");
    EXPECT_FLOAT_EQ(l.frame.value().metres_per_unit, 0.01f);
    EXPECT_EQ(l.frame.value().up, "+Y");
    EXPECT_EQ(l.frame.value().forward, "+Z");
    // Estimated standing height = joint span (head joint 0.885 H to toe 0.012 H = 0.873 H) x 1.1.
    EXPECT_NEAR(l.frame.value().height, 0.873f * 1.75f * 1.1f, 1e-3f);
    // float rounding of offsets of ~100 units: 1e-5 relative.
    EXPECT_LT(worst_position_error(l), 1e-5f);
}

TEST(RigNormalise, CmuUnitsAndMetresAndMillimetres) {
    for (const auto& [per_metre, units] : {std::pair<float, std::string>{1.0f / 0.056444f, "CMU units (0.056444 m)"},
                                           {1.0f, "metres"}, {1000.0f, "millimetres"}}) {
        test::RigStyle s;
        s.units_per_metre = per_metre;
        const Loaded l = load(s, RigFormat::Bvh);
        ASSERT_TRUE(l.frame.ok()) << l.frame.error().to_string();
        EXPECT_EQ(l.frame.value().units, units);
        EXPECT_LT(worst_position_error(l), 1e-5f) << units;
    }
}

TEST(RigNormalise, ZUpRigIsTurnedUpright) {
    test::RigStyle z_up;
    z_up.axes = glm::angleAxis(kPi / 2, glm::vec3(1, 0, 0));  // +Y up -> +Z up, +Z forward -> -Y
    for (RigFormat f : {RigFormat::Bvh, RigFormat::Gltf}) {
        const Loaded l = load(z_up, f);
        ASSERT_TRUE(l.frame.ok()) << l.frame.error().to_string();
        EXPECT_EQ(l.frame.value().up, "+Z");
        EXPECT_EQ(l.frame.value().forward, "-Y");
        EXPECT_LT(worst_position_error(l), 1e-5f);
    }
}

TEST(RigNormalise, RigFacingXIsTurnedToFaceZ) {
    test::RigStyle turned;
    turned.axes = glm::angleAxis(kPi / 2, glm::vec3(0, 1, 0));  // forward +Z -> +X
    turned.bone_frames = true;
    const Loaded l = load(turned, RigFormat::Gltf);
    ASSERT_TRUE(l.frame.ok()) << l.frame.error().to_string();
    EXPECT_EQ(l.frame.value().up, "+Y");
    EXPECT_EQ(l.frame.value().forward, "+X");
    EXPECT_LT(worst_position_error(l), 1e-5f);
    const RigNormalisation n = normalise_rig(l.original, l.frame.value());
    for (const RawJoint& j : n.skeleton.joints) EXPECT_EQ(j.rotation, glm::quat(1, 0, 0, 0)) << j.name;
}

// Local TRS of every joint composed to model matrices.
std::vector<glm::mat4> pose_model(const Skeleton& sk, const std::vector<glm::vec3>& t, const std::vector<glm::quat>& r,
                                  const std::vector<glm::vec3>& s) {
    std::vector<glm::mat4> m(t.size());
    for (size_t j = 0; j < t.size(); ++j) {
        const glm::mat4 local = glm::translate(glm::mat4(1.0f), t[j]) * glm::mat4_cast(r[j]) * glm::scale(glm::mat4(1.0f), s[j]);
        const int p = sk.parents()[j];
        m[j] = p < 0 ? local : m[static_cast<size_t>(p)] * local;
    }
    return m;
}

TEST(RigNormalise, ClipsAndSkinsFollowExactly) {
    // Z-up, centimetres, bone-aligned rest frames: everything a glTF exporter may write.
    test::RigStyle s;
    s.units_per_metre = 100.0f;
    s.axes = glm::angleAxis(kPi / 2, glm::vec3(1, 0, 0));
    s.bone_frames = true;
    const Loaded l = load(s, RigFormat::Gltf);
    ASSERT_TRUE(l.frame.ok()) << l.frame.error().to_string();
    EXPECT_EQ(l.frame.value().units, "centimetres");
    const RigNormalisation n = normalise_rig(l.original, l.frame.value());
    const Skeleton out = build_skeleton(n.skeleton, "normalised").value();
    // A pose: every joint turned from its rest by a different rotation, the root moved.
    const size_t J = static_cast<size_t>(l.original.joint_count());
    RawAnimation clip;
    clip.tracks.resize(J);
    std::vector<glm::vec3> t(J), ts(J, glm::vec3(1.0f));
    std::vector<glm::quat> r(J);
    for (size_t j = 0; j < J; ++j) {
        const float a = 0.1f + 0.05f * static_cast<float>(j);
        r[j] = glm::normalize(l.original.rest_rotations()[j] * glm::angleAxis(a, glm::normalize(glm::vec3(1, 2, 3 - static_cast<float>(j % 5)))));
        t[j] = l.original.rest_translations()[j] + (j == 0 ? glm::vec3(10, -20, 5) : glm::vec3(0.0f));
        clip.tracks[j].rotations = {{0.0f}, {r[j]}};
        clip.tracks[j].translations = {{0.0f}, {t[j]}};
    }
    normalise_clip(clip, l.original, n);
    std::vector<glm::vec3> t2(J), s2(J, glm::vec3(1.0f));
    std::vector<glm::quat> r2(J);
    for (size_t j = 0; j < J; ++j) t2[j] = clip.tracks[j].translations.values[0], r2[j] = clip.tracks[j].rotations.values[0];
    const auto before = pose_model(l.original, t, r, ts), after = pose_model(out, t2, r2, s2);
    float worst = 0.0f;
    for (size_t j = 0; j < J; ++j) {
        const glm::mat4 expected = n.global() * before[j] * n.correction(static_cast<int>(j));
        for (int c = 0; c < 4; ++c) worst = std::max(worst, glm::length(expected[c] - after[j][c]));
    }
    // Products of ~30 float rotations on metre-sized offsets: a few 1e-6 m.
    EXPECT_LT(worst, 2e-5f);
}

TEST(RigNormalise, ImplausibleSizesAreNeverSilent) {
    test::RigStyle tiny;
    tiny.units_per_metre = 0.01f;  // a 1.75 cm humanoid written in metres
    const Loaded l = load(tiny, RigFormat::Gltf);
    ASSERT_FALSE(l.frame.ok());
    EXPECT_NE(l.frame.error().message.find("give 'scale'"), std::string::npos) << l.frame.error().message;
    test::RigStyle giant;
    giant.units_per_metre = 100000.0f;  // 1750 m in metres, 17.5 m in millimetres: neither plausible
    ASSERT_FALSE(load(giant, RigFormat::Gltf).frame.ok());
    // A given scale is used, with a note when it makes the character 170 m tall.
    test::RigStyle m;
    const Loaded given = load(m, RigFormat::Gltf, 100.0f);
    ASSERT_TRUE(given.frame.ok());
    EXPECT_FLOAT_EQ(given.frame.value().metres_per_unit, 100.0f);
    ASSERT_EQ(given.frame.value().notes.size(), 1u);
    EXPECT_NE(given.frame.value().notes[0].find("m tall"), std::string::npos);
    const Loaded cm_given = load(m, RigFormat::Bvh, 1.0f);
    ASSERT_TRUE(cm_given.frame.ok());
    EXPECT_TRUE(cm_given.frame.value().notes.empty());
}

}  // namespace
}  // namespace aloha
