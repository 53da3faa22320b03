// Humanoid muscle layout file and loader errors (file + JSON path for every kind of problem).
#include "systems/geometry/muscle/muscle_loader.hpp"
#include "systems/geometry/muscle/muscle_shape_job.hpp"
#include "systems/geometry/muscle/muscle_tessellate_job.hpp"
#include "tests/systems/geometry/muscle/test_skeletons.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>

namespace aloha {
namespace {

const std::string kHumanoid = std::string(ALOHA_SOURCE_DIR) + "/data/characters/humanoid_muscles.json";

TEST(MuscleLoader, HumanoidLayoutResolvesOnCmuSkeleton) {
    const Skeleton cmu = test::make_cmu_skeleton();
    ASSERT_EQ(cmu.joint_count(), 31);
    auto set = load_muscle_set(kHumanoid, cmu);
    ASSERT_TRUE(set.ok()) << set.error().to_string();
    const MuscleSet& m = set.value();
    EXPECT_GE(m.size(), 30);
    for (int i = 0; i < m.size(); ++i) {
        const size_t u = static_cast<size_t>(i);
        EXPECT_GT(m.volume[u], 0.0f) << m.names[u];
        EXPECT_TRUE(std::isfinite(m.volume[u]) && std::isfinite(m.ratio[u])) << m.names[u];
        EXPECT_GT(m.rest_length[u], 0.02f) << m.names[u];
        EXPECT_NEAR(glm::length(m.depth_hint[u]), 1.0f, 1e-5f) << m.names[u];
    }
    // Mirrored pairs: same definition on both sides, so volumes differ only by the skeleton's own
    // left/right asymmetry in bone lengths (CMU arms differ by ~5 %).
    const int l = m.find("biceps_l"), r = m.find("biceps_r");
    ASSERT_GE(l, 0);
    ASSERT_GE(r, 0);
    EXPECT_NEAR(m.volume[static_cast<size_t>(l)] / m.volume[static_cast<size_t>(r)], 1.0f, 0.1f);
    EXPECT_EQ(cmu.names()[static_cast<size_t>(m.origin_joint[static_cast<size_t>(r)])], "RightShoulder");

    // Rest-pose shapes and a tessellation: finite everywhere, body-sized.
    const auto rest = rest_model_matrices(cmu);
    const size_t n = static_cast<size_t>(m.size());
    std::vector<glm::vec3> centres(n), radii(n);
    std::vector<glm::quat> rots(n);
    MuscleShapeJob shape{&m, rest, centres, rots, radii};
    ASSERT_TRUE(shape.Validate());
    shape.Run();
    const SuperEllipsoidTables tables(8, 6, m);
    std::vector<glm::vec3> pos(n * tables.vertices_per_muscle()), nrm(pos.size());
    MuscleTessellateJob tess{&tables, centres, rots, radii, pos, nrm};
    ASSERT_TRUE(tess.Validate());
    tess.Run();
    glm::vec3 lo(1e9f), hi(-1e9f);
    for (size_t v = 0; v < pos.size(); ++v) {
        ASSERT_TRUE(std::isfinite(pos[v].x + pos[v].y + pos[v].z + nrm[v].x + nrm[v].y + nrm[v].z)) << v;
        lo = glm::min(lo, pos[v]);
        hi = glm::max(hi, pos[v]);
    }
    // CMU rest pose in metres: head top ~0.5 m above the hips, toes ~0.9 m below; legs splayed.
    EXPECT_GT(hi.y, 0.45f);
    EXPECT_LT(hi.y, 0.65f);
    EXPECT_LT(lo.y, -0.85f);
    EXPECT_GT(lo.y, -1.0f);
    for (size_t i = 0; i < n; ++i) EXPECT_LT(radii[i].x, 0.3f) << m.names[i];  // no muscle longer than 0.6 m
}

TEST(MuscleLoader, MirrorJointNames) {
    EXPECT_EQ(mirror_joint_name("LeftShoulder"), "RightShoulder");
    EXPECT_EQ(mirror_joint_name("RightToe"), "LeftToe");
    EXPECT_EQ(mirror_joint_name("LHipJoint"), "RHipJoint");
    EXPECT_EQ(mirror_joint_name("lhand"), "rhand");
    EXPECT_EQ(mirror_joint_name("lowerback"), "lowerback");
    EXPECT_EQ(mirror_joint_name("Chest2"), "Chest2");
}

nlohmann::json one_muscle() {
    return nlohmann::json::parse(R"({"muscles": [{"name": "m",
        "origin": {"joint": "LeftShoulder", "offset": [0, -0.02, 0.02]},
        "insertion": {"joint": "LeftElbow", "along": 0.1}, "radii": [0.03, 0.02]}]})");
}

// Parses + resolves `doc` against the CMU skeleton; returns the error text ("" when it loads).
std::string load_error(const nlohmann::json& doc) {
    auto defs = parse_muscle_defs(doc, "bad.json");
    if (!defs.ok()) return defs.error().to_string();
    auto set = resolve_muscles(defs.value(), test::make_cmu_skeleton(), "bad.json");
    return set.ok() ? "" : set.error().to_string();
}

TEST(MuscleLoader, ValidMinimalDocumentLoads) { EXPECT_EQ(load_error(one_muscle()), ""); }

