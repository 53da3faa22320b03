// The per-pixel frame comparisons of `aloha profile --fidelity` (host/tool/image_compare.hpp): PSNR, the
// picture's change and the change of the LOD's error against the reference.
#include "host/tool/image_compare.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

namespace aloha::tool {
namespace {

constexpr int kW = 32, kH = 16;

// An RGBA image whose pixel (x, y) has the grey value value(x, y).
std::vector<uint8_t> image(const std::function<int(int, int)>& value) {
    std::vector<uint8_t> px(size_t(kW * kH * 4), 255);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x)
            for (int c = 0; c < 3; ++c) px[size_t(4 * (y * kW + x) + c)] = uint8_t(value(x, y));
    return px;
}

// A scene: a ramp moving `shift` pixels to the right, as both pictures see it.
int ramp(int x, int shift) { return (7 * (x - shift) + 64 * kW) % 256; }

TEST(ImageCompare, PsnrOfIdenticalImagesIs99AndOfAKnownErrorFollowsTheFormula) {
    const auto a = image([](int x, int) { return ramp(x, 0); });
    EXPECT_EQ(psnr_db(a, a), 99.0);
    const auto b = image([](int x, int) { return ramp(x, 0) < 246 ? ramp(x, 0) + 10 : ramp(x, 0) - 10; });  // every sample off by 10
    EXPECT_NEAR(psnr_db(a, b), 10.0 * std::log10(255.0 * 255.0 / 100.0), 1e-9);
}

// The camera pans: the picture changes everywhere, but the LOD picture and the reference move together,
// so the LOD's error does not change.
TEST(ImageCompare, MotionSharedWithTheReferenceCancelsInTheErrorChange) {
    const auto before = image([](int x, int) { return ramp(x, 0); });
    const auto now = image([](int x, int) { return ramp(x, 3); });
    std::vector<uint16_t> map;
    EXPECT_GT(change_map(now, before, map), 0.02);
    EXPECT_EQ(error_change(now, now, before, before, map), 0.0);
    ASSERT_EQ(map.size(), size_t(kW * kH));
    for (uint16_t v : map) EXPECT_EQ(v, 0);
}

// A level switch that pops: a 4 x 4 patch of the LOD picture jumps by 60 on one frame while the reference
// only pans. The error change is that jump over the patch: 60 * 16 pixels / (255 * 512 pixels), exactly,
// and the map holds 3 * 60 on the patch and 0 elsewhere.
TEST(ImageCompare, APopIsTheErrorChangeAtFullSize) {
    auto patch = [](int x, int y) { return x >= 8 && x < 12 && y >= 4 && y < 8; };
    const auto ref_before = image([](int x, int) { return ramp(x, 0); });
    const auto ref_now = image([](int x, int) { return ramp(x, 1); });
    const auto lod_before = ref_before;
    const auto lod_now = image([&](int x, int y) { return patch(x, y) ? std::min(255, ramp(x, 1) + 60) : ramp(x, 1); });
    // The patch's ramp values stay below 196, so the jump is never clipped.
    for (int x = 8; x < 12; ++x) ASSERT_LT(ramp(x, 1), 196);
    std::vector<uint16_t> map;
    EXPECT_NEAR(error_change(lod_now, ref_now, lod_before, ref_before, map), 60.0 * 16.0 / (255.0 * kW * kH), 1e-12);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) EXPECT_EQ(map[size_t(y * kW + x)], patch(x, y) ? 180 : 0) << x << "," << y;
}

// The same switch cross-faded over four frames changes the error by a quarter of the jump on each.
TEST(ImageCompare, ACrossFadeSpreadsTheErrorChangeOverItsFrames) {
    const auto ref = image([](int x, int) { return ramp(x, 0); });
    auto lod = [&](int step) {  // 0..4: the patch a quarter further to +60 each step
        return image([&](int x, int y) { return ramp(x, 0) + (x >= 8 && x < 12 && y >= 4 && y < 8 ? 15 * step : 0); });
    };
    std::vector<uint16_t> map;
    for (int step = 1; step <= 4; ++step)
        EXPECT_NEAR(error_change(lod(step), ref, lod(step - 1), ref, map), 15.0 * 16.0 / (255.0 * kW * kH), 1e-12);
}

TEST(ImageCompare, ImagesOfDifferentSizesGiveNoErrorChange) {
    const auto a = image([](int, int) { return 1; });
    std::vector<uint8_t> smaller(a.begin(), a.end() - 4);
    std::vector<uint16_t> map{1, 2};
    EXPECT_EQ(error_change(a, a, smaller, a, map), 0.0);
    EXPECT_TRUE(map.empty());
    map = {1, 2};
    EXPECT_EQ(change_map(a, smaller, map), 0.0);
    EXPECT_TRUE(map.empty());
}

// Silhouettes against the reference's background (its most common colour, grey 30 here): a 4 x 4 figure drawn one
// pixel off is covered both ways within the 1-px reach; three pixels off, not at all; a figure missing from the other
// picture leaves the reference's share covered at half when one of two is drawn; a shade 24 levels (summed) off the
// background is no figure, 27 is.
TEST(ImageCompare, SilhouetteCoverageCountsCharacterPixelsWithinOnePixel) {
    const auto block = [](int x0, int y0) { return [=](int x, int y) { return x >= x0 && x < x0 + 4 && y >= y0 && y < y0 + 4 ? 200 : 30; }; };
    const auto reference = image(block(4, 4));
    const SilhouetteCoverage same = silhouette_coverage(reference, reference, kW);
    EXPECT_EQ(same.reference_pixels, 16u);
    EXPECT_EQ(same.pixels, 16u);
    EXPECT_EQ(same.covered, 1.0);
    EXPECT_EQ(same.on_reference, 1.0);
    const SilhouetteCoverage shifted = silhouette_coverage(image(block(5, 5)), reference, kW);
    EXPECT_EQ(shifted.covered, 1.0);
    EXPECT_EQ(shifted.on_reference, 1.0);
    const SilhouetteCoverage away = silhouette_coverage(image(block(12, 4)), reference, kW);
    EXPECT_EQ(away.covered, 0.0);
    EXPECT_EQ(away.on_reference, 0.0);
    // Two figures in the reference, one drawn.
    const auto two = image([&](int x, int y) { return block(4, 4)(x, y) == 200 || block(20, 8)(x, y) == 200 ? 200 : 30; });
    const SilhouetteCoverage one_of_two = silhouette_coverage(reference, two, kW);
    EXPECT_EQ(one_of_two.reference_pixels, 32u);
    EXPECT_EQ(one_of_two.covered, 0.5);
    EXPECT_EQ(one_of_two.on_reference, 1.0);
    // Nothing drawn: no pixels, the reference's covered share 0, the other share 1 (nothing drawn off it).
    const SilhouetteCoverage none = silhouette_coverage(image([](int, int) { return 30; }), reference, kW);
    EXPECT_EQ(none.pixels, 0u);
    EXPECT_EQ(none.covered, 0.0);
    EXPECT_EQ(none.on_reference, 1.0);
    EXPECT_EQ(silhouette_coverage(image([](int, int) { return 38; }), reference, kW).pixels, 0u) << "8 levels a channel: 24 summed";
    EXPECT_EQ(silhouette_coverage(image([](int, int) { return 39; }), reference, kW).pixels, size_t(kW * kH)) << "27 summed";
    EXPECT_EQ(silhouette_coverage(reference, image([](int, int) { return 30; }), 0).reference_pixels, 0u) << "no width: nothing counted";
}

}  // namespace
}  // namespace aloha::tool
