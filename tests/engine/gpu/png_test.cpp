// PNG writing/reading: exact round trip, and errors that name the file.
#include "engine/gpu/png.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>

namespace aloha::gpu {
namespace {

TEST(Png, RoundTripIsExact) {
    const uint32_t w = 7, h = 5;  // odd sizes catch row-stride mistakes
    std::vector<uint8_t> px(w * h * 4);
    for (size_t i = 0; i < px.size(); ++i) px[i] = static_cast<uint8_t>(i * 37 + 11);
    const std::string path = ::testing::TempDir() + "aloha_png_roundtrip.png";
    ASSERT_TRUE(write_png(path, w, h, px).ok());
    Result<Rgba8Image> back = read_png(path);
    ASSERT_TRUE(back.ok()) << back.error().to_string();
    EXPECT_EQ(back.value().width, w);
    EXPECT_EQ(back.value().height, h);
    EXPECT_EQ(back.value().pixels, px);  // PNG is lossless
    std::remove(path.c_str());
}

TEST(Png, ErrorsNameTheFile) {
    std::vector<uint8_t> px(4 * 4 * 4, 0);
    Status wrong_size = write_png(::testing::TempDir() + "x.png", 4, 5, px);
    ASSERT_FALSE(wrong_size.ok());
    EXPECT_NE(wrong_size.error().file.find("x.png"), std::string::npos);

    Status no_dir = write_png("/nonexistent-dir/out.png", 4, 4, px);
    ASSERT_FALSE(no_dir.ok());
    EXPECT_EQ(no_dir.error().file, "/nonexistent-dir/out.png");

    Result<Rgba8Image> missing = read_png("/nonexistent-dir/in.png");
    ASSERT_FALSE(missing.ok());
    EXPECT_EQ(missing.error().file, "/nonexistent-dir/in.png");

    const std::string junk = ::testing::TempDir() + "aloha_not_a_png.png";
    std::ofstream(junk) << "this is not a png file";
    Result<Rgba8Image> bad = read_png(junk);
    ASSERT_FALSE(bad.ok());
    EXPECT_EQ(bad.error().file, junk);
    EXPECT_NE(bad.error().message.find("not a PNG"), std::string::npos);
    std::remove(junk.c_str());
}

}  // namespace
}  // namespace aloha::gpu
