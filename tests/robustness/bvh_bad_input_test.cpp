// Bad BVH files (docs/BAD_INPUT.md, section "BVH"): truncated CMU files, wrong channel counts, NaN/Inf,
// huge counts, hostile structure. Rows B1, B2, ... (tests/engine/assets/bvh_errors_test.cpp has more).
// B1-B3 cut the CMU file 131_01.bvh, a shared test asset that is not in the repository
// (tests/common/test_assets.hpp): only their test skips without it.
#include "bad_input.hpp"

#include "engine/assets/bvh_loader.hpp"
#include "tests/common/test_assets.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

namespace aloha {
namespace {

using robustness::refused;
using robustness::TempDir;

// Two joints (Hips with 6 channels, Spine with 3), 2 frames; line numbers: 16 MOTION, 17 Frames,
// 18 Frame Time, 19-20 rows.
const std::string kSmall =
    "HIERARCHY\nROOT Hips\n{\n  OFFSET 0 0 0\n  CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation\n"
    "  JOINT Spine\n  {\n    OFFSET 0 5 0\n    CHANNELS 3 Zrotation Xrotation Yrotation\n    End Site\n    {\n"
    "      OFFSET 0 3 0\n    }\n  }\n}\nMOTION\nFrames: 2\nFrame Time: 0.033333\n0 10 0 0 0 0 10 0 0\n1 10 0 5 0 0 20 0 0\n";

// kSmall with the first occurrence of `from` replaced by `to`.
std::string small_with(const std::string& from, const std::string& to) {
    std::string s = kSmall;
    const size_t at = s.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) s.replace(at, from.size(), to);
    return s;
}

Result<BvhData> parse(const std::string& text) { return parse_bvh(text, "bad.bvh"); }

TEST(BvhBadInput, BaseParses) { ASSERT_TRUE(parse(kSmall).ok()) << parse(kSmall).error().to_string(); }

TEST(BvhBadInput, TruncatedCmuFile) {
    ALOHA_REQUIRE_TEST_ASSET(path, "131_01.bvh");
    const std::string cmu = robustness::slurp(path);
    ASSERT_GT(cmu.size(), 700000u);
    const size_t motion = cmu.find("MOTION");
    ASSERT_NE(motion, std::string::npos);
    EXPECT_TRUE(refused(parse_bvh(cmu.substr(0, motion / 2), "131_01.bvh"), "B1 CMU cut in the hierarchy", "131_01.bvh",
                        {"131_01.bvh:87:"}));  // the cut falls inside "Zrotation" of line 87
    EXPECT_TRUE(refused(parse_bvh(cmu.substr(0, cmu.size() / 2), "131_01.bvh"), "B2 CMU cut in the motion", "131_01.bvh",
                        {"Frames", "motion rows"}));
    // Cut in the middle of a number of the last row: the row has too few values.
    EXPECT_TRUE(refused(parse_bvh(cmu.substr(0, cmu.size() - 40), "131_01.bvh"), "B3 CMU cut inside the last row",
                        "131_01.bvh", {"values, expected 96"}));
}

TEST(BvhBadInput, WrongChannelCounts) {
    EXPECT_TRUE(refused(parse(small_with("CHANNELS 3 Z", "CHANNELS 4 Z")), "B4 CHANNELS 4 listing 3", "bad.bvh",
                        {":9:", "declares 4 channels but lists 3"}));
    EXPECT_TRUE(refused(parse(small_with("CHANNELS 6", "CHANNELS 7")), "B5 CHANNELS 7", "bad.bvh", {":5:", "0 to 6"}));
    EXPECT_TRUE(refused(parse(small_with("CHANNELS 3 Z", "CHANNELS 1000000000 Z")), "B6 CHANNELS 1e9", "bad.bvh", {":9:"}));
    EXPECT_TRUE(refused(parse(small_with("CHANNELS 3 Z", "CHANNELS -3 Z")), "B7 negative CHANNELS", "bad.bvh", {":9:"}));
    EXPECT_TRUE(refused(parse(small_with("1 10 0 5 0 0 20 0 0", "1 10 0 5 0 0 20")), "B8 row with too few values",
                        "bad.bvh", {":20:", "has 7 values, expected 9"}));
}

TEST(BvhBadInput, NanInfAndOverflow) {
    EXPECT_TRUE(refused(parse(small_with("1 10 0 5", "1 nan 0 5")), "B9 NaN channel value", "bad.bvh",
                        {":20:", "NaN or infinite"}));
    EXPECT_TRUE(refused(parse(small_with("1 10 0 5", "1 -inf 0 5")), "B10 -inf channel value", "bad.bvh", {":20:"}));
    EXPECT_TRUE(refused(parse(small_with("OFFSET 0 5 0", "OFFSET 0 1e39 0")), "B11 OFFSET 1e39 (float overflow)",
                        "bad.bvh", {":8:"}));
    EXPECT_TRUE(refused(parse(small_with("Frame Time: 0.033333", "Frame Time: nan")), "B12 Frame Time NaN", "bad.bvh",
                        {":18:"}));
    EXPECT_TRUE(refused(parse(small_with("Frame Time: 0.033333", "Frame Time: -0.1")), "B13 negative Frame Time",
                        "bad.bvh", {":18:"}));
}

TEST(BvhBadInput, HugeAndNegativeCounts) {
    EXPECT_TRUE(refused(parse(small_with("Frames: 2", "Frames: 1000000000")), "B14 Frames 1e9", "bad.bvh",
                        {":17:", "exceeds the limit"}));
    EXPECT_TRUE(refused(parse(small_with("Frames: 2", "Frames: 99999999999999999999")), "B15 Frames past int64",
                        "bad.bvh", {":17:"}));
    EXPECT_TRUE(refused(parse(small_with("Frames: 2", "Frames: -2")), "B16 negative Frames", "bad.bvh", {":17:"}));
    // 40000 nested joints (deeper than any skeleton index type allows): refused, no stack overflow.
    std::string deep = "HIERARCHY\n";
    const int n = 40000;
    for (int i = 0; i < n; ++i)
        deep += (i == 0 ? "ROOT j" : "JOINT j") + std::to_string(i) + "\n{\nOFFSET 0 1 0\nCHANNELS 1 Xrotation\n";
    deep += std::string(static_cast<size_t>(n), '}') + "\nMOTION\nFrames: 1\nFrame Time: 0.1\n";
    for (int i = 0; i < n; ++i) deep += "0 ";
    auto r = parse(deep);
    EXPECT_TRUE(refused(r, "B17 40000 nested joints", "bad.bvh", {"joints"}));
}

TEST(BvhBadInput, MissingFolderAndBinaryFiles) {
    TempDir dir("bvh_files");
    EXPECT_TRUE(refused(load_bvh(dir.file("nope.bvh")), "B18 missing file", "nope.bvh", {}));
    std::filesystem::create_directories(dir.file("folder.bvh"));
    EXPECT_TRUE(refused(load_bvh(dir.file("folder.bvh")), "B19 path is a folder", "folder.bvh", {}));
    EXPECT_TRUE(refused(load_bvh(dir.write("bin.bvh", std::string("\0\0\0\xff\xfe HIERARCHY", 15))), "B20 binary garbage",
                        "bin.bvh", {"HIERARCHY"}));
    EXPECT_TRUE(refused(parse(small_with("JOINT Spine", "JOINT Hips")), "B21 duplicate joint name", "bad.bvh",
                        {":6:", "duplicate joint name"}));
}

}  // namespace
}  // namespace aloha
