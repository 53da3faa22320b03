// Replays of the fuzzing inputs through the normally built loaders (docs/BAD_INPUT.md, section
// "Fuzzer findings"): every seed in tests/fuzz/corpus/<target>/ must give a value or an Error naming
// the file, without throwing. Crashes the fuzzers found live in tests/robustness/crashes/<target>/;
// their replay and the deep-nesting stack overflows below are regression tests (the loaders are fixed).
#include "bad_input.hpp"

#include "engine/assets/bvh_loader.hpp"
#include "engine/assets/gltf_loader.hpp"
#include "engine/assets/joint_limits.hpp"
#include "host/scene/scene_loader.hpp"
#include "systems/lod/rule_table.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

namespace aloha {
namespace {

const std::string kRoot = std::string(ALOHA_SOURCE_DIR);

// Runs the loader of fuzz target `target` on `bytes`; "" when it gave a value or an Error naming
// `name`, else what went wrong.
std::string replay(const std::string& target, const std::string& bytes, const std::string& name) {
    auto check = [&](const auto& r) -> std::string {
        if (r.ok()) return "";
        return r.error().file.find(name) != std::string::npos ? "" : "error does not name the file: " + r.error().to_string();
    };
    try {
        if (target == "fuzz_scene") return check(parse_scene(bytes, kRoot + "/data/scenes/" + name));
        if (target == "fuzz_rules") return check(parse_rules(bytes, name));
        if (target == "fuzz_bvh") return check(parse_bvh(bytes, name));
        if (target == "fuzz_gltf") return check(parse_gltf_character(bytes, name, kRoot + "/tests/fuzz"));
        if (target == "fuzz_joint_limits") return check(parse_joint_limits(bytes, name));
    } catch (const std::exception& e) {
        return std::string("exception escaped the loader: ") + e.what();
    }
    return "unknown target " + target;
}

// Replays every file under `folder`/<target>/ and returns one line per failure.
std::vector<std::string> replay_folder(const std::string& folder) {
    std::vector<std::string> failures;
    std::vector<std::filesystem::path> files;
    for (const auto& target : std::filesystem::directory_iterator(folder))
        for (const auto& f : std::filesystem::directory_iterator(target.path())) files.push_back(f.path());
    std::sort(files.begin(), files.end());  // deterministic order
    for (const auto& f : files) {
        const std::string why = replay(f.parent_path().filename().string(), robustness::slurp(f.string()), f.filename().string());
        if (!why.empty()) failures.push_back(f.string() + ": " + why);
    }
    return failures;
}

TEST(FuzzRegression, SeedCorporaGiveValuesOrNamedErrors) {
    const std::vector<std::string> failures = replay_folder(kRoot + "/tests/fuzz/corpus");
    for (const std::string& f : failures) ADD_FAILURE() << f;
}

// Regression (found while fuzzing, fixed): the crash files throw nlohmann::json::out_of_range out of parse_rules and
// parse_joint_limits (see RulesBadInput/JointLimitsBadInput.NumberOverflowIsAnError).
TEST(FuzzRegression, CrashFilesGiveValuesOrNamedErrors) {
    const std::vector<std::string> failures = replay_folder(kRoot + "/tests/robustness/crashes");
    for (const std::string& f : failures) ADD_FAILURE() << f;
}

// `depth` nested JSON arrays.
std::string nested(int depth) { return std::string(static_cast<size_t>(depth), '[') + std::string(static_cast<size_t>(depth), ']'); }

// Regression (found while fuzzing, fixed): 100000 nested arrays where a value is expected overflow the stack (SIGSEGV; found with the
// ASan fuzz builds): nlohmann's dump() and copy constructor and tinygltf's JSON-to-Value conversion
// recurse once per level. Sites: host/scene/json_reader.cpp (messages "found " + value.dump()),
// engine/assets/joint_limits.cpp ("found ... " + v.dump()), systems/lod/rule_parser.cpp:216 (`const
// json when = ...` copies the tree; use a reference) and rule_conditions.cpp (recursive compile), and
// tinygltf (extras). Fix: one helper, e.g. engine/core `Status check_json_depth(std::string_view text,
// const std::string& file, int max_depth = 64)`, that scans the bytes (skipping strings and escapes)
// and reports the line/column where nesting exceeds the limit; call it before json::parse in
// parse_json_text, parse_rules, parse_joint_limits, load_muscle_defs and (on the JSON chunk) in
// gltf_loader.cpp load_from_memory.
TEST(FuzzRegression, DeeplyNestedJsonIsAnErrorNotAStackOverflow) {
    const std::string d = nested(100000);
    EXPECT_TRUE(robustness::refused(
        parse_scene(R"({"camera": {"position": [0, 2, 10], "target": [0, 1, 0]}, "characters": [{"position": )" + d + "}]}",
                    "/tmp/deep.json"),
        "F1 scene value nested 100000 deep", "deep.json", {"nest"}));
    EXPECT_TRUE(robustness::refused(parse_joint_limits(R"({"joints": {"A": {"min": [0, 0, )" + d + R"(], "max": [0, 0, 0]}}})", "deep.json"),
                                    "F2 joint-limit value nested 100000 deep", "deep.json", {"nest"}));
    EXPECT_TRUE(robustness::refused(
        parse_rules(R"({"geometric_levels": [{"name": "g", "method": "rigid_proxy"}], "animation_levels": [{"name": "a", "walk": "clip"}],
                       "rules": [{"name": "x", "when": {"distance": {"lt": )" + d + R"(}}, "then": {"geometry": "g", "animation": "a"}}]})",
                    "deep.json"),
        "F3 rule operand nested 100000 deep", "deep.json", {"nest"}));
    EXPECT_TRUE(robustness::refused(parse_gltf_character(R"({"asset": {"version": "2.0"}, "nodes": [{"extras": )" + d + "}]}", "deep.gltf"),
                                    "F4 glTF extras nested 100000 deep", "deep.gltf", {"nest"}));
}

}  // namespace
}  // namespace aloha
