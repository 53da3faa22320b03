// OcclusionJob: a character straight behind a wider one is hidden, one beside it is not, a partly
// covered one gets a fraction (the estimate, from body shapes); nobody hides themselves; a rolled camera
// estimates nothing (the estimate itself: occlusion_estimate_test.cpp). On a dense crowd with the default
// cores, every character marked fully occluded is checked independently: rays
// from the eye to points all over its bounds box must each hit a nearer character's core cylinder. Pass 2
// in chunks (as the host runs it) gives what one run gives.

#include "tests/systems/lod/occlusion_test_util.hpp"

#include <glm/gtc/constants.hpp>

#include <iostream>

namespace aloha {
namespace {

using occlusion_test::level_camera;
using occlusion_test::ray_hits_cylinder;
using occlusion_test::Scene;
using occlusion_test::solid_cores;


TEST(Occlusion, BehindHiddenBesideVisiblePartlyBetween) {
    Scene s;
    // The occluder's core: 1 m radius at 5 m, so it covers +-0.2 rad (inner rectangle, at its far depth).
    s.add({0, -1, 5}, 4.0f, 0.4f);   // 0: a tall, wide occluder 5 m from the eye
    s.add({0, 0, -10});              // 1: straight behind it, 20 m from the eye (+-0.02 rad)
    s.add({8, 0, -10});              // 2: off to the side (0.38-0.42 rad), nothing in front
    s.add({4, 0, -10});              // 3: across the occluder's edge (0.18-0.22 rad)
    const size_t full = s.run(level_camera(), solid_cores());
    EXPECT_EQ(full, 1u);
    EXPECT_EQ(s.a[0].occluded, 0.0f);  // its own core is behind its nearest point
    EXPECT_EQ(s.a[1].occluded, 1.0f);
    EXPECT_EQ(s.a[2].occluded, 0.0f);
    EXPECT_GT(s.a[3].occluded, 0.0f);
    EXPECT_LT(s.a[3].occluded, 1.0f);
}

TEST(Occlusion, BecomingHiddenNeedsAMarginStayingHiddenDoesNot) {
    // Pixels per metre at depth z: fx / z with fx = 360 / tan(30 deg) = 623.5 (60 degree lens, 720 px
    // high). The occluder's core (1 m radius, 5 m away) covers up to 124.7 px right of the centre; a
    // character at x = 3.4 m, 20 m away, reaches (3.4 + 0.4) m / 19.6 m * 623.5 = 120.9 px: inside, but
    // not with the 8 px margin of a drawn character.
    Scene s;
    s.add({0, -1, 5}, 4.0f, 0.4f);
    s.add({3.4f, 0, -10});
    s.g.resize(2);
    s.g[1].method = GeomMethod::RigidProxy;  // drawn now: needs the margin to become hidden
    s.run(level_camera(), solid_cores());
    EXPECT_GT(s.a[1].occluded, 0.5f);
    EXPECT_LT(s.a[1].occluded, 1.0f);
    s.g[1].method = GeomMethod::Hidden;  // hidden now: stays hidden while its own bounds are covered
    s.run(level_camera(), solid_cores());
    EXPECT_EQ(s.a[1].occluded, 1.0f);
}

TEST(Occlusion, NotVisibleAndRolledCamerasGetNothing) {
    Scene s;
    s.add({0, -1, 5}, 4.0f, 0.4f);
    s.add({0, 0, -10});
    s.a[1].visible = 0;  // outside the frustum: not tested, and not drawn as an occluder either
    s.run(level_camera(), solid_cores());
    EXPECT_EQ(s.a[1].occluded, 0.0f);
    s.a[1].visible = 1;
    s.a[0].visible = 0;  // the occluder is off screen: it hides nothing
    s.run(level_camera(), solid_cores());
    EXPECT_EQ(s.a[1].occluded, 0.0f);
    s.a[0].visible = 1;
    LodCamera rolled = level_camera();
    rolled.view = glm::rotate(glm::mat4(1.0f), 0.3f, glm::vec3(0, 0, 1)) * rolled.view;
    EXPECT_EQ(s.run(rolled, solid_cores()), 0u);
    EXPECT_EQ(s.a[1].occluded, 0.0f);
}


TEST(Occlusion, OneVisibleCharacterHidesNobodyAndNeedsNoGrid) {
    Scene s;
    s.add({0, -1, 5}, 4.0f, 0.4f);  // would hide character 1 were it visible
    s.add({0, 0, -10});
    s.a[0].visible = 0;
    s.a[1].occluded = 0.7f;  // last frame's
    EXPECT_EQ(s.run(level_camera(), solid_cores()), 0u);
    EXPECT_EQ(s.a[0].occluded, 0.0f);
    EXPECT_EQ(s.a[1].occluded, 0.0f);
    EXPECT_EQ(s.grid.width, 0) << "the grid was never filled";
    // With both visible the passes run as before: the same answer as filling the grid.
    s.a[0].visible = 1;
    EXPECT_EQ(s.run(level_camera(), solid_cores()), 1u);
    EXPECT_GT(s.grid.width, 0);
    EXPECT_EQ(s.a[1].occluded, 1.0f);
}

TEST(Occlusion, EveryFullyOccludedCharacterIsReallyHiddenByCores) {
    // A dense crowd, 30 wide and 60 deep, 0.7 m apart with +-0.15 m jitter, heights 1.55-1.95 m, seen
    // from eye height at its front edge (a spectator's view).
    Scene s;
    uint32_t seed = 11u;
    auto rnd = [&] {
        seed = seed * 1664525u + 1013904223u;
        return static_cast<float>(seed >> 8) / 16777216.0f;
    };
    for (int z = 0; z < 60; ++z)
        for (int x = 0; x < 30; ++x)
            s.add({0.7f * (x - 15) + 0.3f * (rnd() - 0.5f), 0.0f, -0.7f * z + 0.3f * (rnd() - 0.5f)}, 1.55f + 0.4f * rnd(), 0.2f);
    const glm::vec3 eye(0, 1.7f, 4);
    const LodCamera cam = make_lod_camera(eye, {0, 1.2f, -20}, glm::radians(50.0f), {1280, 720}, 0.1f, 500.0f);
    OcclusionParams p;
    p.enter_margin_px = 0.0f;  // the estimate itself, without the hysteresis margin
    const size_t full = s.run(cam, p);
    EXPECT_GT(full, 90u);  // not a do-nothing estimate (134 of 1,800 when written): a dense crowd hides part of itself
    EXPECT_LT(full, s.t.size());
    size_t checked = 0;
    for (size_t i = 0; i < s.t.size(); ++i) {
        if (s.a[i].occluded < 1.0f) continue;
        const glm::vec3 f = s.t[i].position;
        const float h = s.b[i].height, r = s.b[i].radius;
        // Points over the whole bounds box: a 5 x 5 x 5 lattice (surface and inside).
        for (int u = 0; u <= 4; ++u)
            for (int v = 0; v <= 4; ++v)
                for (int w = 0; w <= 4; ++w) {
                    const glm::vec3 q = f + glm::vec3(-r + 2 * r * u / 4.0f, h * v / 4.0f, -r + 2 * r * w / 4.0f);
                    bool hit = false;
                    for (size_t k = 0; k < s.t.size() && !hit; ++k) {
                        if (k == i || glm::length(s.t[k].position - eye) > glm::length(q - eye) + 2.5f) continue;
                        const glm::vec3 base = s.t[k].position;
                        const float hk = s.b[k].height;
                        hit = ray_hits_cylinder(eye, q, base, p.torso_y0 * hk, p.torso_y1 * hk, p.torso_radius * hk) ||
                              ray_hits_cylinder(eye, q, base, p.neck_y0 * hk, p.neck_y1 * hk, p.neck_radius * hk) ||
                              ray_hits_cylinder(eye, q, base, p.head_y0 * hk, p.head_y1 * hk, p.head_radius * hk);
                    }
                    ASSERT_TRUE(hit) << "character " << i << " point " << u << "," << v << "," << w;
                }
        ++checked;
    }
    EXPECT_EQ(checked, full);
    // The front row is never hidden.
    for (size_t x = 0; x < 30; ++x) EXPECT_LT(s.a[x].occluded, 1.0f) << x;
}

// The host runs pass 2 in chunks, concurrently: Rasterise() then Test() over any split of the crowd gives
// exactly what Run() gives.
TEST(Occlusion, PassTwoInChunksEqualsOneRun) {
    Scene s;
    for (int z = 0; z < 40; ++z)
        for (int x = 0; x < 30; ++x) s.add({0.5f * (x - 15) + 0.1f * (z % 3), 0.0f, -0.5f * z}, 1.55f + 0.013f * ((x * 7 + z) % 31), 0.2f);
    const LodCamera cam = make_lod_camera({0, 1.7f, 4}, {0, 1.2f, -20}, glm::radians(50.0f), {1280, 720}, 0.1f, 500.0f);
    OcclusionParams p;
    p.enter_margin_px = 0.0f;
    const size_t full = s.run(cam, p);
    ASSERT_GT(full, 0u);  // a dense crowd hides part of itself
    const std::vector<LodAttributes> whole = s.a;
    OcclusionJob job{s.t, s.b, s.g, cam, p, &s.grid, s.a};
    job.Rasterise();
    size_t chunked = 0;
    for (size_t b = 0; b < s.t.size(); b += 37) chunked += job.Test(b, std::min(s.t.size(), b + 37));
    EXPECT_EQ(chunked, full);
    for (size_t i = 0; i < s.t.size(); ++i) EXPECT_EQ(s.a[i].occluded, whole[i].occluded) << i;
}

// The host runs pass 1 in parts, one grid each, concurrently: any number of parts, merged, gives the
// grid of Rasterise() bit for bit (each cell the least of the same depths).
TEST(Occlusion, PassOneInPartsEqualsOneGrid) {
    Scene s;
    for (int z = 0; z < 40; ++z)
        for (int x = 0; x < 30; ++x) s.add({0.5f * (x - 15) + 0.1f * (z % 3), 0.0f, -0.5f * z}, 1.55f + 0.013f * ((x * 7 + z) % 31), 0.2f);
    const LodCamera cam = make_lod_camera({0, 1.7f, 4}, {0, 1.2f, -20}, glm::radians(50.0f), {1280, 720}, 0.1f, 500.0f);
    ASSERT_GT(s.run(cam, OcclusionParams{}), 0u);  // sets `visible`, and cores cover cells
    OcclusionJob job{s.t, s.b, s.g, cam, OcclusionParams{}, &s.grid, s.a};
    job.Rasterise();
    const std::vector<float> whole = s.grid.depth;
    ASSERT_TRUE(std::any_of(whole.begin(), whole.end(), [](float d) { return std::isfinite(d); }));
    for (const size_t parts : {size_t{2}, size_t{3}, size_t{7}, size_t{64}}) {
        job.PrepareParts(parts);
        for (size_t p = parts; p-- > 0;) job.RasterisePart(p, parts);  // any order
        job.MergeParts(parts);
        ASSERT_EQ(s.grid.depth.size(), whole.size());
        for (size_t i = 0; i < whole.size(); ++i) ASSERT_EQ(s.grid.depth[i], whole[i]) << parts << " parts, cell " << i;
    }
}

// Pass 2 answers "nothing covered" and "all covered" from the grid's block summary: the fractions must be
// those of counting every cell (a plain re-count from the grid here, with the rectangle found the same way),
// on a crowd that has near characters (big rectangles, many blocks), far ones (a few cells) and everything
// between, seen from several heights.
TEST(Occlusion, BlockSummaryGivesTheCellByCellAnswer) {
    Scene s;
    for (int z = 0; z < 80; ++z)
        for (int x = 0; x < 25; ++x)
            s.add({0.7f * (x - 12) + 0.2f * (z % 3), 0.0f, -5.0f - 0.055f * static_cast<float>(z * z) - 0.6f * z},
                  1.55f + 0.013f * ((x * 7 + z) % 31), 0.25f);
    size_t partial = 0, none = 0, all = 0;
    for (const float eye_y : {1.7f, 4.0f, 12.0f}) {
        SCOPED_TRACE(eye_y);
        const LodCamera cam = make_lod_camera({0, eye_y, 4}, {0, 1.0f, -30}, glm::radians(50.0f), {1280, 720}, 0.1f, 500.0f);
        OcclusionParams p;
        p.enter_margin_px = eye_y < 2.0f ? 0.0f : 3.0f;  // no margin at eye height: some are fully hidden
        (void)s.run(cam, p);
        const OcclusionGrid& g = s.grid;
        const glm::mat4 vp = cam.projection * cam.view;
        for (size_t i = 0; i < s.t.size(); ++i) {
            const float h = s.b[i].height, r = s.b[i].radius;
            glm::vec2 lo(1e30f), hi(-1e30f);
            float near_z = 1e30f;
            for (int k = 0; k < 8; ++k) {
                const glm::vec3 c = s.t[i].position + glm::vec3(k & 1 ? r : -r, k & 2 ? h : 0.0f, k & 4 ? r : -r);
                const glm::vec4 v = cam.view * glm::vec4(c, 1.0f);
                const glm::vec4 q = vp * glm::vec4(c, 1.0f);
                const glm::vec2 px((q.x / q.w + 1.0f) * 640.0f, (1.0f - q.y / q.w) * 360.0f);
                lo = glm::min(lo, px), hi = glm::max(hi, px), near_z = std::min(near_z, -v.z);
            }
            lo -= p.enter_margin_px, hi += p.enter_margin_px;
            const int cx0 = std::max(0, static_cast<int>(std::floor(lo.x / p.cell_px)));
            const int cx1 = std::min(g.width, static_cast<int>(std::ceil(hi.x / p.cell_px)));
            const int cy0 = std::max(0, static_cast<int>(std::floor(lo.y / p.cell_px)));
            const int cy1 = std::min(g.height, static_cast<int>(std::ceil(hi.y / p.cell_px)));
            if (cx0 >= cx1 || cy0 >= cy1) continue;
            size_t covered = 0, cells = 0;
            for (int y = cy0; y < cy1; ++y)
                for (int x = cx0; x < cx1; ++x) covered += g.depth[static_cast<size_t>(y) * g.width + x] < near_z, ++cells;
            // Where counting gives all, the job must say exactly 1; otherwise below 1 (the estimate).
            if (covered == 0) {
                EXPECT_LT(s.a[i].occluded, 1.0f) << i;
                ++none;
            } else if (covered == cells) {
                EXPECT_EQ(s.a[i].occluded, 1.0f) << i;
                ++all;
            } else {
                EXPECT_GT(s.a[i].occluded, 0.0f - 1e-6f) << i;
                EXPECT_LT(s.a[i].occluded, 1.0f) << i;
                ++partial;
            }
        }
    }
    EXPECT_GT(none, 0u);  // the views hold all three cases (else the check proves little)
    EXPECT_GT(all, 0u);
    EXPECT_GT(partial, 0u);
    std::cout << "cells none / all / partly covered: " << none << " / " << all << " / " << partial << "\n";
}

TEST(Occlusion, ValidateListsEveryProblem) {
    std::vector<Transform> t(2);
    std::vector<LodAttributes> a(1);
    OcclusionJob job;
    job.transforms = t;
    job.attributes = a;
    job.params.cell_px = 0.5f;
    job.params.head_y1 = job.params.head_y0;
    job.params.enter_margin_px = -1.0f;
    job.params.body_cell_px = 0.5f;
    job.params.body_legs.y1 = job.params.body_legs.y0;
    std::vector<GeomLod> g(3);
    job.geom = g;
    std::vector<std::string> errors;
    EXPECT_FALSE(job.Validate(&errors));
    // attribute size, geom size, no grid, cell_px, body_cell_px, margin, core shape, body shape
    EXPECT_EQ(errors.size(), 8u);
}

}  // namespace
}  // namespace aloha
