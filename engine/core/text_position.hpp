// Positions in JSON text for error messages: the 1-based line and column of a byte, where the string
// value of a top-level member starts, and which raw byte a decoded string byte came from (escapes
// such as \" and \u00e9 take several raw bytes). Used to point errors found inside a string value
// (an expression, say) at the exact place in the file.
#pragma once

#include <cstddef>
#include <string_view>

namespace aloha {

/// 1-based line and column of byte `offset` of `text` (an offset past the end counts as the end).
void line_column_of(std::string_view text, size_t offset, int* line, int* column);

/// Byte offset in JSON `text` of the first character inside the string value of the top-level
/// member `key`, or npos when there is none (comments and strings are skipped while searching).
[[nodiscard]] size_t find_top_level_string(std::string_view text, std::string_view key);

/// Byte offset in JSON `text` of decoded byte `decoded` of the string whose contents start at
/// `content_start` (stops at the closing quote).
[[nodiscard]] size_t raw_offset_in_string(std::string_view text, size_t content_start, size_t decoded);

}  // namespace aloha
