// Typed, path-tracking access to JSON objects for data files (scenes, humanoid definitions). Every problem is recorded as an
// Error naming the file and the JSON path; unknown keys are errors (they are usually typos).
#pragma once

#include "engine/core/result.hpp"

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include <set>
#include <string>
#include <string_view>
#include <vector>

namespace aloha {

/// Reads fields of one JSON object at `path` in `file`, appending problems to `errors`.
/// Requires `errors` to outlive the reader.
class JsonObjectReader {
public:
    /// `value` must be the JSON value at `path`; a non-object records an error and reads nothing.
    JsonObjectReader(const nlohmann::json& value, std::string path, const std::string& file,
                     std::vector<Error>& errors);

    /// True when the object has `key` (and marks it known).
    bool has(const char* key);
    /// A finite number in [lo, hi]; `fallback` when absent and not `required`.
    double number(const char* key, double fallback, double lo, double hi, bool required = false);
    /// An integer in [lo, hi].
    int64_t integer(const char* key, int64_t fallback, int64_t lo, int64_t hi, bool required = false);
    /// A boolean.
    bool boolean(const char* key, bool fallback);
    /// A string (non-empty when `required`).
    std::string string(const char* key, const std::string& fallback, bool required = false);
    /// A 3-vector [x, y, z] of finite numbers.
    glm::vec3 vec3(const char* key, const glm::vec3& fallback, bool required = false);
    /// The raw child value (nullptr when absent); marks the key known.
    const nlohmann::json* child(const char* key);
    /// Path of a child key, for nested readers.
    [[nodiscard]] std::string child_path(const char* key) const { return path_ + "/" + key; }
    /// Records an error at `sub_path` (relative to this object; "" for the object itself).
    void error(const std::string& sub_path, const std::string& message);
    /// Reports keys that were never asked for. Call once after reading every field.
    void reject_unknown_keys();
    /// True when this reader was given an object.
    [[nodiscard]] bool is_object() const { return object_ != nullptr; }

private:
    const nlohmann::json* object_ = nullptr;
    std::string path_;
    const std::string& file_;
    std::vector<Error>& errors_;
    std::set<std::string> known_;
};

/// Reads a 3-vector from `value` at `path`, recording problems; returns `fallback` on error.
glm::vec3 read_vec3(const nlohmann::json& value, const std::string& path, const std::string& file,
                    std::vector<Error>& errors, const glm::vec3& fallback);

/// Parses JSON text (nested at most as deep as check_json_depth allows; `//` and `/* */` comments
/// when `allow_comments`): the one JSON front end of every data format (scenes, rules, muscle layouts,
/// joint limits, humanoid definitions). A syntax error or an overflowing number becomes an Error
/// "invalid JSON: ..." with the file, line and column.
Result<nlohmann::json> parse_json_text(std::string_view text, const std::string& file, bool allow_comments = false);

}  // namespace aloha
