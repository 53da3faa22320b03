// The continuous skin (skin_layer.hpp) at the default rule file's mesh levels: one connected closed
// surface on the built-in humanoid, and no tearing or collapsing triangle edge under the walk, on the
// built-in humanoid and on CesiumMan (a shared third-party asset: that part skips without it).
#include "systems/geometry/body_skin/skin_remesh.hpp"
#include "systems/geometry/spring_skin/subdivision.hpp"
#include "tests/common/test_assets.hpp"
#include "tests/systems/geometry/controller/test_cesium.hpp"
#include "tests/systems/geometry/controller/test_humanoid.hpp"

#include <gtest/gtest.h>

#include <iostream>
#include <map>

namespace aloha {
namespace {

// The mesh levels of data/rules/default.json (subdivided 24x16/1, layered 16x12 and 8x6, skinned 6x3).
std::vector<GeomLod> default_mesh_levels() {
    std::vector<GeomLod> levels = {test::grid_level(GeomMethod::Subdivided, 24, 16, 1), test::grid_level(GeomMethod::Layered, 16, 12),
                                   test::grid_level(GeomMethod::Layered, 8, 6), test::grid_level(GeomMethod::SkinnedMesh, 6, 3)};
    for (size_t i = 0; i < levels.size(); ++i) levels[i].level = static_cast<uint8_t>(i);
    return levels;
}

// Smallest and largest ratio of an edge's current length to its bind length over a triangle list.
struct StretchRange {
    float lo = 1.0f, hi = 1.0f;
    glm::vec3 lo_at{0.0f}, hi_at{0.0f};  // bind-pose midpoints of the extreme edges
    size_t edges = 0, outside = 0;       // edges measured, edges outside [0.5, 2]
    void add(std::span<const uint32_t> indices, std::span<const glm::vec3> bind, std::span<const glm::vec3> now) {
        for (size_t f = 0; f + 2 < indices.size(); f += 3)
            for (int k = 0; k < 3; ++k) {
                const uint32_t a = indices[f + k], b = indices[f + (k + 1) % 3];
                const float rest = glm::length(bind[a] - bind[b]);
                if (rest <= 0.0f) continue;
                const float r = glm::length(now[a] - now[b]) / rest;
                ++edges;
                outside += r < 0.5f || r > 2.0f;
                if (r < lo) lo = r, lo_at = 0.5f * (bind[a] + bind[b]);
                if (r > hi) hi = r, hi_at = 0.5f * (bind[a] + bind[b]);
            }
    }
};

// Walks `g` through `keys` keys of `clip` (every `step`-th, at 30 Hz) at every level of `levels` and
// returns the edge stretch range of every level's displayed surface against its rest surface.
std::vector<StretchRange> walk_stretch(const CharacterGeometry& g, const RawAnimation& clip, std::span<const GeomLod> levels,
                                       size_t keys, size_t step) {
    GeometryController ctl(g, levels, static_cast<uint32_t>(levels.size()));
    std::vector<std::vector<glm::vec3>> bind(levels.size());
    const PoseSource rest{g.rest_model().data(), 0};
    for (uint32_t l = 0; l < levels.size(); ++l) {
        ctl.begin_level(l, static_cast<uint8_t>(l), -1, 0);
        ctl.reference_surface(rest, l, static_cast<uint8_t>(l), bind[l]);
    }
    std::vector<StretchRange> range(levels.size());
    for (size_t key = 0; key < keys; key += step) {
        const auto pose = test::clip_pose(g.skeleton(), clip, key);
        for (uint32_t l = 0; l < levels.size(); ++l) {
            ctl.update(static_cast<uint8_t>(l), std::span(&l, 1), PoseSource{pose.data(), 0}, static_cast<float>(step) / 30.0f);
            const SurfaceView view = ctl.surface(l);
            range[l].add(ctl.level_indices(static_cast<uint8_t>(l)), bind[l], view.positions);
        }
    }
    return range;
}

TEST(ContinuousSkin, HumanoidSkinIsOneClosedSurfaceAtEveryMeshLevel) {
    const auto& h = test::humanoid();
    ASSERT_NE(h.geometry, nullptr);
    const CharacterGeometry& g = *h.geometry;
    const auto levels = default_mesh_levels();
    GeometryController ctl(g, levels, 1);
    uint32_t previous = 0;
    for (uint8_t l = 0; l < levels.size(); ++l) {
        SCOPED_TRACE(static_cast<int>(l));
        const uint32_t n = ctl.vertices_per_character(l);
        const SurfaceTopology t = analyse_surface(ctl.level_indices(l), n);
        if (t.components != 1) {  // where the components are (diagnostic)
            const SkinLayer& sk = g.skin_layer(levels[l].theta_steps, levels[l].phi_steps);
            std::vector<uint32_t> parent(sk.rest_positions.size());
            for (uint32_t i = 0; i < parent.size(); ++i) parent[i] = i;
            auto root = [&](uint32_t v) {
                while (parent[v] != v) v = parent[v] = parent[parent[v]];
                return v;
            };
            for (size_t f = 0; f < sk.indices.size(); f += 3)
                for (int k = 0; k < 2; ++k) parent[root(sk.indices[f + k])] = root(sk.indices[f + k + 1]);
            std::map<uint32_t, std::pair<size_t, glm::vec3>> parts;
            for (uint32_t i = 0; i < parent.size(); ++i) {
                auto& e = parts[root(i)];
                ++e.first;
                e.second += sk.rest_positions[i];
            }
            for (const auto& [r, e] : parts)
                std::cout << "component of " << e.first << " vertices around " << e.second.x / e.first << " " << e.second.y / e.first << " "
                          << e.second.z / e.first << "\n";
        }
        EXPECT_TRUE(t.closed_connected()) << "components " << t.components << ", boundary edges " << t.boundary_edges
                                          << ", non-manifold edges " << t.non_manifold_edges << ", degenerate " << t.degenerate_triangles;
        // One tessellation parameter sets the resolution: M * V(T, P) triangles are asked of the
        // simplifier (it may stop a little above at the coarsest level), so the control surface
        // shrinks with (T, P).
        const SkinLayer& skin = g.skin_layer(levels[l].theta_steps, levels[l].phi_steps);
        const size_t asked = size_t{g.muscle_count()} * grid_vertex_count(levels[l].theta_steps, levels[l].phi_steps);
        EXPECT_LE(skin.indices.size() / 3, asked + asked / 4);
        EXPECT_GE(skin.indices.size() / 3, asked * 3 / 4);
        if (l > 0) {
            EXPECT_LT(skin.rest_positions.size(), previous);
        }
        previous = static_cast<uint32_t>(skin.rest_positions.size());
    }
}

TEST(ContinuousSkin, HumanoidWalkNeitherTearsNorCollapsesEdges) {
    const auto& h = test::humanoid();
    ASSERT_NE(h.geometry, nullptr);
    const auto levels = default_mesh_levels();
    const auto range = walk_stretch(*h.geometry, h.clip, levels, 90, 3);
    for (size_t l = 0; l < levels.size(); ++l) {
        SCOPED_TRACE(l);
        const StretchRange& r = range[l];
        std::cout << "level " << l << ": edge length / bind length in [" << r.lo << ", " << r.hi << "], " << r.outside << " of "
                  << r.edges << " outside [0.5, 2]; extremes at (" << r.lo_at.x << " " << r.lo_at.y << " " << r.lo_at.z << ") and ("
                  << r.hi_at.x << " " << r.hi_at.y << " " << r.hi_at.z << ")\n";
        // Issue 14's tear / collapse bound: every edge within [0.5, 2] x its bind length. The skin is
        // strain limited (strain_limit.hpp: projected into [0.55, 1.8], 8 passes on the control
        // surface, 16 on the refined one); before it, with the binding weights smoothed over the skin
        // graph, the walk gave level 0 [0.11, 3.95], 1 [0.20, 3.04], 2 [0.30, 2.29], 3 [0.20, 2.37]
        // (creases where an arm's inner side meets the torso, and at the gluteal fold).
        EXPECT_GE(r.lo, 0.5f);
        EXPECT_LE(r.hi, 2.0f);
        EXPECT_EQ(r.outside, 0u);
    }
}

TEST(ContinuousSkin, CesiumManWalkNeitherTearsNorCollapsesEdges) {
    ALOHA_REQUIRE_TEST_ASSET(path, "CesiumMan.glb");
    const test::Cesium& cesium = test::load_cesium(path);
    ASSERT_NE(cesium.geometry, nullptr) << cesium.error;
    const auto levels = default_mesh_levels();
    size_t keys = 0;
    for (const auto& track : cesium.clip.tracks) keys = std::max(keys, track.rotations.values.size());
    const auto range = walk_stretch(*cesium.geometry, cesium.clip, levels, keys, 2);
    for (size_t l = 0; l < levels.size(); ++l) {
        SCOPED_TRACE(l);
        const StretchRange& r = range[l];
        std::cout << "CesiumMan level " << l << ": edge length / bind length in [" << r.lo << ", " << r.hi << "], " << r.outside
                  << " of " << r.edges << " outside [0.5, 2]\n";
        // Issue 14's bound [0.5, 2] on an authored mesh too. Before strain limiting, CesiumMan's own
        // linear-blend skinning (level 3, its authored weights) gave [0.025, 6.1] on its walk (sharp
        // authored transitions at the knees and shoulders) and the muscle-driven levels 0-2 [0.059,
        // 2.16], [0.034, 2.28], [0.021, 2.19] (collapses at the knees' back and the hip front); the
        // mesh's seams (one point, several texture coordinates) are welded so limiting keeps them shut.
        EXPECT_GE(r.lo, 0.5f);
        EXPECT_LE(r.hi, 2.0f);
        EXPECT_EQ(r.outside, 0u);
    }
}

}  // namespace
}  // namespace aloha
