// Geomorphing: a tessellation switch moves no vertex more per frame than the derived bound.
#include "systems/geometry/spring_skin/geomorph.hpp"
#include "systems/geometry/spring_skin/grid_sample.hpp"
#include "tests/systems/geometry/spring_skin/test_grids.hpp"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <algorithm>

namespace aloha {
namespace {

// Two muscles of one character, sliding and turning slowly (the surface's own motion).
test::Grids muscles_at(uint32_t T, uint32_t P, int frame) {
    const float f = static_cast<float>(frame);
    test::Grids g;
    const glm::mat4 drift = glm::translate(glm::mat4(1.0f), glm::vec3(0.001f * f, 0.0f, 0.0f)) *
                            glm::rotate(glm::mat4(1.0f), 0.004f * f, glm::vec3(0, 0, 1));
    test::append_ellipsoid(g, T, P, {0.06f, 0.05f, 0.15f}, drift);
    test::append_ellipsoid(g, T, P, {0.05f, 0.05f, 0.12f}, drift * glm::translate(glm::mat4(1.0f), glm::vec3(0.2f, 0, 0)));
    return g;
}

TEST(Geomorph, SamplingAtGridVerticesReturnsTheVertices) {
    const test::Grids g = muscles_at(7, 5, 3);
    const std::span<const glm::vec3> first = std::span(g.positions).first(grid_vertex_count(7, 5));
    for (uint32_t i = 0; i < first.size(); ++i) {
        // Bilinear weights are exactly 0/1 at a vertex up to float rounding of theta/phi (~1e-6 rad
        // times radius 0.15 m).
        EXPECT_NEAR(glm::length(sample_grid(first, 7, 5, grid_vertex_param(7, 5, i)) - first[i]), 0.0f, 1e-5f) << i;
    }
}

// Runs a switch (5, 3) -> (20, 12) at frame `switch_frame` with N morph frames (N = 0: no morph) and
// returns the largest per-vertex move per frame after the switch, and the derived bound.
struct SwitchResult {
    float max_move = 0.0f;
    float bound = 0.0f;
};

SwitchResult run_switch(uint16_t frames) {
    const uint32_t To = 5, Po = 3, Tn = 20, Pn = 12;
    const int switch_frame = 3;
    const size_t vn = 2 * size_t{grid_vertex_count(Tn, Pn)};
    std::vector<glm::vec3> deltas(vn), shown(vn), previous(vn);
    const uint16_t total = std::max<uint16_t>(frames, 1);
    std::vector<uint16_t> frames_total{total}, frames_left{0};
    SwitchResult result;
    float max_delta = 0.0f, max_motion = 0.0f;
    test::Grids prev_new;
    for (int frame = switch_frame; frame < switch_frame + 15; ++frame) {
        const test::Grids now = muscles_at(Tn, Pn, frame);
        if (frame == switch_frame) {
            // The last displayed old surface (previous frame, old tessellation).
            const test::Grids old = muscles_at(To, Po, frame - 1);
            GeomorphBeginJob begin{To, Po, Tn, Pn, old.positions, now.positions, deltas};
            EXPECT_TRUE(begin.Validate());
            begin.Run();
            frames_left[0] = frames;
            // What the viewer saw last frame at each new vertex's (theta, phi): the old surface.
            for (size_t i = 0; i < vn; ++i) {
                previous[i] = now.positions[i] + deltas[i];
                max_delta = std::max(max_delta, glm::length(deltas[i]));
            }
        } else {
            for (size_t i = 0; i < vn; ++i) max_motion = std::max(max_motion, glm::length(now.positions[i] - prev_new.positions[i]));
        }
        GeomorphJob morph{static_cast<uint32_t>(vn), now.positions, deltas, frames_total, frames_left, shown};
        EXPECT_TRUE(morph.Validate());
        morph.Run();
        for (size_t i = 0; i < vn; ++i) result.max_move = std::max(result.max_move, glm::length(shown[i] - previous[i]));
        previous = shown;
        prev_new = now;
    }
    // Frame k shows new_k + (1 - k/N) delta: consecutive frames differ by (new_k - new_{k-1}) - delta/N
    // and the first differs from the old surface by delta/N, so every move is at most
    // max|delta| / N + max per-frame motion of the new surface.
    result.bound = max_delta / static_cast<float>(total) + max_motion;
    return result;
}

TEST(Geomorph, SwitchMovesEachVertexLessThanTheDerivedBound) {
    const uint16_t N = 8;
    const SwitchResult morphed = run_switch(N);
    // Tolerance: float rounding of positions ~0.3 m, relative 1e-5.
    EXPECT_LE(morphed.max_move, morphed.bound + 1e-5f);
    // Without geomorphing the same switch pops by the full old-to-new distance in one frame.
    const SwitchResult popped = run_switch(0);
    EXPECT_GT(popped.max_move, morphed.bound);
    EXPECT_GT(popped.max_move, 2.0f * morphed.max_move);
}

TEST(Geomorph, FinishedMorphShowsTheNewSurfaceExactly) {
    const test::Grids now = muscles_at(8, 6, 0);
    std::vector<glm::vec3> deltas(now.positions.size(), glm::vec3(0.1f)), shown(now.positions.size());
    std::vector<uint16_t> total{2}, left{2};
    GeomorphJob morph{static_cast<uint32_t>(now.positions.size()), now.positions, deltas, total, left, shown};
    morph.Run();
    EXPECT_EQ(left[0], 1);
    EXPECT_NEAR(glm::length(shown[0] - now.positions[0] - glm::vec3(0.05f)), 0.0f, 1e-6f);
    morph.Run();
    morph.Run();
    EXPECT_EQ(left[0], 0);
    for (size_t i = 0; i < shown.size(); ++i) EXPECT_EQ(shown[i], now.positions[i]);
}

TEST(Geomorph, ValidateListsEveryFailure) {
    std::vector<glm::vec3> a(10), b(20), d(5);
    GeomorphBeginJob begin{2, 4, 6, 4, a, b, d};
    std::vector<std::string> errors;
    EXPECT_FALSE(begin.Validate(&errors));
    EXPECT_EQ(errors.size(), 2u);  // old T < 3, deltas size
    std::vector<uint16_t> total{4}, left{5};
    GeomorphJob morph{20, b, d, total, left, d};
    errors.clear();
    EXPECT_FALSE(morph.Validate(&errors));
    EXPECT_EQ(errors.size(), 3u);  // deltas size, morphed size, frames_left > frames_total
}

}  // namespace
}  // namespace aloha
