// The one JSON front end of every data format (scenes, rules, muscle layouts, joint limits, humanoid
// definitions): parse_json_text (syntax errors with line and column) and JsonObjectReader (typed, ranged,
// path-tracking access to one object). Every problem is recorded as an Error naming the file and the JSON
// path; unknown keys are errors (they are usually typos) and list the keys allowed there.
#pragma once

#include "engine/core/result.hpp"

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include <initializer_list>
#include <set>
#include <string>
#include <string_view>
#include <type_traits>
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
    /// Marks keys as known without reading them (e.g. "description", or keys read through child()).
    void allow(std::initializer_list<const char*> keys);
    /// A finite number in [lo, hi]; `fallback` when absent (an error too when `required`).
    double number(const char* key, double fallback, double lo, double hi, bool required = false);
    /// An integer in [lo, hi].
    int64_t integer(const char* key, int64_t fallback, int64_t lo, int64_t hi, bool required = false);
    /// Reads `key` into `out` when present and valid in [lo, hi]: an integer for integral T, a number for
    /// floating T; otherwise `out` keeps its value (and a present but bad value is recorded).
    template <class T>
    void read(const char* key, T& out, double lo, double hi) {
        if constexpr (std::is_integral_v<T>)
            out = static_cast<T>(integer(key, static_cast<int64_t>(out), static_cast<int64_t>(lo), static_cast<int64_t>(hi)));
        else
            out = static_cast<T>(number(key, static_cast<double>(out), lo, hi));
    }
    /// A boolean.
    bool boolean(const char* key, bool fallback);
    /// A string (non-empty when `required`).
    std::string string(const char* key, const std::string& fallback, bool required = false);
    /// A 3-vector [x, y, z] of finite numbers within +-`bound`.
    glm::vec3 vec3(const char* key, const glm::vec3& fallback, bool required = false, double bound = 1e7);
    /// A string among `names`: its index; `fallback` when absent (an error too when `required`).
    int choice(const char* key, std::initializer_list<const char*> names, int fallback, bool required = false);
    /// Reports `old_key` when present: a key of an earlier format replaced by `new_key` (`why` says how).
    void renamed(const char* old_key, const char* new_key, const std::string& why);
    /// The raw child value (nullptr when absent); marks the key known.
    const nlohmann::json* child(const char* key);
    /// Path of a child key, for nested readers.
    [[nodiscard]] std::string child_path(const char* key) const { return path_ + "/" + key; }
    /// Records an error at `sub_path` (relative to this object; "" for the object itself).
    void error(const std::string& sub_path, const std::string& message);
    /// The same with a line and column of the file text.
    void error_at(int line, int column, const std::string& sub_path, const std::string& message);
    /// Reports keys that were never asked for or allowed, listing the known ones. Call once after
    /// reading every field.
    void reject_unknown_keys();
    /// The JSON path of this object ("" for the document).
    [[nodiscard]] const std::string& path() const { return path_; }
    /// True when this reader was given an object.
    [[nodiscard]] bool is_object() const { return object_ != nullptr; }

private:
    const nlohmann::json* object_ = nullptr;
    std::string path_;
    const std::string& file_;
    std::vector<Error>& errors_;
    std::set<std::string> known_;
    std::vector<std::string> known_order_;  // for the "allowed:" list, in the order asked
};

/// Reads a 3-vector of finite numbers within +-`bound` from `value` at `path`, recording problems;
/// returns `fallback` on error.
glm::vec3 read_vec3(const nlohmann::json& value, const std::string& path, const std::string& file,
                    std::vector<Error>& errors, const glm::vec3& fallback, double bound = 1e7);

/// A number as JSON writes it (2, 0.9, 1e+30): for messages.
std::string json_number_text(double value);

/// Parses JSON text (nested at most as deep as check_json_depth allows; `//` and `/* */` comments
/// when `allow_comments`): the one JSON front end of every data format (scenes, rules, muscle layouts,
/// joint limits, humanoid definitions). A syntax error or an overflowing number becomes an Error
/// "invalid JSON: ..." with the file, line and column.
Result<nlohmann::json> parse_json_text(std::string_view text, const std::string& file, bool allow_comments = false);

}  // namespace aloha
