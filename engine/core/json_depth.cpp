#include "engine/core/json_depth.hpp"

namespace aloha {

Status check_json_depth(std::string_view text, const std::string& file, int max_depth) {
    int depth = 0, line = 1, column = 0;
    bool in_string = false, escaped = false;
    for (const char c : text) {
        ++column;
        if (c == '\n') {
            ++line;
            column = 0;
        }
        if (in_string) {
            if (escaped) escaped = false;
            else if (c == '\\') escaped = true;
            else if (c == '"') in_string = false;
            continue;
        }
        if (c == '"') {
            in_string = true;
        } else if (c == '[' || c == '{') {
            if (++depth > max_depth)
                return make_error(file, "JSON nests deeper than " + std::to_string(max_depth) + " levels", line, column);
        } else if ((c == ']' || c == '}') && depth > 0) {
            --depth;
        }
    }
    return {};
}

}  // namespace aloha
