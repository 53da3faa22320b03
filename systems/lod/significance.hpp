// Significance as data: a small arithmetic expression over a character's LOD attributes, compiled
// once to postfix code and evaluated per character. The frame budget and the level caps rank
// characters by it (least significant are demoted first, most significant fill capped levels).
#pragma once

#include "components/lod.hpp"

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace aloha {

/// The expression used when a rule file names none (the original fixed formula): small, peripheral,
/// unimportant characters score lowest, characters outside the view score 0.
inline constexpr std::string_view kDefaultSignificance =
    "visible * projected_height_px * (0.25 + importance) / (1 + min(eccentricity, 1000)^2)";

/// Where and why an expression does not compile: `offset` is the 0-based byte in the expression.
struct ExprError {
    size_t offset = 0;    ///< byte of the expression text the problem starts at
    std::string message;  ///< what is wrong ("unknown name 'distanse' (known: ...)")
};

/// A compiled significance expression. Grammar: numbers, the attribute names distance,
/// projected_height_px, eccentricity, speed, importance, visible (0/1) and occluded (0..1),
/// + - * / ^ (power, right-associative), unary minus, parentheses and the functions min(a, b, ...),
/// max(a, b, ...), abs(x), sqrt(x), clamp(x, lo, hi). Evaluation allocates nothing.
class SignificanceExpr {
public:
    /// An expression equal to kDefaultSignificance.
    SignificanceExpr();
    /// Compiles `text`; on failure returns false and fills `error` (the object is left unchanged).
    bool compile(std::string_view text, ExprError* error);
    /// Evaluates for `a`. Never NaN: NaN becomes 0, infinities the largest finite float of their sign.
    [[nodiscard]] float evaluate(const LodAttributes& a) const;
    /// The source text compiled.
    [[nodiscard]] const std::string& text() const { return text_; }

    /// One postfix instruction (public for tests and tools; not meant to be built by hand).
    struct Op {
        uint8_t code = 0;   ///< Opcode
        uint8_t arg = 0;    ///< attribute slot (push attribute) or argument count (min/max)
        float value = 0.0f; ///< the constant (push constant)
    };
    /// The compiled postfix code.
    [[nodiscard]] const std::vector<Op>& code() const { return code_; }

    /// Deepest evaluation stack an expression may need (deeper ones are refused at compile time).
    static constexpr int kMaxStack = 32;

private:
    std::string text_;
    std::vector<Op> code_;
};

}  // namespace aloha
