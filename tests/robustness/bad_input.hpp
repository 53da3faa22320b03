// Helpers for the bad-input regression tests: temporary files and a check that a loader refused an
// input with an Error naming the file and the problem. Every checked message is printed as
// "BAD_INPUT <row>: <Error::to_string()>" so docs/BAD_INPUT.md can quote real output.
#pragma once

#include "engine/core/result.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <iostream>
#include <iterator>
#include <string>

namespace aloha::robustness {

/// A fresh folder under the system temp folder, removed with its contents on destruction.
class TempDir {
public:
    /// Creates <tmp>/aloha_robustness_<tag>_<pid> (emptied first).
    explicit TempDir(const std::string& tag) {
        path_ = std::filesystem::temp_directory_path() /
                ("aloha_robustness_" + tag + "_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
                 "_" + std::to_string(reinterpret_cast<uintptr_t>(this)));
        std::filesystem::remove_all(path_);
        std::filesystem::create_directories(path_);
    }
    ~TempDir() {
        std::error_code ec;
        std::filesystem::remove_all(path_, ec);
    }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
    /// Absolute path of `name` inside the folder.
    [[nodiscard]] std::string file(const std::string& name) const { return (path_ / name).string(); }
    /// Writes `bytes` to `name` (creating sub-folders) and returns its absolute path.
    std::string write(const std::string& name, const std::string& bytes) const {
        const std::filesystem::path p = path_ / name;
        std::filesystem::create_directories(p.parent_path());
        std::ofstream(p, std::ios::binary) << bytes;
        return p.string();
    }
    /// The folder itself.
    [[nodiscard]] const std::filesystem::path& path() const { return path_; }

private:
    std::filesystem::path path_;
};

/// Reads a whole file as bytes ("" when it cannot be read).
inline std::string slurp(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

/// Success when `error` names `file` (substring of Error::file) and its formatted text contains every
/// string of `parts`; prints the formatted error tagged with `row`.
inline ::testing::AssertionResult names_problem(const Error& error, const std::string& row, const std::string& file,
                                                std::initializer_list<const char*> parts) {
    const std::string text = error.to_string();
    std::cout << "BAD_INPUT " << row << ": " << text << "\n";
    if (file.empty() || error.file.find(file) == std::string::npos)
        return ::testing::AssertionFailure() << row << ": error does not name '" << file << "': " << text;
    for (const char* part : parts)
        if (text.find(part) == std::string::npos)
            return ::testing::AssertionFailure() << row << ": expected '" << part << "' in: " << text;
    return ::testing::AssertionSuccess();
}

/// Success when `result` failed and names_problem() holds for its error.
template <class T>
::testing::AssertionResult refused(const Result<T>& result, const std::string& row, const std::string& file,
                                   std::initializer_list<const char*> parts) {
    if (result.ok()) return ::testing::AssertionFailure() << row << ": input was accepted";
    return names_problem(result.error(), row, file, parts);
}

/// Status overload of refused().
inline ::testing::AssertionResult refused(const Status& status, const std::string& row, const std::string& file,
                                          std::initializer_list<const char*> parts) {
    if (status.ok()) return ::testing::AssertionFailure() << row << ": input was accepted";
    return names_problem(status.error(), row, file, parts);
}

}  // namespace aloha::robustness
