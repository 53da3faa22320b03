#include "engine/assets/text_scan.hpp"

#include <charconv>
#include <cmath>
#include <limits>

namespace aloha {

bool LineCursor::next(std::string_view* line, int* number) {
    if (pos_ >= text_.size()) return false;
    size_t end = pos_;
    while (end < text_.size() && text_[end] != '\n' && text_[end] != '\r') ++end;
    *line = text_.substr(pos_, end - pos_);
    if (end < text_.size()) {
        if (text_[end] == '\r' && end + 1 < text_.size() && text_[end + 1] == '\n') end += 2;
        else end += 1;
    }
    pos_ = end;
    *number = ++line_;
    return true;
}

void tokenize_line(std::string_view line, int line_number, std::vector<TextToken>* out) {
    for_each_token(line, [&](std::string_view tok, int column) {
        out->push_back({tok, line_number, column});
        return true;
    });
}

std::optional<float> parse_float(std::string_view token) {
    if (!token.empty() && token.front() == '+') token.remove_prefix(1);
    if (token.empty() || token.front() == '+') return std::nullopt;
    float value = 0.0f;
    const char* first = token.data();
    const char* last = token.data() + token.size();
    const auto [ptr, ec] = std::from_chars(first, last, value);
    if (ec == std::errc::result_out_of_range && ptr == last) {
        // Too large or too small for float: too large becomes infinite (the caller's finiteness
        // check names it), too small becomes the nearest float (0 or a denormal).
        double wide = 0.0;
        const auto [wptr, wec] = std::from_chars(first, last, wide);
        if (wptr != last) return std::nullopt;
        if (wec == std::errc::result_out_of_range || std::fabs(wide) > std::numeric_limits<float>::max())
            return std::numeric_limits<float>::infinity();
        return static_cast<float>(wide);
    }
    if (ec != std::errc() || ptr != last) return std::nullopt;
    return value;
}

std::optional<int64_t> parse_int(std::string_view token) {
    if (!token.empty() && token.front() == '+') token.remove_prefix(1);
    if (token.empty() || token.front() == '+') return std::nullopt;
    int64_t value = 0;
    const char* last = token.data() + token.size();
    const auto [ptr, ec] = std::from_chars(token.data(), last, value);
    if (ec != std::errc() || ptr != last) return std::nullopt;
    return value;
}

}  // namespace aloha
