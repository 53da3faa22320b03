// Small text-scanning helpers for line-based asset formats (BVH): line splitting that accepts
// LF, CR LF and lone CR, whitespace tokenising (spaces and tabs), strict number parsing.
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

namespace aloha {

/// Walks a text line by line. Line numbers are 1-based; LF, CR LF and lone CR all end a line.
class LineCursor {
public:
    /// Starts at the beginning of `text` (which must outlive the cursor).
    explicit LineCursor(std::string_view text) : text_(text) {}
    /// Stores the next line (without its terminator) in `line` and its number in `number`;
    /// returns false at the end of the text.
    bool next(std::string_view* line, int* number);
    /// Number of the line returned last (0 before the first call).
    [[nodiscard]] int line_number() const { return line_; }
    /// Whether every line has been returned.
    [[nodiscard]] bool at_end() const { return pos_ >= text_.size(); }

private:
    std::string_view text_;
    size_t pos_ = 0;
    int line_ = 0;
};

/// One whitespace-separated token and the 1-based line and column it starts at.
struct TextToken {
    std::string_view text;
    int line = 0;
    int column = 0;
};

/// Appends the tokens of `line` (numbered `line_number`), split on spaces, tabs and other
/// ASCII whitespace, to `out`.
void tokenize_line(std::string_view line, int line_number, std::vector<TextToken>* out);

/// Calls `fn(token, column)` for each whitespace-separated token of `line` without allocating;
/// stops early and returns false when `fn` returns false.
template <class Fn>
bool for_each_token(std::string_view line, Fn&& fn) {
    size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\v' || line[i] == '\f')) ++i;
        if (i >= line.size()) break;
        const size_t start = i;
        while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\v' && line[i] != '\f') ++i;
        if (!fn(line.substr(start, i - start), static_cast<int>(start) + 1)) return false;
    }
    return true;
}

/// Parses the whole token as a decimal float ("1.5", "-.25", ".0083333", "+2", "1e-3").
/// Returns nullopt for anything else. NaN and infinity spellings parse (callers check finiteness).
[[nodiscard]] std::optional<float> parse_float(std::string_view token);

/// Parses the whole token as a decimal integer (optional sign). Returns nullopt on junk or overflow.
[[nodiscard]] std::optional<int64_t> parse_int(std::string_view token);

}  // namespace aloha
