// Geomorphing between levels, the generated peeled mesh, and the fidelity reference.
#include "systems/geometry/spring_skin/grid_sample.hpp"
#include "systems/geometry/surface_grid.hpp"
#include "tests/systems/geometry/controller/test_humanoid.hpp"

#include <gtest/gtest.h>

#include <cstdio>

#include <iostream>

namespace aloha {
namespace {

using test::humanoid;

// Positions are at most ~2 m from the origin; a vertex goes through a few float operations per
// job (tessellation, spring step, morph), each rounding by <= 2^-24 * 2 m ~ 1.2e-7 m, so 2e-5 m
// bounds the accumulated rounding with a wide margin while staying far below the millimetre moves
// being measured.
constexpr float kRound = 2e-5f;

// The displayed surface of a level: its skin at (T, P), refined when the level is Subdivided.
SkinSurfaceKey display_key(const GeomLod& l) {
    return {l.theta_steps, l.phi_steps, l.method == GeomMethod::Subdivided ? uint32_t{l.subdiv_level} : 0u};
}

// The old displayed skin read at the new level's displayed vertices: vertex by vertex for the same
// surface, through the rest-pose correspondence between the two surfaces otherwise.
std::vector<glm::vec3> sample_at(const CharacterGeometry& g, std::span<const glm::vec3> old, const GeomLod& a, const GeomLod& b) {
    if (display_key(a) == display_key(b)) return {old.begin(), old.end()};
    const SurfaceMap& map = g.surface_map(display_key(a), display_key(b));
    std::vector<glm::vec3> out(map.corners.size());
    map.apply(old, out);
    return out;
}

std::vector<glm::vec3> copy(std::span<const glm::vec3> s) { return {s.begin(), s.end()}; }

// Character 0 switches with N morph frames, character 1 (same poses, same springs) with none, so
// character 1 shows the new level's own surface new_k. Per vertex i, with delta_i = old_i - new_1:
//   at the switch   |shown_1 - old_i| = |delta_i| / N                  (first morphed frame)
//   later frames    |shown_k - shown_{k-1}| <= |new_k - new_{k-1}| + |delta_i| / N   (triangle ineq.)
// while the unmorphed character jumps by |delta_i| at once.
void check_switch(GeometryController& ctl, uint8_t from, uint8_t to, uint16_t N, size_t& key) {
    const CharacterGeometry& g = ctl.geometry();
    const auto old_surface = sample_at(g, ctl.surface(0).positions, ctl.level(from), ctl.level(to));
    ctl.begin_level(0, to, static_cast<int8_t>(from), N);
    ctl.begin_level(1, to, static_cast<int8_t>(from), 0);
    EXPECT_EQ(ctl.geomorph_frames_left(0), N);
    const uint32_t both[2] = {0, 1};
    std::vector<glm::vec3> prev_morph, prev_new, delta;
    float largest_morph_step = 0.0f, largest_jump = 0.0f;
    for (uint16_t k = 1; k <= N + 1; ++k) {
        const auto pose = test::clip_pose(g.skeleton(), humanoid().clip, key++);
        ctl.update(to, both, PoseSource{pose.data(), 0}, 1.0f / 30.0f);
        const auto morph = copy(ctl.surface(0).positions), fresh = copy(ctl.surface(1).positions);
        ASSERT_EQ(morph.size(), old_surface.size());
        if (k == 1) {
            delta.resize(morph.size());
            for (size_t i = 0; i < morph.size(); ++i) {
                delta[i] = old_surface[i] - fresh[i];
                const float step = glm::length(morph[i] - old_surface[i]);
                ASSERT_NEAR(step, glm::length(delta[i]) / N, kRound) << i;
                largest_morph_step = std::max(largest_morph_step, step);
                largest_jump = std::max(largest_jump, glm::length(delta[i]));
            }
        } else {
            for (size_t i = 0; i < morph.size(); ++i) {
                const float step = glm::length(morph[i] - prev_morph[i]);
                ASSERT_LE(step, glm::length(fresh[i] - prev_new[i]) + glm::length(delta[i]) / N + kRound) << i;
            }
        }
        prev_morph = morph;
        prev_new = fresh;
    }
    // The morph has ended: both characters show the same surface.
    EXPECT_EQ(ctl.geomorph_frames_left(0), 0);
    EXPECT_LE(test::max_distance(prev_morph, prev_new), kRound);
    // The switch itself is a visible jump (millimetres) that the morph divides by N.
    EXPECT_GT(largest_jump, 1e-3f);
    EXPECT_LE(largest_morph_step, largest_jump / N + kRound);
}

TEST(GeometryControllerMorph, SwitchesMoveEachVertexByAtMostTheJumpOverN) {
    ASSERT_NE(humanoid().geometry, nullptr);
    const CharacterGeometry& g = *humanoid().geometry;
    GeometryController ctl(g, test::test_levels(), 2);
    ctl.begin_level(0, 1, -1, 0);
    ctl.begin_level(1, 1, -1, 0);
    const uint32_t both[2] = {0, 1};
    size_t key = 200;
    for (int f = 0; f < 5; ++f) {  // walk at Layered(16, 12) first so the springs carry motion
        const auto pose = test::clip_pose(g.skeleton(), humanoid().clip, key++);
        ctl.update(1, both, PoseSource{pose.data(), 0}, 1.0f / 30.0f);
    }
    constexpr uint16_t N = 8;
    // Level names of test_levels(); the last four switches go into and out of the subdivided level,
    // whose morph runs on the refined (displayed) surface.
    const char* names[] = {"Subdivided(8,6,1)", "Layered(16,12)", "Layered(8,6)", "SkinnedMesh(8,6)"};
    const std::pair<uint8_t, uint8_t> switches[] = {{1, 2}, {2, 3}, {3, 1}, {1, 0}, {0, 2}, {2, 0}, {0, 3}};
    for (const auto& [from, to] : switches) {
        SCOPED_TRACE(std::string(names[from]) + " -> " + names[to]);
        check_switch(ctl, from, to, N, key);
    }
}

// Two linear-blend levels over the same vertices (the second with a simplified triangle list, as the default rules'
// skinned, skinned_fine and skinned_light) place them alike for a pose: a switch between them shows the entered
// level's own surface at once, at the pose of the frame, with no geomorph replaying the motion since the left
// level was last shown.
TEST(GeometryControllerMorph, SkinnedLevelsOverTheSameVerticesSwitchWithoutAMorph) {
    ASSERT_NE(humanoid().geometry, nullptr);
    const CharacterGeometry& g = *humanoid().geometry;
    std::vector<GeomLod> levels = test::test_levels();
    GeomLod simplified = levels[3];  // SkinnedMesh(8, 6)
    simplified.simplify_error = 0.012f;
    simplified.level = static_cast<uint8_t>(levels.size());
    levels.push_back(simplified);
    const uint8_t skinned = 3, light = simplified.level;
    GeometryController ctl(g, levels, 2);
    for (const uint32_t c : {0u, 1u}) ctl.begin_level(c, skinned, -1, 0);
    const uint32_t both[2] = {0, 1}, switching[1] = {0}, witness[1] = {1};
    auto pose = test::clip_pose(g.skeleton(), humanoid().clip, 600);
    ctl.update(skinned, both, PoseSource{pose.data(), 0}, 1.0f / 60.0f);
    const auto shown_before = copy(ctl.surface(0).positions);
    for (const auto& [from, to] : {std::pair{skinned, light}, std::pair{light, skinned}}) {
        ctl.begin_level(0, to, static_cast<int8_t>(from), 8);
        EXPECT_EQ(ctl.geomorph_frames_left(0), 0);
        pose = test::clip_pose(g.skeleton(), humanoid().clip, 604);  // four frames on
        ctl.update(to, switching, PoseSource{pose.data(), 0}, 1.0f / 60.0f);
        ctl.update(skinned, witness, PoseSource{pose.data(), 0}, 1.0f / 60.0f);
        EXPECT_EQ(copy(ctl.surface(0).positions), copy(ctl.surface(1).positions));  // the same skin of the same pose
    }
    EXPECT_GT(test::max_distance(shown_before, ctl.surface(1).positions), 0.01f);  // a morph would have replayed centimetres
}

// Distance of every point of `points` to the triangle surface (positions, indices): map_surface's
// closest point (exact: triangle_grid_test.cpp holds it to a search over every triangle).
std::vector<float> distance_to_surface(std::span<const glm::vec3> positions, std::span<const uint32_t> indices,
                                       std::span<const glm::vec3> points) {
    const SurfaceMap map = map_surface(positions, indices, points);
    std::vector<glm::vec3> closest(points.size());
    map.apply(positions, closest);
    std::vector<float> d(points.size());
    for (size_t i = 0; i < points.size(); ++i) d[i] = glm::length(points[i] - closest[i]);
    return d;
}

// A switch into or out of the subdivided level changes the displayed surface continuously: the pose
// held, the first morphed frame shown_1 = fresh + (N - 1) / N (o - fresh) with o on the old displayed
// surface, so its distance to that surface is at most |o - fresh| / N = |shown_1 - fresh| / (N - 1),
// measured here against the old deformed surface itself (not through the controller's rest-pose
// correspondence). Morphing the control surface before refinement would leave the first frame off
// the old surface by Catmull-Clark's shrinkage of the control hull (millimetres, not divided by N).
TEST(GeometryControllerMorph, SwitchesIntoAndOutOfSubdividedStartOnTheShownSurface) {
    ASSERT_NE(humanoid().geometry, nullptr);
    const CharacterGeometry& g = *humanoid().geometry;
    constexpr uint16_t N = 8;
    const std::pair<uint8_t, uint8_t> switches[] = {{1, 0}, {0, 1}, {2, 0}, {0, 2}, {3, 0}, {0, 3}};
    for (const auto& [from, to] : switches) {
        SCOPED_TRACE(std::to_string(from) + " -> " + std::to_string(to));
        GeometryController ctl(g, test::test_levels(), 2);
        const uint32_t both[2] = {0, 1};
        ctl.begin_level(0, from, -1, 0);
        ctl.begin_level(1, from, -1, 0);
        std::vector<glm::mat4> pose;
        for (size_t key = 120; key < 126; ++key) {  // walk so the springs carry motion
            pose = test::clip_pose(g.skeleton(), humanoid().clip, key);
            ctl.update(from, both, PoseSource{pose.data(), 0}, 1.0f / 30.0f);
        }
        const auto old_surface = copy(ctl.surface(0).positions);
        const std::span<const uint32_t> old_indices = ctl.level_indices(from);
        ctl.begin_level(0, to, static_cast<int8_t>(from), N);
        ctl.begin_level(1, to, static_cast<int8_t>(from), 0);
        ctl.update(to, both, PoseSource{pose.data(), 0}, 1.0f / 30.0f);  // the same pose
        const auto shown = copy(ctl.surface(0).positions), fresh = copy(ctl.surface(1).positions);
        ASSERT_EQ(shown.size(), ctl.vertices_per_character(to));
        const std::vector<float> off = distance_to_surface(old_surface, old_indices, shown);
        const std::vector<float> jump = distance_to_surface(old_surface, old_indices, fresh);
        float largest_off = 0.0f, largest_jump = 0.0f;
        for (size_t i = 0; i < shown.size(); ++i) {
            ASSERT_LE(off[i], glm::length(shown[i] - fresh[i]) / (N - 1) + kRound) << i;
            largest_off = std::max(largest_off, off[i]);
            largest_jump = std::max(largest_jump, jump[i]);
        }
        // Without the morph the surface would jump visibly (millimetres off what was shown).
        EXPECT_GT(largest_jump, 1e-3f);
        std::cout << "largest jump " << largest_jump * 1000 << " mm, first morphed frame off the old surface by at most "
                  << largest_off * 1000 << " mm\n";
    }
}

TEST(GeometryControllerMorph, GeneratedSkinnedMeshMatchesLayeredAtRest) {
    ASSERT_NE(humanoid().geometry, nullptr);
    const CharacterGeometry& g = *humanoid().geometry;
    GeometryController ctl(g, test::test_levels(), 2);
    ctl.begin_level(0, 3, -1, 0);  // SkinnedMesh(8, 6), generated
    ctl.begin_level(1, 2, -1, 0);  // Layered(8, 6)
    const PoseSource rest{g.rest_model().data(), 0};
    for (int f = 0; f < 3; ++f) {
        const uint32_t c0 = 0, c1 = 1;
        ctl.update(3, std::span(&c0, 1), rest, 1.0f / 30.0f);
        ctl.update(2, std::span(&c1, 1), rest, 1.0f / 30.0f);
    }
    const SurfaceView peeled = ctl.surface(0), layered = ctl.surface(1);
    ASSERT_EQ(peeled.positions.size(), layered.positions.size());
    // The peeled skin at the rest pose is the skin layer's rest surface (the rest palette is the
    // identity up to rounding).
    const SkinLayer& layer = g.skin_layer(8, 6);
    ASSERT_EQ(peeled.positions.size(), layer.rest_positions.size());
    EXPECT_LE(test::max_distance(peeled.positions, layer.rest_positions), kRound);
    // Springs at rest put the layered skin at the same place (the blended rest ends equal the bound
    // vertices at the bind pose), to rounding; normals are the same area-weighted normals.
    EXPECT_LE(test::max_distance(peeled.positions, layered.positions), kRound);
    EXPECT_LE(test::max_distance(peeled.normals, layered.normals), 1e-4f);  // unit vectors, rounding of
                                                                            // cross products of ~1 cm edges
}

TEST(GeometryControllerMorph, ReferenceSurfaceAndDeviationPairs) {
    ASSERT_NE(humanoid().geometry, nullptr);
    const CharacterGeometry& g = *humanoid().geometry;
    GeometryController ctl(g, test::test_levels(), 2);
    ctl.begin_level(0, 2, -1, 0);  // Layered(8, 6)
    ctl.begin_level(1, 1, -1, 0);  // Layered(16, 12)
    const auto pose = test::clip_pose(g.skeleton(), humanoid().clip, 300);
    const PoseSource src{pose.data(), 0};
    const uint32_t c0 = 0, c1 = 1;
    ctl.update(2, std::span(&c0, 1), src, 1.0f / 30.0f);  // first frame: springs start at rest
    ctl.update(1, std::span(&c1, 1), src, 1.0f / 30.0f);
    const auto shown = copy(ctl.surface(0).positions);

    // The reference at level 1 equals what a character at level 1 shows with springs at rest.
    std::vector<glm::vec3> reference;
    ctl.reference_surface(src, 0, 1, reference);
    ASSERT_EQ(reference.size(), ctl.vertices_per_character(1));
    EXPECT_LE(test::max_distance(reference, ctl.surface(1).positions), kRound);
    EXPECT_EQ(test::max_distance(shown, ctl.surface(0).positions), 0.0f) << "reference_surface touched state";

    // The (8, 6) and (16, 12) skins are two resolutions of one body surface: each (8, 6) vertex is
    // paired with the (16, 12) reference read at its rest-pose closest point. The pairs differ by the
    // two meshes' chordal gaps and their bindings' differences, far below the body's size.
    std::vector<glm::vec3> current, ref;
    ctl.deviation_pairs(src, 0, 1, current, ref);
    ASSERT_EQ(current.size(), shown.size());
    ASSERT_EQ(ref.size(), current.size());
    double resolution_sum = 0.0;
    for (size_t i = 0; i < current.size(); ++i) resolution_sum += glm::length(current[i] - ref[i]);
    std::printf("[figure] (8, 6) against (16, 12): mean %.2f mm, largest %.1f mm\n", 1000.0 * resolution_sum / static_cast<double>(current.size()),
                static_cast<double>(1000.0f * test::max_distance(current, ref)));
    // Measured at this pose: mean 1.54 mm, max 15.0 mm with the 54-muscle layout (15.3 with 53; 1.40 / 11.9 mm before the trunk's hollows were filled: a
    // vertex in a filled hollow lies farther from the muscles it is bound to, and the two resolutions' bindings
    // differ more there). Regression bounds 2 mm / 2 cm.
    EXPECT_LT(resolution_sum / static_cast<double>(current.size()), 0.002);
    EXPECT_LT(test::max_distance(current, ref), 0.02f);
    // Against the peeled level the pairs differ by what linear blending cannot follow (the muscle
    // cross-section turning and bulging): first-order motion along the axis is matched by the
    // generated weights, so the error is second order. Measured at this pose with the continuous
    // skin: mean 6.2 mm, max 3.5 cm (the per-muscle grid skin gave 1.4 / 5.6 cm); regression bounds
    // 2 cm / 8 cm.
    ctl.deviation_pairs(src, 0, 3, current, ref);
    ASSERT_EQ(ref.size(), current.size());
    double sum = 0.0;
    for (size_t i = 0; i < current.size(); ++i) sum += glm::length(current[i] - ref[i]);
    const float peeled_max = test::max_distance(current, ref);
    EXPECT_GT(peeled_max, 1e-3f);
    EXPECT_LT(peeled_max, 0.08f);
    EXPECT_LT(sum / static_cast<double>(current.size()), 0.02);
    // No pairs at a level without a mesh.
    ctl.deviation_pairs(src, 0, 4, current, ref);
    EXPECT_TRUE(current.empty());
    EXPECT_TRUE(ref.empty());
}

// The at-rest side of deviation_pairs: a character walking at the reference level itself has its fat
// springs displaced by the motion, so its displayed surface differs from the reference (springs at
// rest); with its own springs put at rest too the difference is gone. That split is what the fidelity
// report's rest deviation reads: the level's geometric error without the springs' own motion.
TEST(GeometryControllerMorph, DeviationAtRestLeavesOutTheSpringsOwnMotion) {
    const CharacterGeometry& g = *humanoid().geometry;
    GeometryController ctl(g, test::test_levels(), 1);
    ctl.begin_level(0, 1, -1, 0);  // Layered(16, 12), the reference level below
    const uint32_t c0 = 0;
    std::vector<glm::mat4> pose;
    for (int frame = 300; frame <= 330; frame += 2) {  // a second of walking: the springs lag the body
        pose = test::clip_pose(g.skeleton(), humanoid().clip, frame);
        ctl.update(1, std::span(&c0, 1), PoseSource{pose.data(), 0}, 1.0f / 30.0f);
    }
    const PoseSource src{pose.data(), 0};
    std::vector<glm::vec3> current, ref, rest;
    ctl.deviation_pairs(src, 0, 1, current, ref, &rest);
    ASSERT_EQ(rest.size(), current.size());
    ASSERT_EQ(ref.size(), current.size());
    EXPECT_GT(test::max_distance(current, ref), 1e-4f) << "the springs did not move: the test shows nothing";
    EXPECT_LE(test::max_distance(rest, ref), kRound);
    // Without the at-rest output the pairs are the same.
    std::vector<glm::vec3> current2, ref2;
    ctl.deviation_pairs(src, 0, 1, current2, ref2);
    EXPECT_EQ(test::max_distance(current2, current), 0.0f);
    EXPECT_EQ(test::max_distance(ref2, ref), 0.0f);
}

}  // namespace
}  // namespace aloha
