// OcclusionJob's estimate (occluded below 1): a character behind a row of people is mostly covered, one in
// front of them or beside them is not, one half behind their edge about half; it never says 1; over a crowd
// it agrees with rays cast against the same shapes.
#include "tests/systems/lod/occlusion_test_util.hpp"

#include <iostream>

namespace aloha {
namespace {

using occlusion_test::ray_hits_cylinder;
using occlusion_test::Scene;

// The estimate with the default body shapes, at eye height 1.7 m looking level along -z. A row of 1.8 m
// people 5 m away, 0.4 m apart (their torso shapes, 0.396 m wide, touch; their heads and legs leave
// gaps), for x in [-2.8, 2.8]. Seen from 10 m, a 1.8 m character's legs (0-0.86 m) lie in the angles the
// row's torsos (0.86-1.48 m at 5 m) cover and its torso and head in those of the row's torsos and heads.
TEST(Occlusion, EstimateBehindARowBesideItAndHalfAtItsEdge) {
    Scene s;
    for (int k = -7; k <= 7; ++k) s.add({0.4f * static_cast<float>(k), 0.0f, 5.0f});
    const size_t row = s.t.size();
    s.add({0.0f, 0.0f, 0.0f});  // straight behind the row, 10 m from the eye
    s.add({0.2f, 0.0f, 7.0f});  // in front of the row: nothing nearer
    s.add({9.0f, 0.0f, 0.0f});  // beside the row's end (0.9 against the row's 0.64 of x per depth)
    // Half behind the row's end: its axis on the last torso's edge, (2.8 + 0.198) / 5 of x per depth.
    s.add({(2.8f + 0.198f) * 2.0f, 0.0f, 0.0f});
    const LodCamera cam = make_lod_camera({0, 1.7f, 10}, {0, 1.7f, 0}, glm::radians(60.0f), {1280, 720}, 0.1f, 500.0f);
    (void)s.run(cam);
    EXPECT_GE(s.a[row].occluded, 0.85f);
    EXPECT_LT(s.a[row].occluded, 1.0f);  // the cores leave gaps: not certainly hidden, so an estimate
    EXPECT_EQ(s.a[row + 1].occluded, 0.0f);
    EXPECT_EQ(s.a[row + 2].occluded, 0.0f);
    // About half of its legs' cells (~40% of its shapes' cells) and of the lower 63% of its torso's (~45%:
    // the rest of it lies in the angles of the row's heads, which do not reach it), none of its head's
    // (~15%). In whole 4 px cells (legs 4.2 cells wide, torso 6.2, counted outwards: 5-6 and 7-8 columns,
    // of which only those wholly left of the edge, 2 and 3, are covered): 2/6 * 0.40 + 3/8 * 0.63 * 0.45
    // = 0.24; 0.15-0.5 allows a column either way.
    EXPECT_GT(s.a[row + 3].occluded, 0.15f);
    EXPECT_LT(s.a[row + 3].occluded, 0.5f);
    std::cout << "behind / half at the edge: " << s.a[row].occluded << " / " << s.a[row + 3].occluded << "\n";
    // Nobody's own shapes count: a character alone gets 0.
    Scene alone;
    alone.add({0.0f, 0.0f, 0.0f});
    (void)alone.run(cam);
    EXPECT_EQ(alone.a[0].occluded, 0.0f);
}


// The estimate against the model it rasterises, ray cast: in a dense crowd seen from eye height, for each
// character at least 100 px tall, the share of points over the camera-facing cross-sections of its own legs,
// torso and head shapes (area-weighted) that a ray from the eye reaches only through a nearer character's body
// shape (the same vertical cylinders). The grid differs from the rays in three ways, each bounded: the shapes'
// screen rectangles are counted in whole 4 px cells (outwards for the character, by cell centre for the
// occluders), an occluder is compared at its axis depth against the character's nearest shape less its torso
// radius (a ray compares true depths), and shapes are sampled (16 cells each at most). For a character 100 px
// tall the torso is 5.5 x 8.5 cells, so one column or row of cells counted differently on each side of a
// partly covered shape moves its share by up to about 2 / 5.5 = 0.36: the per-character bound below (0.45)
// allows that and the rays' own 5 x 5 sampling. Over a crowd the roundings fall both ways, so the mean
// difference is small: its bound (0.12) is a regression guard, not derived (0.071 over 135 characters, 57
// of them partly covered, when written; largest 0.37). Off-screen characters are left out: the job counts
// only cells on screen, the rays see past its edges.
TEST(Occlusion, EstimateMatchesRayCastShapes) {
    Scene s;
    uint32_t seed = 7;
    auto rnd = [&] { return static_cast<float>((seed = seed * 1664525u + 1013904223u) >> 8) / 16777216.0f; };
    for (int z = 0; z < 24; ++z)
        for (int x = 0; x < 16; ++x)
            s.add({0.8f * (x - 8) + 0.4f * (rnd() - 0.5f), 0.0f, -0.8f * z + 0.4f * (rnd() - 0.5f)}, 1.55f + 0.4f * rnd(), 0.2f);
    const glm::vec3 eye(0, 1.7f, 4);
    const LodCamera cam = make_lod_camera(eye, {0, 1.3f, -10}, glm::radians(60.0f), {1280, 720}, 0.1f, 500.0f);
    const OcclusionParams p;
    (void)s.run(cam, p);
    const glm::mat4 vp = cam.projection * cam.view;
    const OcclusionParams::BodyShape shapes[3] = {p.body_legs, p.body_torso, p.body_head};
    double sum_diff = 0.0, max_diff = 0.0;
    size_t checked = 0, partly = 0;
    for (size_t i = 0; i < s.t.size(); ++i) {
        const glm::vec3 f = s.t[i].position;
        const float h = s.b[i].height;
        const glm::vec4 c0 = vp * glm::vec4(f, 1.0f), c1 = vp * glm::vec4(f + glm::vec3(0, h, 0), 1.0f);
        if (c0.w <= 0.5f || c1.w <= 0.5f || std::fabs(c1.y / c1.w - c0.y / c0.w) * 360.0f < 100.0f) continue;
        // Wholly on screen (the job counts only the cells on screen; the rays see past its edges).
        auto on_screen = [](const glm::vec4& c) { return std::fabs(c.x / c.w) < 0.9f && std::fabs(c.y / c.w) < 1.0f; };
        if (!on_screen(c0) || !on_screen(c1)) continue;
        if (s.a[i].occluded >= 1.0f || !s.a[i].visible) continue;
        // The camera-facing cross-section: across the view direction in the ground plane.
        const glm::vec3 to_eye = glm::normalize(glm::vec3(eye.x - f.x, 0.0f, eye.z - f.z));
        const glm::vec3 across(to_eye.z, 0.0f, -to_eye.x);
        double covered = 0.0, total = 0.0;
        for (const auto& sh : shapes) {
            const float area = (sh.y1 - sh.y0) * sh.radius;
            for (int u = 0; u < 5; ++u)
                for (int v = 0; v < 5; ++v) {
                    const glm::vec3 q = f + across * (sh.radius * h * (-0.9f + 1.8f * u / 4.0f)) +
                                        glm::vec3(0.0f, h * (sh.y0 + (sh.y1 - sh.y0) * (0.1f + 0.8f * v / 4.0f)), 0.0f);
                    bool hit = false;
                    for (size_t k = 0; k < s.t.size() && !hit; ++k) {
                        if (k == i) continue;
                        const float hk = s.b[k].height;
                        for (const auto& o : shapes)
                            hit = hit || ray_hits_cylinder(eye, q, s.t[k].position, o.y0 * hk, o.y1 * hk, o.radius * hk);
                    }
                    covered += hit ? area : 0.0;
                    total += area;
                }
        }
        const double ray = covered / total;
        const double diff = std::fabs(ray - std::min(1.0, static_cast<double>(s.a[i].occluded) / 0.99));
        EXPECT_LT(diff, 0.45) << "character " << i << ": estimate " << s.a[i].occluded << ", rays " << ray;
        sum_diff += diff;
        max_diff = std::max(max_diff, diff);
        partly += ray > 0.05 && ray < 0.95 ? 1u : 0u;
        ++checked;
    }
    ASSERT_GT(checked, 30u);  // enough characters at that size to speak of a mean
    EXPECT_GT(partly, 5u);    // and some partly covered ones (else the comparison proves little)
    EXPECT_LT(sum_diff / static_cast<double>(checked), 0.12);
    std::cout << checked << " characters (" << partly << " partly covered): mean |estimate - rays| "
              << sum_diff / static_cast<double>(checked) << ", largest " << max_diff << "\n";
}

}  // namespace
}  // namespace aloha
