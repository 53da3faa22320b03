// A glTF character (CesiumMan, muscles fitted per bone) at every geometric level. CesiumMan.glb is a
// shared test asset, not in the repository (tests/common/test_assets.hpp): the test skips without it.
#include "tests/common/test_assets.hpp"
#include "tests/systems/geometry/controller/test_cesium.hpp"
#include "tests/systems/geometry/controller/test_humanoid.hpp"

#include <gtest/gtest.h>

namespace aloha {
namespace {

TEST(GeometryControllerGltf, CesiumManWorksAtEveryLevel) {
    ALOHA_REQUIRE_TEST_ASSET(path, "CesiumMan.glb");
    const test::Cesium& cesium = test::load_cesium(path);
    ASSERT_NE(cesium.geometry, nullptr) << cesium.error;
    const CharacterGeometry& g = *cesium.geometry;
    const uint32_t n = static_cast<uint32_t>(g.mesh().positions.size());
    EXPECT_EQ(n, 3273u);
    const auto levels = test::test_levels();
    GeometryController ctl(g, levels, levels.size());
    for (uint8_t l = 0; l < levels.size(); ++l) ctl.begin_level(l, l, -1, 0);
    // Mesh levels show the real mesh's vertices (refined ones at the Subdivided level).
    for (uint8_t l = 1; l <= 3; ++l) EXPECT_EQ(ctl.vertices_per_character(l), n);
    EXPECT_GT(ctl.vertices_per_character(0), n);
    EXPECT_EQ(ctl.level_indices(1).size(), g.mesh().indices.size());
    // CesiumMan's one textured material: its UVs reach every mesh level (through the subdivision
    // stencils at level 0, as weighted sums of UVs in [0, 1]: still in [0, 1]).
    ASSERT_EQ(g.mesh().uvs.size(), n);
    for (uint8_t l = 0; l <= 3; ++l) {
        ASSERT_EQ(ctl.level_uvs(l).size(), ctl.vertices_per_character(l)) << int(l);
        ASSERT_EQ(ctl.level_vertex_materials(l).size(), ctl.vertices_per_character(l)) << int(l);
    }
    for (const glm::vec2& uv : ctl.level_uvs(0)) {
        ASSERT_GE(uv.x, -1e-5f);
        ASSERT_LE(uv.x, 1.0f + 1e-5f);
    }

    // At the rest pose the real mesh is reproduced: SkinnedMesh by construction (palette = rest *
    // inverse bind) and Layered(16, 12) because it is the bind tessellation, where a binding
    // evaluates to its own vertex (float rounding of frames at ~1 m: 1e-4).
    const PoseSource rest{g.rest_model().data(), 0};
    for (uint32_t c = 0; c < levels.size(); ++c) ctl.update(static_cast<uint8_t>(c), std::span(&c, 1), rest, 1.0f / 30.0f);
    EXPECT_LE(test::max_distance(ctl.surface(3).positions, g.mesh_rest_positions()), 1e-4f);
    EXPECT_LE(test::max_distance(ctl.surface(1).positions, g.mesh_rest_positions()), 1e-4f);

    // Animated frames: every level gives finite output of its size, unit normals.
    for (size_t key = 0; key < 40; key += 8) {
        const auto pose = test::clip_pose(g.skeleton(), cesium.clip, key);
        for (uint32_t c = 0; c < levels.size(); ++c) ctl.update(static_cast<uint8_t>(c), std::span(&c, 1), PoseSource{pose.data(), 0}, 1.0f / 30.0f);
        for (uint8_t l = 0; l <= 3; ++l) {
            SCOPED_TRACE(static_cast<int>(l));
            const SurfaceView view = ctl.surface(l);
            ASSERT_EQ(view.positions.size(), ctl.vertices_per_character(l));
            ASSERT_EQ(view.normals.size(), view.positions.size());
            for (size_t i = 0; i < view.positions.size(); ++i) {
                ASSERT_TRUE(test::finite(view.positions[i])) << i;
                ASSERT_NEAR(glm::length(view.normals[i]), 1.0f, 1e-5f) << i;
            }
        }
        EXPECT_EQ(ctl.proxy_boxes(4).size(), g.joint_count());
        // The layered mesh follows the skinned one: muscles sit inside the skin, so the two agree to
        // a few centimetres in any pose (not exactly: the muscles bulge and the tessellation differs).
        EXPECT_LT(test::max_distance(ctl.surface(1).positions, ctl.surface(3).positions), 0.1f);
    }

    // Morphing between mesh levels of a real mesh is vertex to vertex: the first frame moves each
    // vertex by |old - new| / N.
    const auto pose = test::clip_pose(g.skeleton(), cesium.clip, 20);
    const PoseSource src{pose.data(), 0};
    const std::vector<glm::vec3> old(ctl.surface(1).positions.begin(), ctl.surface(1).positions.end());
    ctl.begin_level(1, 3, 1, 4);
    const uint32_t c1 = 1;
    ctl.update(3, std::span(&c1, 1), src, 1.0f / 30.0f);
    std::vector<glm::vec3> fresh;
    ctl.reference_surface(src, 1, 3, fresh);  // what level 3 shows without a morph
    const auto shown = ctl.surface(1).positions;
    ASSERT_EQ(shown.size(), old.size());
    for (size_t i = 0; i < shown.size(); ++i)
        ASSERT_NEAR(glm::length(shown[i] - old[i]), glm::length(old[i] - fresh[i]) / 4.0f, 2e-5f) << i;
}

}  // namespace
}  // namespace aloha
