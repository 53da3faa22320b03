// Bad scene files (docs/BAD_INPUT.md, section "Scene files"): each must be refused with an Error that
// names the file, the place (line/column or JSON path) and the problem. Rows are tagged S1, S2, ...
#include "bad_input.hpp"

#include "host/scene/scene_loader.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

namespace aloha {
namespace {

using robustness::refused;
using robustness::TempDir;

const std::string kCamera = R"("camera": {"position": [0, 2, 10], "target": [0, 1, 0]})";

// A scene placed in `dir` so relative references resolve against it.
Result<SceneDesc> parse_in(const TempDir& dir, const std::string& body) {
    return parse_scene("{" + kCamera + ", " + body + "}", dir.file("bad.json"));
}

TEST(SceneBadInput, TruncatedFileGivesLineAndColumn) {
    TempDir dir("scene_trunc");
    const std::string full = robustness::slurp(std::string(ALOHA_SOURCE_DIR) + "/data/scenes/closeup.json");
    ASSERT_GT(full.size(), 100u);
    const std::string path = dir.write("bad.json", full.substr(0, full.size() / 2));
    auto r = load_scene(path);
    EXPECT_TRUE(refused(r, "S1 truncated", "bad.json", {"invalid JSON"}));
    if (!r.ok()) {
        EXPECT_GT(r.error().line, 1) << "half of closeup.json spans several lines";
        EXPECT_GT(r.error().column, 0);
    }
    EXPECT_TRUE(refused(load_scene(dir.write("empty.json", "")), "S2 empty file", "empty.json", {"invalid JSON"}));
    EXPECT_TRUE(refused(load_scene(dir.write("bin.json", std::string("\x89PNG\r\n\x1a\n\0\0", 10))), "S3 binary garbage",
                        "bin.json", {"invalid JSON"}));
}

TEST(SceneBadInput, WrongTypes) {
    TempDir dir("scene_types");
    EXPECT_TRUE(refused(parse_in(dir, R"("characters": [{}], "frames": "300")"), "S4 string for a number", "bad.json",
                        {"/frames"}));
    EXPECT_TRUE(refused(parse_in(dir, R"("characters": {"type": "humanoid"})"), "S5 object for an array", "bad.json",
                        {"/characters"}));
    EXPECT_TRUE(refused(parse_scene("[1, 2, 3]", dir.file("bad.json")), "S6 top level not an object", "bad.json", {}));
    EXPECT_TRUE(refused(parse_in(dir, R"("characters": [{"position": [0, 0]}])"), "S7 vec3 with 2 numbers", "bad.json",
                        {"/characters/0/position"}));
    EXPECT_TRUE(refused(parse_in(dir, R"("characters": [{"importance": true}])"), "S8 bool for a number", "bad.json",
                        {"/characters/0/importance"}));
}

TEST(SceneBadInput, NanInfAndOverflowingNumbers) {
    TempDir dir("scene_nan");
    // JSON has no NaN/Infinity literals: they are syntax errors.
    EXPECT_TRUE(refused(parse_in(dir, R"("characters": [{"position": [0, NaN, 0]}])"), "S9 NaN literal", "bad.json",
                        {"invalid JSON"}));
    EXPECT_TRUE(refused(parse_in(dir, R"("characters": [{"heading_deg": Infinity}])"), "S10 Infinity literal",
                        "bad.json", {"invalid JSON"}));
    // 1e999 overflows double: nlohmann reports it; the loader places it.
    EXPECT_TRUE(refused(parse_in(dir, R"("characters": [{"position": [0, 1e999, 0]}])"), "S11 1e999", "bad.json",
                        {"number overflow"}));
    // 1e39 is a finite double but overflows float (max 3.4e38): must not become inf in a component.
    EXPECT_TRUE(refused(parse_in(dir, R"("characters": [{"position": [0, 1e39, 0]}])"), "S12 1e39 (float overflow)",
                        "bad.json", {"/characters/0/position"}));
}

TEST(SceneBadInput, HugeCountsAndNegativeSizes) {
    TempDir dir("scene_huge");
    EXPECT_TRUE(refused(parse_in(dir, R"("crowds": [{"count": 1000000000}])"), "S13 1e9 characters", "bad.json",
                        {"/crowds/0/count"}));
    EXPECT_TRUE(refused(parse_in(dir, R"("crowds": [{"count": 4294967297}])"), "S14 count past 2^32", "bad.json",
                        {"/crowds/0/count"}));
    EXPECT_TRUE(refused(parse_in(dir, R"("crowds": [{"count": 600000}, {"count": 600000}])"),
                        "S15 1.2e6 characters over two crowds", "bad.json", {"1000000"}));
    EXPECT_TRUE(refused(parse_in(dir, R"("crowds": [{"count": -5}])"), "S16 negative count", "bad.json",
                        {"/crowds/0/count"}));
    EXPECT_TRUE(refused(parse_in(dir, R"("crowds": [{"count": 10, "layout": "disc", "radius": -3}])"),
                        "S17 negative radius", "bad.json", {"/crowds/0/radius"}));
    EXPECT_TRUE(refused(parse_in(dir, R"("crowds": [{"count": 10, "walk_route": "spiral"}])"), "S17b unknown walk route",
                        "bad.json", {"/crowds/0/walk_route", "spiral"}));
    EXPECT_TRUE(refused(parse_in(dir, R"("characters": [{}], "viewport": {"width": -1280, "height": 720})"),
                        "S18 negative viewport width", "bad.json", {"/viewport/width"}));
    EXPECT_TRUE(refused(parse_in(dir, R"("characters": [{}], "frames": 1e300)"), "S19 frames 1e300", "bad.json",
                        {"/frames"}));
}

TEST(SceneBadInput, DeepNestingIsRefusedWithoutStackOverflow) {
    TempDir dir("scene_deep");
    // 100000 nested arrays: nlohmann parses and destroys iteratively; the loader must not recurse either.
    const std::string deep = std::string(100000, '[') + std::string(100000, ']');
    EXPECT_TRUE(refused(parse_in(dir, R"("characters": [{}], "paths": )" + deep), "S20 100000 nested arrays",
                        "bad.json", {"nests deeper than 64"}));
}

TEST(SceneBadInput, MissingAndUnreadableFiles) {
    TempDir dir("scene_missing");
    EXPECT_TRUE(refused(load_scene(dir.file("nope.json")), "S21 missing scene file", "nope.json", {"does not exist"}));
    std::filesystem::create_directories(dir.file("folder.json"));
    EXPECT_TRUE(refused(load_scene(dir.file("folder.json")), "S22 scene path is a folder", "folder.json", {"folder"}));
    const std::string big = dir.write("big.json", "{}");
    std::filesystem::resize_file(big, (64u << 20) + 1);  // sparse: no 64 MiB written
    EXPECT_TRUE(refused(load_scene(big), "S23 scene file over 64 MiB", "big.json", {"64 MiB"}));
    EXPECT_TRUE(refused(parse_in(dir, R"("character_types": [{"name": "m", "bvh": "missing.bvh"}], "characters": [{"type": "m"}])"),
                        "S24 missing BVH asset", "bad.json", {"/character_types/0/bvh", "does not exist"}));
    EXPECT_TRUE(refused(parse_in(dir, R"("characters": [{}], "rules": "builtin:nonexistent")"), "S25 unknown builtin",
                        "bad.json", {"/rules", "unknown built-in"}));
}

TEST(SceneBadInput, PathsThatEscapeTheSceneFolder) {
    TempDir dir("scene_escape");
    dir.write("inside/ok.bvh", "HIERARCHY\n");
    const std::string scene = dir.file("inside/bad.json");
    auto with_bvh = [&](const std::string& ref) {
        return parse_scene("{" + kCamera + R"(, "character_types": [{"name": "m", "bvh": ")" + ref +
                               R"("}], "characters": [{"type": "m"}]})",
                           scene);
    };
    EXPECT_TRUE(refused(with_bvh("../../../etc/passwd"), "S26 ../ escape", "bad.json", {"escapes the scene's folder"}));
    EXPECT_TRUE(refused(with_bvh("sub/../../x.bvh"), "S27 escape through a sub-folder", "bad.json", {"escapes"}));
    EXPECT_TRUE(refused(with_bvh("/etc/passwd"), "S28 absolute path", "bad.json", {"absolute path"}));
    // One problem, one error: the refused path does not also count as a type with no source.
    const auto absolute = with_bvh("/etc/passwd");
    ASSERT_FALSE(absolute.ok());
    EXPECT_EQ(absolute.error().to_string().find("give exactly one of"), std::string::npos) << absolute.error().to_string();
    EXPECT_TRUE(refused(with_bvh("builtin:../../etc/passwd"), "S29 builtin: with ..", "bad.json", {"unknown built-in"}));
    // A name that merely starts with the folder's name is outside it ("inside" vs "inside_evil").
    dir.write("inside_evil/x.bvh", "HIERARCHY\n");
    EXPECT_TRUE(refused(with_bvh("../inside_evil/x.bvh"), "S30 sibling folder with the same prefix", "bad.json", {"escapes"}));
    EXPECT_TRUE(with_bvh("./sub/../ok.bvh").ok()) << "a path that goes down and back up stays inside";
}

// Regression (found while fuzzing, fixed): resolve_scene_path checks containment lexically, so a symbolic link inside the scene's
// folder that points elsewhere is followed (the loader would read /etc/passwd through it). Fix:
// host/scene/scene_loader.cpp resolve_scene_path(): compare fs::weakly_canonical(folder) with
// fs::weakly_canonical(full) in is_inside() (canonical paths resolve links) before accepting.
TEST(SceneBadInput, SymlinkThatEscapesTheSceneFolder) {
    TempDir dir("scene_symlink");
    std::error_code ec;
    std::filesystem::create_symlink("/etc/passwd", dir.file("evil.bvh"), ec);
    if (ec) GTEST_SKIP() << "cannot create symbolic links here: " << ec.message();
    EXPECT_TRUE(refused(parse_in(dir, R"("character_types": [{"name": "m", "bvh": "evil.bvh"}], "characters": [{"type": "m"}])"),
                        "S31 symlink escape", "bad.json", {"escapes"}));
}

}  // namespace
}  // namespace aloha
