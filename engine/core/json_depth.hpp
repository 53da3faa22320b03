// A guard run before parsing JSON: nlohmann::json (and tinygltf's conversion) recurse once per
// nesting level, so a hostile file nested 100,000 deep would overflow the stack. This byte scan
// refuses such text first, with the line and column where the limit is passed.
#pragma once

#include "engine/core/result.hpp"

#include <string_view>

namespace aloha {

/// Deepest array/object nesting ALOHA's data files may use.
inline constexpr int kMaxJsonDepth = 64;

/// Fails when `text` nests arrays/objects deeper than `max_depth` (strings and escapes are skipped).
/// `file` names the text in the error. Linear in the text, allocates nothing.
Status check_json_depth(std::string_view text, const std::string& file, int max_depth = kMaxJsonDepth);

}  // namespace aloha
