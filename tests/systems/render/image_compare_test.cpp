// Image comparison: thresholds, fractions, size mismatches, and golden-file errors.
#include "engine/gpu/png.hpp"
#include "systems/render/image_compare.hpp"

#include <gtest/gtest.h>

#include <cstdlib>

namespace aloha {
namespace {

gpu::Rgba8Image flat(uint32_t w, uint32_t h, uint8_t v) {
    return {w, h, std::vector<uint8_t>(size_t(w) * h * 4, v)};
}

TEST(ImageCompare, ThresholdAndFraction) {
    gpu::Rgba8Image a = flat(10, 10, 100), b = flat(10, 10, 100);
    ImageDiff d = compare_images(a, b, 0);
    EXPECT_TRUE(d.same_size);
    EXPECT_EQ(d.differing_pixels, 0u);
    b.pixels[0] = 105;      // pixel 0, channel R: +5
    b.pixels[4 * 7 + 2] = 90;  // pixel 7, channel B: -10
    d = compare_images(a, b, 5);
    EXPECT_EQ(d.differing_pixels, 1u);  // only the -10 exceeds 5
    EXPECT_DOUBLE_EQ(d.differing_fraction, 0.01);
    EXPECT_EQ(d.max_channel_diff, 10);
    EXPECT_FALSE(compare_images(a, flat(10, 11, 100), 0).same_size);
}

TEST(ImageCompare, GoldenMismatchAndMissingFileAreErrors) {
    ASSERT_EQ(std::getenv("ALOHA_UPDATE_GOLDEN") == nullptr ||
                  std::string(std::getenv("ALOHA_UPDATE_GOLDEN")) != "1",
              true)
        << "this test needs ALOHA_UPDATE_GOLDEN unset";
    const std::string path = ::testing::TempDir() + "aloha_golden_test.png";
    const gpu::Rgba8Image img = flat(8, 8, 50);
    ASSERT_TRUE(gpu::write_png(path, 8, 8, img.pixels).ok());
    EXPECT_TRUE(check_golden(img, path).ok());
    gpu::Rgba8Image changed = img;
    for (size_t i = 0; i < 4 * 4; ++i) changed.pixels[i] = 200;  // 4 of 64 pixels = 6% > 0.5%
    Status s = check_golden(changed, path);
    ASSERT_FALSE(s.ok());
    EXPECT_EQ(s.error().file, path);
    Status missing = check_golden(img, path + ".missing.png");
    ASSERT_FALSE(missing.ok());
    EXPECT_NE(missing.error().message.find("ALOHA_UPDATE_GOLDEN"), std::string::npos);
    std::remove(path.c_str());
}

}  // namespace
}  // namespace aloha
