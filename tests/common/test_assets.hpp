// Test helper: finds third-party test assets (CMU 131_01.bvh, Khronos CesiumMan.glb, ...) that are
// never part of the repository. They are looked up in one folder: $ALOHA_TEST_ASSETS when set and
// non-empty, else the compile-time default ALOHA_DEFAULT_TEST_ASSETS (<repository>/../shared/assets,
// set by aloha_test/aloha_bench in cmake/AlohaTargets.cmake). A test that needs one skips, naming
// the file and the folder, when it is absent: it never fails and never passes silently.
#pragma once

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>

#ifndef ALOHA_DEFAULT_TEST_ASSETS
#error "ALOHA_DEFAULT_TEST_ASSETS must be defined (aloha_test and aloha_bench in cmake/AlohaTargets.cmake do it)"
#endif

namespace aloha::test {

/// Name of the environment variable that overrides the shared test-asset folder.
inline constexpr const char* kTestAssetsEnv = "ALOHA_TEST_ASSETS";

/// The folder searched for shared test assets: $ALOHA_TEST_ASSETS if set and non-empty, else the
/// compile-time default ALOHA_DEFAULT_TEST_ASSETS (lexically normalised, so "a/../b" prints as "b").
inline std::string test_assets_dir() {
    const char* env = std::getenv(kTestAssetsEnv);
    const std::string dir = env != nullptr && *env != '\0' ? std::string(env) : std::string(ALOHA_DEFAULT_TEST_ASSETS);
    return std::filesystem::path(dir).lexically_normal().string();
}

/// Full path of the shared test asset `name` (a plain file name, e.g. "CesiumMan.glb"), or nullopt
/// when test_assets_dir() holds no regular file of that name.
inline std::optional<std::string> find_test_asset(const std::string& name) {
    const std::filesystem::path path = std::filesystem::path(test_assets_dir()) / name;
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) return std::nullopt;
    return path.string();
}

/// Why a test skips when `name` is missing: the file, the folder looked in (and where that folder
/// came from) and how to provide it.
inline std::string missing_test_asset_message(const std::string& name) {
    const char* env = std::getenv(kTestAssetsEnv);
    const bool from_env = env != nullptr && *env != '\0';
    return "test asset '" + name + "' not found; looked in " + test_assets_dir() +
           (from_env ? " (from $ALOHA_TEST_ASSETS)" : " (built-in default; $ALOHA_TEST_ASSETS is unset or empty)") +
           ". Set ALOHA_TEST_ASSETS to a folder holding it, or place ../shared/assets next to the repository.";
}

}  // namespace aloha::test

/// Declares `const std::string var` = full path of the shared test asset `name`, or skips the
/// current test (GTEST_SKIP with missing_test_asset_message) when it is absent. Use in a function
/// returning void: a TEST body, or a fixture's SetUp() (skips that test) / SetUpTestSuite().
#define ALOHA_REQUIRE_TEST_ASSET(var, name)                                                  \
    const std::optional<std::string> var##_found_ = ::aloha::test::find_test_asset(name);    \
    if (!var##_found_) {                                                                     \
        GTEST_SKIP() << ::aloha::test::missing_test_asset_message(name);                     \
    }                                                                                        \
    const std::string var = *var##_found_
