// Table of malformed BVH inputs: each must give an Error naming the file, the right line and the problem.
#include "engine/assets/bvh_loader.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace aloha {
namespace {

// Base file, one statement per line so line numbers are easy to read off:
//  1 HIERARCHY / 2 ROOT Hips / 3 { / 4 OFFSET / 5 CHANNELS 6 / 6 JOINT Knee / 7 { / 8 OFFSET /
//  9 CHANNELS 3 / 10 End Site / 11 { / 12 OFFSET / 13 } / 14 } / 15 } / 16 MOTION / 17 Frames /
// 18 Frame Time / 19 row 0 / 20 row 1
std::vector<std::string> base_lines() {
    return {"HIERARCHY", "ROOT Hips", "{", "\tOFFSET 0 0 0",
            "\tCHANNELS 6 Xposition Yposition Zposition Zrotation Yrotation Xrotation", "\tJOINT Knee", "\t{",
            "\t\tOFFSET 0 -1 0", "\t\tCHANNELS 3 Zrotation Xrotation Yrotation", "\t\tEnd Site", "\t\t{",
            "\t\t\tOFFSET 0 -1 0", "\t\t}", "\t}", "}", "MOTION", "Frames: 2", "Frame Time: .5",
            "1 2 3 4 5 6 7 8 9", "1 2 3 4 5 6 7 8 9"};
}

std::string join(const std::vector<std::string>& lines) {
    std::string out;
    for (const std::string& l : lines) out += l + "\r\n";
    return out;
}

// The base file with line `n` (1-based) replaced by `text`.
std::string with_line(int n, const std::string& text) {
    std::vector<std::string> lines = base_lines();
    lines[static_cast<size_t>(n - 1)] = text;
    return join(lines);
}

// The base file cut after line `n`.
std::string first_lines(int n) {
    std::vector<std::string> lines = base_lines();
    lines.resize(static_cast<size_t>(n));
    return join(lines);
}

struct BadCase {
    const char* what;
    std::string text;
    int line;                 // expected Error::line
    const char* message_part; // expected substring of Error::message
};

TEST(BvhErrors, BaseFileParses) {
    Result<BvhData> r = parse_bvh(join(base_lines()), "base.bvh");
    ASSERT_TRUE(r.ok()) << r.error().to_string();
    EXPECT_EQ(r.value().skeleton.joints.size(), 2u);
}

TEST(BvhErrors, EachBadInputNamesFileLineAndProblem) {
    const std::vector<BadCase> cases = {
        {"too few values", with_line(20, "1 2 3"), 20, "has 3 values, expected 9"},
        {"too many values", with_line(19, "1 2 3 4 5 6 7 8 9 10"), 19, "has 10 values, expected 9"},
        {"unknown channel", with_line(9, "CHANNELS 3 Zrotation Wrotation Yrotation"), 9, "unknown channel name 'Wrotation'"},
        {"channel count mismatch", with_line(9, "CHANNELS 3 Zrotation Xrotation"), 9, "declares 3 channels but lists 2"},
        {"channel count not a number", with_line(9, "CHANNELS three Zrotation"), 9, "is not a number from 0 to 6"},
        {"duplicate channel", with_line(9, "CHANNELS 3 Zrotation Zrotation Yrotation"), 9, "listed twice"},
        {"missing MOTION", first_lines(15), 15, "missing MOTION"},
        {"Frames too large for rows", with_line(17, "Frames: 3"), 17, "only 2 motion rows"},
        {"Frames too small for rows", with_line(17, "Frames: 1"), 20, "more motion rows"},
        {"huge Frames", with_line(17, "Frames: 100000000"), 17, "exceeds the limit"},
        {"negative Frames", with_line(17, "Frames: -4"), 17, "at least 0"},
        {"Frames 0 with rows", with_line(17, "Frames: 0"), 19, "more motion rows than 'Frames: 0'"},
        {"Frames not a number", with_line(17, "Frames: lots"), 17, "not an integer"},
        {"missing Frames", with_line(17, "Frame Count 2"), 17, "expected 'Frames: <count>'"},
        {"zero Frame Time", with_line(18, "Frame Time: 0"), 18, "Frame Time must be"},
        {"NaN value", with_line(19, "1 2 3 4 nan 6 7 8 9"), 19, "NaN or infinite"},
        {"Inf value", with_line(20, "1 2 3 4 5 6 7 8 inf"), 20, "NaN or infinite"},
        {"overflowing value", with_line(20, "1 2 3 4 5 6 7 8 1e60"), 20, "NaN or infinite"},
        {"junk value", with_line(19, "1 2 3 4 5 x6 7 8 9"), 19, "'x6' is not a number"},
        {"missing closing brace", with_line(14, ""), 16, "not closed (unbalanced braces)"},
        {"extra closing brace", with_line(16, "}"), 16, "unbalanced '}'"},
        {"truncated in hierarchy", first_lines(9), 9, "unexpected end of file"},
        {"truncated motion", first_lines(19), 17, "only 1 motion rows"},
        {"truncated after MOTION", first_lines(16), 16, "missing 'Frames:'"},
        {"no HIERARCHY", with_line(1, "HIERARCHIE"), 1, "expected HIERARCHY"},
        {"OFFSET with two numbers", with_line(8, "OFFSET 0 -1"), 8, "OFFSET needs 3 numbers"},
        {"OFFSET not a number", with_line(8, "OFFSET 0 abc 0"), 8, "'abc' is not a number"},
        {"OFFSET NaN", with_line(4, "OFFSET 0 nan 0"), 4, "NaN or infinite"},
        {"missing OFFSET", with_line(8, ""), 14, "has no OFFSET"},
        {"missing CHANNELS", with_line(5, ""), 15, "has no CHANNELS"},
        {"missing brace after JOINT", with_line(7, "OFFSET 0 0 0"), 7, "expected '{' after joint 'Knee'"},
        {"duplicate joint name", with_line(6, "JOINT Hips"), 6, "duplicate joint name 'Hips'"},
        {"JOINT without a name", with_line(6, "JOINT"), 6, "has no name"},
        {"unexpected keyword", with_line(8, "OFSET 0 -1 0"), 8, "unexpected 'OFSET'"},
        {"CHANNELS in End Site", with_line(12, "CHANNELS 1 Xrotation"), 12, "CHANNELS in an End Site"},
        {"empty file", "", 1, "expected HIERARCHY"},
    };
    for (const BadCase& c : cases) {
        Result<BvhData> r = parse_bvh(c.text, "bad.bvh");
        ASSERT_FALSE(r.ok()) << c.what;
        EXPECT_EQ(r.error().file, "bad.bvh") << c.what;
        EXPECT_EQ(r.error().line, c.line) << c.what << ": " << r.error().to_string();
        EXPECT_NE(r.error().message.find(c.message_part), std::string::npos) << c.what << ": " << r.error().to_string();
    }
}

TEST(BvhErrors, BadOptionsAreRefused) {
    BvhOptions o;
    o.unit_scale = 0.0f;
    EXPECT_FALSE(parse_bvh(join(base_lines()), "base.bvh", o).ok());
}

}  // namespace
}  // namespace aloha
