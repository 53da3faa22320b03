// Test helper for character types: load one from a file, and check that it has the canonical
// layers, walks kinematically with planted feet and reaches with its right wrist.
#pragma once

#include "host/scene/character_type.hpp"
#include "systems/motion/dynamic/dynamic_hook.hpp"
#include "systems/motion/ik/chain_fk.hpp"
#include "systems/motion/ik/ik_hooks.hpp"
#include "tests/common/test_humanoid.hpp"
#include "tests/systems/motion/walk_request.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <system_error>
#include <vector>

#include <unistd.h>

namespace aloha::test {

namespace fs = std::filesystem;

inline constexpr float kDt = 1.0f / 60.0f;

/// The folders temp_dir made, removed when the test program ends if every test passed (kept to look into after a
/// failure).
struct TempDirs {
    std::vector<fs::path> made;
    ~TempDirs() {
        if (!::testing::UnitTest::GetInstance()->Passed()) return;
        for (const fs::path& p : made) {
            std::error_code ec;
            fs::remove_all(p, ec);
        }
    }
};

/// A fresh folder for one test's files under the system's temporary folder (per process; see TempDirs).
inline fs::path temp_dir(const std::string& name) {
    static TempDirs dirs;
    const fs::path p = fs::temp_directory_path() / ("aloha_chars_" + name + "_" + std::to_string(::getpid()));
    fs::create_directories(p);
    dirs.made.push_back(p);
    return p;
}

inline std::string builtin_humanoid() { return test::humanoid_definition_path(); }

inline CharacterTypeDesc desc_for(const std::string& name, const std::string& file) {
    CharacterTypeDesc d;
    d.name = name;
    (file.size() > 4 && file.substr(file.size() - 4) == ".bvh" ? d.bvh : d.gltf) = file;
    d.canonical = builtin_humanoid();
    d.scene_file = "test-scene.json";
    d.pointer = "/character_types/0";
    return d;
}

/// The humanoid_map that makes CesiumMan.glb (../shared/assets), whose joint names follow no convention, a
/// humanoid (docs/CHARACTERS.md prints the same map).
inline std::map<std::string, std::string> cesium_man_humanoid_map() {
    return {{"Hips", "Skeleton_torso_joint_1"}, {"Chest", "Skeleton_torso_joint_2"}, {"Chest2", "torso_joint_3"},
            {"lowerneck", "Skeleton_neck_joint_1"}, {"Head", "Skeleton_neck_joint_2"},
            {"LeftShoulder", "Skeleton_arm_joint_L__4_"}, {"LeftElbow", "Skeleton_arm_joint_L__3_"},
            {"LeftWrist", "Skeleton_arm_joint_L__2_"}, {"RightShoulder", "Skeleton_arm_joint_R"},
            {"RightElbow", "Skeleton_arm_joint_R__2_"}, {"RightWrist", "Skeleton_arm_joint_R__3_"},
            {"LeftHip", "leg_joint_L_1"}, {"LeftKnee", "leg_joint_L_2"}, {"LeftAnkle", "leg_joint_L_3"},
            {"LeftToe", "leg_joint_L_5"}, {"RightHip", "leg_joint_R_1"}, {"RightKnee", "leg_joint_R_2"},
            {"RightAnkle", "leg_joint_R_3"}, {"RightToe", "leg_joint_R_5"}};
}

inline CharacterType load_or_fail(const CharacterTypeDesc& d) {
    auto t = load_character_type(d);
    EXPECT_TRUE(t.ok()) << (t.ok() ? "" : t.error().to_string());
    return t.ok() ? std::move(t.value()) : CharacterType{};
}

inline int builtin_muscle_count() {
    CharacterTypeDesc d;
    d.name = "h";
    d.humanoid = builtin_humanoid();
    return load_or_fail(d).muscles.size();
}

inline glm::vec3 world_of(const MotionController& mc, const Transform& x, int joint) {
    return x.position + x.rotation * ik::matrix_position(mc.poses().view(0).model[static_cast<size_t>(joint)]);
}

// The canonical layers: every canonical muscle placed, knees limited, a walk rig.
// `canonical_muscles` false: the type has a mesh its muscles are fitted to instead.
inline void expect_layers(const CharacterType& t, const std::string& convention, const std::string& knee,
                          bool canonical_muscles = true) {
    EXPECT_TRUE(t.map.humanoid);
    EXPECT_EQ(t.map.convention, convention);
    if (canonical_muscles) EXPECT_EQ(t.muscles.size(), builtin_muscle_count());
    else EXPECT_GT(t.muscles.size(), 0);
    const int k = t.skeleton.find(knee);
    ASSERT_GE(k, 0);
    EXPECT_TRUE(t.skeleton.limits()[static_cast<size_t>(k)].limited) << knee;
    EXPECT_TRUE(t.rig.has_value());
}

// Kinematic walk for 5 s at 1.2 m/s: planted feet hold within 1 cm (the walk's requirement), the
// root advances at the speed, the head stays above 80% of the standing height (upright).
inline void expect_walks(const CharacterType& t) {
    ASSERT_TRUE(t.rig.has_value());
    MotionController mc(t.skeleton, t.clips, 1);
    mc.set_walk_rig(*t.rig);
    std::vector<AnimLod> lods(1);
    lods[0].walk = WalkMethod::Kinematic;
    std::vector<MotionState> states(1);
    std::vector<Transform> xs(1);
    std::vector<Velocity> vs(1);
    ASSERT_TRUE(mc.push_request(0, straight_walk(1.2f)));
    const int head = t.map.find("Head");
    glm::vec3 start[2];
    bool in_stance[2] = {false, false};
    float worst = 0.0f, lowest_head = 1e9f;
    int stances = 0;
    for (int frame = 0; frame < 300; ++frame) {
        mc.update(kDt, lods, states, xs, vs);
        lowest_head = std::min(lowest_head, world_of(mc, xs[0], head).y);
        for (int side = 0; side < 2; ++side) {
            float phi = states[0].phase + (side == 0 ? 0.0f : 0.5f);
            phi -= std::floor(phi);
            const bool st = phi < GaitParams{}.duty;
            const glm::vec3 p = world_of(mc, xs[0], t.rig->ankle[side]);
            if (st && !in_stance[side]) start[side] = p, ++stances;
            else if (st) worst = std::max(worst, glm::length(p - start[side]));
            in_stance[side] = st;
        }
    }
    std::printf("[figure] %s kinematic walk: planted ankle drift %.2g m, root %.4f m, lowest head %.3f m\n",
                t.name.c_str(), static_cast<double>(worst), static_cast<double>(xs[0].position.z), static_cast<double>(lowest_head));
    EXPECT_GE(stances, 8);
    EXPECT_LT(worst, 0.01f);
    EXPECT_NEAR(xs[0].position.z, 1.2f * 300 * kDt, 1e-3f);
    EXPECT_GT(lowest_head, 0.8f * t.frame.height);
}

// Dynamic walk for 5 s at 1.2 m/s: simulated, finite, upright (the head stays above the pelvis by
// more than cos 45 degrees of its rest height over it: a torso leaning less than 45 degrees), the
// pelvis within 0.15 m of the kinematic gait's it tracks, the root at 1.2 m/s (as in
// tests/systems/motion/dynamic/dynamic_hook_test.cpp).
// `max_track` loosens the pelvis bound for a rig the dynamic walk is known to track looser.
inline void expect_dynamic_walks(const CharacterType& t, float max_track = 0.15f) {
    ASSERT_TRUE(t.rig.has_value());
    MotionController mc(t.skeleton, t.clips, 2);
    mc.set_walk_rig(*t.rig);
    DynamicHookContext dyn;
    register_dynamic_walk_hook(mc, dyn);
    std::vector<AnimLod> lods(2);
    lods[0].walk = WalkMethod::Dynamic;
    lods[1].walk = WalkMethod::Kinematic;
    std::vector<MotionState> states(2);
    std::vector<Transform> xs(2);
    std::vector<Velocity> vs(2);
    ASSERT_TRUE(mc.push_request(0, straight_walk(1.2f)));
    ASSERT_TRUE(mc.push_request(1, straight_walk(1.2f)));
    const auto hips = static_cast<size_t>(t.rig->root), head = static_cast<size_t>(t.map.find("Head"));
    const auto rest = skeleton_rest_model(t.skeleton);
    const float rest_rise = rest[head][3].y - rest[hips][3].y;
    float min_rise = 1e9f, worst_track = 0.0f;
    for (int frame = 0; frame < 300; ++frame) {
        mc.update(kDt, lods, states, xs, vs);
        const ConstPoseView d = mc.poses().view(0), k = mc.poses().view(1);
        ASSERT_EQ(dyn.simulated(), 1u);
        ASSERT_TRUE(std::isfinite(d.model[head][3].y)) << "frame " << frame;
        min_rise = std::min(min_rise, d.model[head][3].y - d.model[hips][3].y);
        worst_track = std::max(worst_track, glm::length(glm::vec3(d.model[hips][3]) - glm::vec3(k.model[hips][3])));
    }
    std::printf("[figure] %s dynamic walk: head over pelvis >= %.3f m (rest %.3f), pelvis tracking <= %.3f m, root %.3f m\n",
                t.name.c_str(), static_cast<double>(min_rise), static_cast<double>(rest_rise), static_cast<double>(worst_track),
                static_cast<double>(xs[0].position.z));
    EXPECT_GT(min_rise, 0.7071f * rest_rise);
    EXPECT_LT(worst_track, max_track);
    EXPECT_NEAR(xs[0].position.z, 6.0f, 0.05f);
}

// Reach with the right wrist (the canonical RightWrist) to a point forward-down of the right
// shoulder at 75% of the arm's length: within the LOD's 1 mm tolerance (plus float slack) after 1 s.
inline void expect_reaches(const CharacterType& t) {
    ClipLibrary clips;
    MotionController mc(t.skeleton, clips, 1);
    IkHookContext ik;
    ik.map = &t.map;
    register_ik_hooks(mc, ik);
    EXPECT_EQ(ik.reach_base[static_cast<size_t>(t.map.find("RightWrist"))], t.map.find("RightShoulder"));
    std::vector<AnimLod> lods(1);
    lods[0].ik = IkSolver::Dls;
    lods[0].ik_iterations = 20;
    lods[0].ik_tolerance = 1e-3f;
    std::vector<MotionState> states(1);
    std::vector<Transform> xs(1);
    std::vector<Velocity> vs(1);
    mc.update(kDt, lods, states, xs, vs);
    const glm::vec3 shoulder = world_of(mc, xs[0], t.map.find("RightShoulder"));
    const glm::vec3 elbow = world_of(mc, xs[0], t.map.find("RightElbow"));
    const glm::vec3 wrist = world_of(mc, xs[0], t.map.find("RightWrist"));
    const float arm = glm::length(elbow - shoulder) + glm::length(wrist - elbow);
    MotionRequest r;
    r.kind = RequestKind::Reach;
    r.effector = static_cast<int16_t>(t.map.find("RightWrist"));
    r.target = shoulder + 0.75f * arm * glm::normalize(glm::vec3(-0.1f, -0.55f, 0.82f));
    r.crossfade_s = 0.2f;
    ASSERT_TRUE(mc.push_request(0, r));
    for (int frame = 0; frame < 60; ++frame) mc.update(kDt, lods, states, xs, vs);
    const float miss = glm::length(world_of(mc, xs[0], r.effector) - r.target);
    std::printf("[figure] %s reach: %.3f m from the shoulder, wrist %.2g m from the target\n", t.name.c_str(),
                static_cast<double>(glm::length(r.target - shoulder)), static_cast<double>(miss));
    EXPECT_LE(miss, 1e-3f + 1e-4f);
}

// Walks `t` for 5 s at `speed` at the clip level over its walk clips: the number of ankle contacts and the
// farthest a planted ankle moved from its touchdown, contact as issue 15 defines it (within 5 mm of the ankle's
// lowest height and under 0.5 m/s); `travel` gets the distance the character went.
inline std::pair<int, float> clip_walk(const CharacterType& t, float speed, float* travel) {
    MotionController mc(t.skeleton, t.clips, 1);
    mc.set_walk_rig(*t.rig);
    mc.set_walk_clips(t.gait_clips);
    std::vector<AnimLod> lods(1);
    lods[0].walk = WalkMethod::ClipPlayback;
    std::vector<MotionState> states(1);
    std::vector<Transform> xs(1);
    std::vector<Velocity> vs(1);
    EXPECT_TRUE(mc.push_request(0, straight_walk(speed)));
    std::vector<std::array<glm::vec3, 2>> ankles;
    for (int frame = 0; frame < 300; ++frame) {
        mc.update(kDt, lods, states, xs, vs);
        ankles.push_back({world_of(mc, xs[0], t.rig->ankle[0]), world_of(mc, xs[0], t.rig->ankle[1])});
    }
    float worst = 0.0f;
    int contacts = 0;
    for (size_t side = 0; side < 2; ++side) {
        float lowest = 1e9f;
        for (const auto& a : ankles) lowest = std::min(lowest, a[side].y);
        bool down = false;
        glm::vec3 start{};
        for (size_t f = 1; f < ankles.size(); ++f) {
            const glm::vec3 p = ankles[f][side], q = ankles[f - 1][side];
            const bool on = p.y < lowest + 0.005f && glm::length(glm::vec2(p.x - q.x, p.z - q.z)) / kDt < 0.5f;
            if (on && !down) start = p, ++contacts;
            if (on) worst = std::max(worst, glm::length(glm::vec2(p.x - start.x, p.z - start.z)));
            down = on;
        }
    }
    *travel = glm::length(xs[0].position);
    return {contacts, worst};
}

/// `t` walks at `speed` at the clip level for 5 s (clip_walk) as every clip walk must: at least 6 ankle contacts,
/// planted ankles drifting under 1 cm (the kinematic walk's bar), the distance the speed says within 5 cm. Prints the
/// figures as "[figure] <what> at <speed> m/s: ...".
inline void expect_clip_walk(const CharacterType& t, float speed, const std::string& what) {
    float travel = 0.0f;
    const auto [contacts, drift] = clip_walk(t, speed, &travel);
    std::printf("[figure] %s at %.2f m/s: %d contacts, planted ankle drift %.2g m, went %.3f m\n", what.c_str(), static_cast<double>(speed),
                contacts, static_cast<double>(drift), static_cast<double>(travel));
    EXPECT_GE(contacts, 6) << what << " at " << speed;
    EXPECT_LT(drift, 0.01f) << what << " at " << speed;
    EXPECT_NEAR(travel, speed * 300 * kDt, 0.05f) << what << " at " << speed;
}

}  // namespace aloha::test
