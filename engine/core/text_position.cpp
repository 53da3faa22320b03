#include "engine/core/text_position.hpp"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <string>

namespace aloha {

size_t find_top_level_string(std::string_view text, std::string_view key) {
    // Inside the top-level object (depth 1) the tokens go key, ':', value, ','; deeper levels are skipped.
    enum class Want { Key, Colon, Value, Comma } want = Want::Key;
    int depth = 0;
    bool key_matches = false;
    for (size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (c == '/' && i + 1 < text.size() && text[i + 1] == '/') {
            while (i + 1 < text.size() && text[i + 1] != '\n') ++i;
        } else if (c == '/' && i + 1 < text.size() && text[i + 1] == '*') {
            const size_t end = text.find("*/", i + 2);
            i = end == std::string_view::npos ? text.size() : end + 1;
        } else if (c == '"') {
            const size_t start = i + 1;
            for (++i; i < text.size() && text[i] != '"'; ++i)
                if (text[i] == '\\') ++i;
            if (depth != 1) continue;
            if (want == Want::Key) {
                key_matches = text.substr(start, std::min(i, text.size()) - start) == key;
                want = Want::Colon;
            } else if (want == Want::Value) {
                if (key_matches) return start;
                want = Want::Comma;
            }
        } else if (c == '{' || c == '[') {
            ++depth;
        } else if (c == '}' || c == ']') {
            if (--depth == 1) want = Want::Comma;
        } else if (depth == 1 && c == ':' && want == Want::Colon) {
            want = Want::Value;
        } else if (depth == 1 && c == ',') {
            want = Want::Key;
        } else if (depth == 1 && want == Want::Value && !std::isspace(static_cast<unsigned char>(c))) {
            want = Want::Comma;  // a number or literal
        }
    }
    return std::string_view::npos;
}

size_t raw_offset_in_string(std::string_view text, size_t content_start, size_t decoded) {
    size_t raw = content_start, seen = 0;
    while (raw < text.size() && text[raw] != '"' && seen < decoded) {
        if (text[raw] != '\\' || raw + 1 >= text.size()) {
            ++raw, ++seen;
            continue;
        }
        if (text[raw + 1] != 'u') {
            raw += 2, ++seen;
            continue;
        }
        const unsigned code = static_cast<unsigned>(std::strtoul(std::string(text.substr(raw + 2, 4)).c_str(), nullptr, 16));
        raw += 6;
        if (code >= 0xD800 && code < 0xDC00) raw += 6, seen += 4;  // surrogate pair: one 4-byte character
        else seen += code < 0x80 ? 1 : code < 0x800 ? 2 : 3;
    }
    return raw;
}

void line_column_of(std::string_view text, size_t offset, int* line, int* column) {
    *line = 1;
    size_t line_start = 0;
    for (size_t i = 0; i < offset && i < text.size(); ++i)
        if (text[i] == '\n') ++*line, line_start = i + 1;
    *column = static_cast<int>(std::min(offset, text.size()) - line_start) + 1;
}

}  // namespace aloha
