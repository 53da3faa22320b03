// Impostor atlas packing (systems/render/impostor_packing.hpp): colour and normal of one atlas point in one
// texel, each half's mip chain made as a linear blit makes it, and the halves never mixed.
#include "systems/render/impostor_packing.hpp"

#include <gtest/gtest.h>

namespace aloha {
namespace {

uint32_t word(uint8_t r, uint8_t g, uint8_t b, uint8_t a) {
    return uint32_t{r} | uint32_t{g} << 8 | uint32_t{b} << 16 | uint32_t{a} << 24;
}

TEST(ImpostorPacking, DownsampleOfAnEvenSizeIsTheRoundedMeanOfTwoByTwo) {
    // 2 x 2 -> 1 x 1: the destination centre maps to the source's centre, bilinear weights 1/4 each.
    const std::vector<uint8_t> src = {0, 1, 2, 3, 10, 11, 12, 13, 20, 21, 22, 23, 31, 32, 33, 34};
    const std::vector<uint8_t> d = downsample_rgba8(src, 2, 2);
    ASSERT_EQ(d.size(), 4u);
    EXPECT_EQ(d[0], 15);  // (0 + 10 + 20 + 31) / 4 = 15.25
    EXPECT_EQ(d[1], 16);  // 16.25
    EXPECT_EQ(d[2], 17);  // 17.25
    EXPECT_EQ(d[3], 18);  // 18.25
}

TEST(ImpostorPacking, DownsampleOfAnOddSizeSamplesWhereTheBlitMapsTheCentre) {
    // 3 x 1 -> 1 x 1: the centre 0.5 maps to 1.5 source texels, the middle texel's centre (weights 0, 1, 0).
    const std::vector<uint8_t> src = {0, 0, 0, 0, 90, 91, 92, 93, 200, 200, 200, 200};
    const std::vector<uint8_t> d = downsample_rgba8(src, 3, 1);
    EXPECT_EQ(d, (std::vector<uint8_t>{90, 91, 92, 93}));
}

TEST(ImpostorPacking, TexelsPairColourAndNormalOfOnePointOverEveryLevel) {
    // A 4 x 4 atlas: colour half rows 0-1, normal half rows 2-3. Colour texel (x, y) = (x, y, 1, 255), normal
    // texel (x, y) = (100 + x, 100 + y, 7, 0): the normal half is transparent, which must not reach the colour.
    TextureImage image;
    image.width = 4;
    image.height = 4;
    image.rgba.resize(4 * 4 * 4);
    for (uint8_t y = 0; y < 2; ++y)
        for (uint8_t x = 0; x < 4; ++x) {
            uint8_t* c = &image.rgba[(size_t{y} * 4 + x) * 4];
            c[0] = x, c[1] = y, c[2] = 1, c[3] = 255;
            uint8_t* n = &image.rgba[(size_t{y + 2u} * 4 + x) * 4];
            n[0] = uint8_t(100 + x), n[1] = uint8_t(100 + y), n[2] = 7, n[3] = 0;
        }
    const PackedImpostorAtlas p = pack_impostor_atlas(image);
    EXPECT_EQ(p.width, 4u);
    EXPECT_EQ(p.height, 2u);
    ASSERT_EQ(p.levels, 3u);                       // 4 x 2, 2 x 1, 1 x 1
    ASSERT_EQ(p.texels.size(), 2u * (8 + 2 + 1));  // two words a texel
    for (uint8_t y = 0; y < 2; ++y)
        for (uint8_t x = 0; x < 4; ++x) {
            const size_t t = size_t{y} * 4 + x;
            EXPECT_EQ(p.texels[2 * t], word(x, y, 1, 255));
            EXPECT_EQ(p.texels[2 * t + 1], word(uint8_t(100 + x), uint8_t(100 + y), 7, 0));
        }
    // Level 1, texel 0: the mean of colour texels x 0-1, y 0-1 = (0.5, 0.5, 1, 255), rounded half away from zero;
    // the normal's mean (100.5, 100.5, 7, 0). The colour's alpha stays 255: nothing of the normal half in it.
    EXPECT_EQ(p.texels[16], word(1, 1, 1, 255));
    EXPECT_EQ(p.texels[17], word(101, 101, 7, 0));
    // Level 2 (1 x 1) from level 1's (1, 1, 1, 255) and (3, 1, 1, 255): their mean.
    EXPECT_EQ(p.texels[20], word(2, 1, 1, 255));
}

}  // namespace
}  // namespace aloha
