// Internal to the rule loader: the rule file being read (its name and every problem found so far) and
// the file-wide sections. Objects are read with the foundation's JsonObjectReader (engine/core/json_reader).
#pragma once

#include "engine/core/json_reader.hpp"
#include "engine/core/result.hpp"
#include "systems/lod/rule_table.hpp"

#include <nlohmann/json.hpp>

#include <string>
#include <string_view>
#include <vector>

namespace aloha::lod_detail {

/// The rule file being read: its name for messages and every problem found so far.
struct RuleFile {
    std::string source;         ///< file (or source name) for messages
    std::vector<Error> errors;  ///< every problem found so far

    /// A reader of the object `value` found at JSON path `path` (records an error when it is not one).
    JsonObjectReader object(const nlohmann::json& value, const std::string& path) { return {value, path, source, errors}; }
    /// Records `message` at JSON path `path`.
    void err(const std::string& path, std::string message) { errors.push_back(make_error(source, std::move(message), 0, 0, path)); }
};

/// Why the frame-counted keys of earlier rule files were replaced (JsonObjectReader::renamed).
inline constexpr const char* kSecondsNotFrames = "seconds of simulated time, so the behaviour does not depend on the frame rate";

/// Reads the file-wide sections of the document `root` into `table`: tiers, default_tier, hysteresis,
/// budget and significance (`text` is the file text, so expression errors get a line and column).
void parse_settings(JsonObjectReader& root, std::string_view text, RuleFile& in, RuleTable& table);

/// Checks the level caps of `table` once every level is read (caps need a poorer, uncapped level).
void check_caps(RuleFile& in, const RuleTable& table);

}  // namespace aloha::lod_detail
