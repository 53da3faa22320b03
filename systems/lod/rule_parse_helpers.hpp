// Internal to the rule loader: checked reading of JSON members (typed, ranged, known keys), every
// problem recorded as an Error naming the file and the JSON path.
#pragma once

#include "engine/core/result.hpp"
#include "systems/lod/rule_table.hpp"

#include <nlohmann/json.hpp>

#include <initializer_list>
#include <string>
#include <string_view>
#include <vector>

namespace aloha::lod_detail {

/// Collects problems of one rule file while its members are read.
struct JsonChecker {
    std::string source;        ///< file (or source name) for messages
    std::vector<Error> errors; ///< every problem found so far

    /// Records `message` at JSON path `path`.
    void err(const std::string& path, std::string message);
    /// Records `message` at a line and column of the file text (with the JSON path too).
    void err_at(int line, int column, const std::string& path, std::string message);
    /// Reports keys of `obj` not in `allowed` (typos are errors, not silently ignored).
    void check_keys(const nlohmann::json& obj, const std::string& path, std::initializer_list<const char*> allowed);
    /// Reports `old_key` of `obj` when present: a key of an earlier format replaced by `new_key`
    /// (list `old_key` among check_keys' allowed keys so it is reported once, by this).
    void renamed_key(const nlohmann::json& obj, const std::string& path, const char* old_key, const char* new_key);
    /// Reads optional number `key` of `obj` into *out when it lies in [lo, hi] (an integer when
    /// `integer`); a missing key keeps *out; anything else is reported.
    template <class T>
    void number(const nlohmann::json& obj, const char* key, const std::string& path, double lo, double hi,
                bool integer, T* out) {
        double x = 0.0;
        if (number_value(obj, key, path, lo, hi, integer, &x)) *out = static_cast<T>(x);
    }
    /// The checking behind number(): true and *out set when `key` is present and valid.
    bool number_value(const nlohmann::json& obj, const char* key, const std::string& path, double lo, double hi,
                      bool integer, double* out);
    /// Required non-empty string member; returns "" (and reports) when missing or not a string.
    std::string string(const nlohmann::json& obj, const char* key, const std::string& path);
    /// Optional boolean member; a missing key keeps *out.
    void boolean(const nlohmann::json& obj, const char* key, const std::string& path, bool* out);
    /// Maps string member `key` through `names` (index = result); reports unknown names. Missing:
    /// `fallback` (reported when `required`).
    int choice(const nlohmann::json& obj, const char* key, const std::string& path,
               std::initializer_list<const char*> names, int fallback, bool required);
};

/// Reads the file-wide sections of `root` into `table`: tiers, default_tier, hysteresis, budget and
/// significance (`text` is the file text, so expression errors get a line and column).
void parse_settings(const nlohmann::json& root, std::string_view text, JsonChecker& in, RuleTable& table);

/// Checks the level caps of `table` once every level is read (caps need a poorer, uncapped level).
void check_caps(JsonChecker& in, const RuleTable& table);

}  // namespace aloha::lod_detail
