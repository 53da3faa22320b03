// Characters users bring, real files from ../shared/assets (never in the repository; skipped when
// absent): the CMU 131_01.bvh maps by name in CMU units; CesiumMan.glb, whose joint names follow no
// convention, maps through an explicit humanoid_map; both get limits, a kinematic and a dynamic walk
// and a reach.
#include "tests/common/test_assets.hpp"
#include "tests/host/scene/character_checks.hpp"

namespace aloha {
namespace {

using namespace test;  // NOLINT: the character checks

TEST(CharacterReal, Cmu131BvhMapsByName) {
    ALOHA_REQUIRE_TEST_ASSET(path, "131_01.bvh");
    const CharacterType t = load_or_fail(desc_for("cmu", path));
    EXPECT_EQ(t.frame.units, "CMU units (0.056444 m)");
    EXPECT_EQ(t.frame.up, "+Y");
    expect_layers(t, "CMU BVH", "LeftKnee");
    expect_walks(t);
    expect_dynamic_walks(t);
    expect_reaches(t);
}

TEST(CharacterReal, CesiumManThroughAnExplicitMap) {
    ALOHA_REQUIRE_TEST_ASSET(path, "CesiumMan.glb");
    CharacterTypeDesc d = desc_for("cesium", path);
    d.humanoid_map = {{"Hips", "Skeleton_torso_joint_1"}, {"Chest", "Skeleton_torso_joint_2"}, {"Chest2", "torso_joint_3"},
                      {"lowerneck", "Skeleton_neck_joint_1"}, {"Head", "Skeleton_neck_joint_2"},
                      {"LeftShoulder", "Skeleton_arm_joint_L__4_"}, {"LeftElbow", "Skeleton_arm_joint_L__3_"},
                      {"LeftWrist", "Skeleton_arm_joint_L__2_"}, {"RightShoulder", "Skeleton_arm_joint_R"},
                      {"RightElbow", "Skeleton_arm_joint_R__2_"}, {"RightWrist", "Skeleton_arm_joint_R__3_"},
                      {"LeftHip", "leg_joint_L_1"}, {"LeftKnee", "leg_joint_L_2"}, {"LeftAnkle", "leg_joint_L_3"},
                      {"LeftToe", "leg_joint_L_5"}, {"RightHip", "leg_joint_R_1"}, {"RightKnee", "leg_joint_R_2"},
                      {"RightAnkle", "leg_joint_R_3"}, {"RightToe", "leg_joint_R_5"}};
    const CharacterType bare = load_or_fail(desc_for("cesium", path));
    EXPECT_FALSE(bare.map.humanoid);
    // Unmapped it is a non-humanoid: its mesh, no muscles (layered levels refused), no walk rig.
    EXPECT_TRUE(bare.mesh.has_value());
    EXPECT_EQ(bare.muscles.size(), 0);
    EXPECT_FALSE(bare.rig.has_value());
    const CharacterType t = load_or_fail(d);
    EXPECT_EQ(t.frame.units, "metres");
    expect_layers(t, "explicit humanoid_map", "leg_joint_L_2", /*canonical_muscles=*/false);
    expect_walks(t);
    expect_dynamic_walks(t);
    expect_reaches(t);
}

}  // namespace
}  // namespace aloha
