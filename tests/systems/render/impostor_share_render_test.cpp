// A shared atlas against the type's own (systems/frame/impostor_share.hpp) on lavapipe under validation: a type
// impostor_share_between lets share another's atlas, baked on its own, shows within the measured distance of the
// shared atlas's pictures. Both atlases have the same cells (sized by each figure's own height: the same layout in
// pixels), so texel (x, y) of one is the point of the other drawn at the share's scale, and the check is on the
// images themselves: every covered texel of either lies within ceil(distance) + 1 texels of a covered texel of the
// other (the surface moved by at most the distance; one more for the rasteriser's coverage rounding at each edge).
#include "impostor_figure.hpp"
#include "systems/frame/impostor_share.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace aloha {
namespace {

using namespace impostor_test;

// Coverage of the colour half of `atlas` (alpha >= half), row-major over its width.
std::vector<uint8_t> coverage(const ImpostorAtlas& atlas) {
    const uint32_t w = atlas.image.width, h = atlas.image.height / 2;
    std::vector<uint8_t> on(size_t{w} * h);
    for (size_t i = 0; i < on.size(); ++i) on[i] = atlas.image.rgba[i * 4 + 3] >= 128;
    return on;
}

// How many covered texels of `a` have no covered texel of `b` within `r` (Chebyshev).
size_t uncovered_within(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b, int w, int h, int r) {
    size_t missing = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            if (!a[size_t(y) * size_t(w) + size_t(x)]) continue;
            bool found = false;
            for (int dy = -r; dy <= r && !found; ++dy)
                for (int dx = -r; dx <= r && !found; ++dx) {
                    const int u = x + dx, v = y + dy;
                    found = u >= 0 && v >= 0 && u < w && v < h && b[size_t(v) * size_t(w) + size_t(u)];
                }
            missing += !found;
        }
    return missing;
}

TEST(ImpostorShareRender, ASharedAtlasShowsTheTypeWithinTheMeasuredDistance) {
    std::unique_ptr<gpu::Context> ctx = test::lavapipe_context();
    ASSERT_TRUE(ctx);
    const Figure fig;
    const ImpostorBakeInput owner = bake_input(fig, 2);
    // The figure 1.2 times as tall with its belly's front 0.8 of the owner's pixels flatter (at the larger size): inward,
    // so neither its height nor its radius about the vertical (the cells' size) changes.
    const float texel = impostor_texel_size(owner) * 1.2f;
    ImpostorBakeInput other = bake_input(fig, 2);
    for (ImpostorPose& row : other.rows)
        for (glm::vec3& p : row.positions) {
            const bool belly = p.y > 0.5f && p.y < 1.1f && p.z > 0.0f;
            p = p * 1.2f - (belly ? glm::vec3(0.0f, 0.0f, std::min(0.8f * texel, 1.2f * p.z)) : glm::vec3(0.0f));
        }
    const ImpostorShare share = impostor_share_between(owner, other);
    ASSERT_TRUE(share.shareable(kImpostorShareTolerancePx, kImpostorShareToleranceSteps)) << share.distance_px;
    EXPECT_NEAR(share.scale, 1.2f, 1e-5f);
    EXPECT_GT(share.distance_px, 0.5f) << "the belly moved";
    EXPECT_LE(share.distance_px, 0.8f * 1.0001f) << "no vertex further than the move";

    Result<ImpostorAtlas> a = bake_impostor_atlas(*ctx, owner), b = bake_impostor_atlas(*ctx, other);
    ASSERT_TRUE(a.ok()) << a.error().to_string();
    ASSERT_TRUE(b.ok()) << b.error().to_string();
    ASSERT_EQ(a.value().image.width, b.value().image.width) << "the same cells: texel for texel";
    ASSERT_EQ(a.value().image.height, b.value().image.height);
    EXPECT_NEAR(b.value().layout.height / a.value().layout.height, 1.2f, 1e-4f);
    const int w = static_cast<int>(a.value().image.width), h = static_cast<int>(a.value().image.height / 2);
    const std::vector<uint8_t> mine = coverage(b.value()), shared = coverage(a.value());
    const int reach = static_cast<int>(std::ceil(share.distance_px)) + 1;
    EXPECT_EQ(uncovered_within(mine, shared, w, h, reach), 0u) << "the type's own picture inside the shared one's reach";
    EXPECT_EQ(uncovered_within(shared, mine, w, h, reach), 0u) << "and the other way";
    // The check can fail: without the reach the pictures differ where the belly moved.
    const size_t differ = uncovered_within(mine, shared, w, h, 0) + uncovered_within(shared, mine, w, h, 0);
    EXPECT_GT(differ, 0u);
    std::printf("[ measured ] %.3f px apart: %zu covered texels without a match in place, none beyond %d\n", share.distance_px, differ, reach);
    EXPECT_TRUE(ctx->validation_messages().empty());
}

}  // namespace
}  // namespace aloha