// "trunk_skin" (default false) reaches the set, on a muscle and on its mirrored copy; the humanoid's deltoids have it.
TEST(MuscleLoader, TrunkSkinIsReadAndMirrored) {
    auto doc = one_muscle();
    doc["muscles"][0]["trunk_skin"] = true;
    doc["muscles"][0]["mirror"] = "m_r";
    doc["muscles"].push_back(one_muscle()["muscles"][0]);
    doc["muscles"][1]["name"] = "plain";
    auto defs = parse_muscle_defs(doc, "t.json");
    ASSERT_TRUE(defs.ok()) << defs.error().to_string();
    auto set = resolve_muscles(defs.value(), test::make_cmu_skeleton(), "t.json");
    ASSERT_TRUE(set.ok()) << set.error().to_string();
    const MuscleSet& m = set.value();
    ASSERT_EQ(m.trunk_skin.size(), 3u);
    EXPECT_EQ(m.trunk_skin[static_cast<size_t>(m.find("m"))], 1);
    EXPECT_EQ(m.trunk_skin[static_cast<size_t>(m.find("m_r"))], 1);
    EXPECT_EQ(m.trunk_skin[static_cast<size_t>(m.find("plain"))], 0);
    auto humanoid = load_muscle_set(kHumanoid, test::make_cmu_skeleton());
    ASSERT_TRUE(humanoid.ok());
    for (const char* name : {"deltoid_l", "deltoid_r"}) EXPECT_EQ(humanoid.value().trunk_skin[static_cast<size_t>(humanoid.value().find(name))], 1) << name;
    EXPECT_EQ(humanoid.value().trunk_skin[static_cast<size_t>(humanoid.value().find("biceps_l"))], 0);
}

TEST(MuscleLoader, ErrorsNameFileAndJsonPath) {
    auto doc = one_muscle();
    doc["muscles"][0]["origin"]["joint"] = "LeftShoulderr";
    EXPECT_EQ(load_error(doc), "bad.json: /muscles/0/origin/joint: muscle 'm': unknown joint 'LeftShoulderr'");

    doc = one_muscle();
    doc["muscles"][0]["radii"] = {0.03, -0.01};
    EXPECT_NE(load_error(doc).find("bad.json: /muscles/0/radii: radii must be positive"), std::string::npos);

    doc = one_muscle();
    doc["muscles"][0]["exponents"] = {1.0, 2.5};
    EXPECT_NE(load_error(doc).find("/muscles/0/exponents"), std::string::npos) << load_error(doc);

    doc = one_muscle();
    doc["muscles"][0].erase("insertion");
    EXPECT_EQ(load_error(doc), "bad.json: /muscles/0: missing required key 'insertion'");

    doc = one_muscle();
    doc["muscles"][0].erase("radii");
    EXPECT_NE(load_error(doc).find("/muscles/0: give exactly one of 'radii'"), std::string::npos);

    doc = one_muscle();
    doc["muscles"][0]["origin"]["along"] = 0.5;
    doc["muscles"][0]["origin"]["joint"] = "lowerneck";  // fine: lowerneck -> Neck has length
    doc["muscles"][0]["insertion"] = {{"joint", "LeftWrist"}, {"along", 0.5}};  // LeftWrist's children have zero offsets
    EXPECT_NE(load_error(doc).find("/muscles/0/insertion/along"), std::string::npos) << load_error(doc);

    doc = one_muscle();
    doc["muscles"][0]["insertion"] = doc["muscles"][0]["origin"];  // zero length at rest
    EXPECT_NE(load_error(doc).find("coincide"), std::string::npos);

    doc = one_muscle();
    doc["muscles"][0]["fat_thickness"] = "thick";
    EXPECT_EQ(load_error(doc), "bad.json: /muscles/0/fat_thickness: expected a number, got string");

    doc = one_muscle();
    doc["muscles"][0]["trunk_skin"] = "yes";
    EXPECT_EQ(load_error(doc), "bad.json: /muscles/0/trunk_skin: expected true or false, got string") << load_error(doc);

    doc = one_muscle();
    doc["muscles"][0]["radius"] = 0.03;  // a typo is refused, naming the keys a muscle may have
    EXPECT_NE(load_error(doc).find("/muscles/0/radius: unknown key 'radius' (allowed: name, description, origin"), std::string::npos)
        << load_error(doc);
}

TEST(MuscleLoader, EveryBadEntryIsReported) {
    auto doc = one_muscle();
    doc["muscles"].push_back(doc["muscles"][0]);
    doc["muscles"].push_back(doc["muscles"][0]);
    doc["muscles"][1]["name"] = "second";
    doc["muscles"][1]["origin"]["joint"] = "Nope";
    doc["muscles"][2]["name"] = "third";
    doc["muscles"][2]["insertion"]["joint"] = "AlsoNope";
    const std::string e = load_error(doc);
    EXPECT_NE(e.find("/muscles/1/origin/joint"), std::string::npos) << e;
    EXPECT_NE(e.find("/muscles/2/insertion/joint"), std::string::npos) << e;
}

TEST(MuscleLoader, SyntaxErrorHasLineAndColumnAndMissingFileIsNamed) {
    const auto path = std::filesystem::temp_directory_path() / "aloha_muscle_loader_syntax_test.json";
    {
        std::ofstream out(path);
        out << "{\n  \"muscles\": [\n    { \"name\": \"x\",, }\n  ]\n}\n";
    }
    auto r = load_muscle_defs(path.string());
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().file, path.string());
    EXPECT_EQ(r.error().line, 3);
    EXPECT_GT(r.error().column, 1);
    std::filesystem::remove(path);
    auto missing = load_muscle_defs("/nonexistent/muscles.json");
    ASSERT_FALSE(missing.ok());
    EXPECT_EQ(missing.error().to_string(), "/nonexistent/muscles.json: cannot open muscle layout file");
}

}  // namespace
}  // namespace aloha
