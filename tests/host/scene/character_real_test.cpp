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
    d.humanoid_map = cesium_man_humanoid_map();
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
