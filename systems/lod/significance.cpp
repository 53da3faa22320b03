#include "systems/lod/significance.hpp"

#include <algorithm>
#include <cctype>
#include <cfloat>
#include <cmath>
#include <cstdlib>

namespace aloha {
namespace {

enum Opcode : uint8_t { kConst, kAttr, kAdd, kSub, kMul, kDiv, kPow, kNeg, kMin, kMax, kAbs, kSqrt, kClamp };

constexpr std::string_view kNames[] = {"distance", "projected_height_px", "eccentricity", "speed",
                                       "importance", "visible", "occluded"};

float attribute(const LodAttributes& a, uint8_t slot) {
    switch (slot) {
        case 0: return a.distance;
        case 1: return a.projected_height_px;
        case 2: return a.eccentricity;
        case 3: return a.speed;
        case 4: return a.importance;
        case 5: return static_cast<float>(a.visible);
        default: return a.occluded;
    }
}

// Recursive-descent compiler to postfix code; the first error stops it.
struct Compiler {
    std::string_view s;
    size_t pos = 0;
    std::vector<SignificanceExpr::Op> code;
    int depth = 0, max_depth = 0;
    ExprError error;
    bool failed = false;

    void fail(size_t at, std::string message) {
        if (failed) return;
        failed = true;
        error = {at, std::move(message)};
    }
    void skip() {
        while (pos < s.size() && std::isspace(static_cast<unsigned char>(s[pos]))) ++pos;
    }
    bool eat(char c) {
        skip();
        if (pos < s.size() && s[pos] == c) return ++pos, true;
        return false;
    }
    void emit(uint8_t op, int pops, int pushes, uint8_t arg = 0, float value = 0.0f) {
        code.push_back({op, arg, value});
        depth += pushes - pops;
        max_depth = std::max(max_depth, depth);
    }
    void expr() {
        term();
        while (!failed) {
            if (eat('+')) term(), emit(kAdd, 2, 1);
            else if (eat('-')) term(), emit(kSub, 2, 1);
            else break;
        }
    }
    void term() {
        unary();
        while (!failed) {
            if (eat('*')) unary(), emit(kMul, 2, 1);
            else if (eat('/')) unary(), emit(kDiv, 2, 1);
            else break;
        }
    }
    void unary() {
        if (eat('-')) return unary(), emit(kNeg, 1, 1);
        if (eat('+')) return unary();
        primary();
        if (!failed && eat('^')) unary(), emit(kPow, 2, 1);
    }
    void primary() {
        skip();
        if (failed) return;
        if (pos >= s.size()) return fail(pos, "expression ends where a value is expected");
        const size_t start = pos;
        const char c = s[pos];
        if (c == '(') {
            ++pos;
            expr();
            if (!failed && !eat(')')) fail(pos, "expected ')' to close the '(' at column " + std::to_string(start + 1));
            return;
        }
        if (std::isdigit(static_cast<unsigned char>(c)) || c == '.') {
            const std::string number(s.substr(pos, std::min<size_t>(64, s.size() - pos)));
            char* end = nullptr;
            const double v = std::strtod(number.c_str(), &end);
            const size_t used = static_cast<size_t>(end - number.c_str());
            if (used == 0) return fail(start, "malformed number");
            if (!std::isfinite(v) || std::fabs(v) > FLT_MAX) return fail(start, "number too large for a float");
            pos += used;
            return emit(kConst, 0, 1, 0, static_cast<float>(v));
        }
        if (!std::isalpha(static_cast<unsigned char>(c)) && c != '_')
            return fail(start, std::string("unexpected '") + c + "' where a value is expected");
        while (pos < s.size() && (std::isalnum(static_cast<unsigned char>(s[pos])) || s[pos] == '_')) ++pos;
        const std::string_view name = s.substr(start, pos - start);
        if (eat('(')) return call(name, start);
        for (size_t k = 0; k < std::size(kNames); ++k)
            if (kNames[k] == name) return emit(kAttr, 0, 1, static_cast<uint8_t>(k));
        std::string known;
        for (std::string_view n : kNames) known += std::string(known.empty() ? "" : ", ") + std::string(n);
        if (name == "tier") return fail(start, "'tier' is not a per-character attribute (known: " + known + ")");
        fail(start, "unknown name '" + std::string(name) + "' (known: " + known + "; functions min, max, abs, sqrt, clamp)");
    }
    void call(std::string_view name, size_t start) {
        int args = 0;
        if (!eat(')')) {
            do {
                expr();
                ++args;
            } while (!failed && eat(','));
            if (!failed && !eat(')')) return fail(pos, "expected ',' or ')' in the arguments of " + std::string(name) + "()");
        }
        if (failed) return;
        auto need = [&](bool ok, const char* what) {
            if (!ok) fail(start, std::string(name) + "() takes " + what + ", got " + std::to_string(args));
            return ok;
        };
        if (name == "min" || name == "max") {
            if (need(args >= 2 && args <= 255, "2 or more arguments"))
                emit(name == "min" ? kMin : kMax, args, 1, static_cast<uint8_t>(args));
        } else if (name == "abs" || name == "sqrt") {
            if (need(args == 1, "1 argument")) emit(name == "abs" ? kAbs : kSqrt, 1, 1);
        } else if (name == "clamp") {
            if (need(args == 3, "3 arguments (x, lo, hi)")) emit(kClamp, 3, 1);
        } else {
            fail(start, "unknown function '" + std::string(name) + "' (known: min, max, abs, sqrt, clamp)");
        }
    }
};

float finite(float v) {
    if (std::isnan(v)) return 0.0f;
    if (std::isinf(v)) return v > 0.0f ? FLT_MAX : -FLT_MAX;
    return v;
}

}  // namespace

SignificanceExpr::SignificanceExpr() {
    ExprError unused;
    compile(kDefaultSignificance, &unused);
}

bool SignificanceExpr::compile(std::string_view text, ExprError* error) {
    Compiler c;
    c.s = text;
    c.expr();
    c.skip();
    if (!c.failed && c.pos < text.size()) c.fail(c.pos, std::string("unexpected '") + text[c.pos] + "' after a complete expression");
    if (!c.failed && c.code.empty()) c.fail(0, "empty expression");
    if (!c.failed && c.max_depth > kMaxStack)
        c.fail(0, "expression nests too deeply (needs more than " + std::to_string(kMaxStack) + " stack slots)");
    if (c.failed) {
        if (error) *error = c.error;
        return false;
    }
    text_ = std::string(text);
    code_ = std::move(c.code);
    return true;
}

float SignificanceExpr::evaluate(const LodAttributes& a) const {
    float st[kMaxStack];
    int n = 0;
    for (const Op& op : code_) {
        switch (op.code) {
            case kConst: st[n++] = op.value; break;
            case kAttr: st[n++] = attribute(a, op.arg); break;
            case kAdd: --n, st[n - 1] += st[n]; break;
            case kSub: --n, st[n - 1] -= st[n]; break;
            case kMul: --n, st[n - 1] *= st[n]; break;
            case kDiv: --n, st[n - 1] /= st[n]; break;
            case kPow: --n, st[n - 1] = std::pow(st[n - 1], st[n]); break;
            case kNeg: st[n - 1] = -st[n - 1]; break;
            case kAbs: st[n - 1] = std::fabs(st[n - 1]); break;
            case kSqrt: st[n - 1] = std::sqrt(st[n - 1]); break;
            case kClamp: n -= 2, st[n - 1] = std::min(std::max(st[n - 1], st[n]), st[n + 1]); break;
            case kMin:
            case kMax: {
                const int k = op.arg;
                float v = st[n - k];
                for (int j = n - k + 1; j < n; ++j) v = op.code == kMin ? std::min(v, st[j]) : std::max(v, st[j]);
                n -= k - 1;
                st[n - 1] = v;
                break;
            }
            default: break;
        }
    }
    return n == 1 ? finite(st[0]) : 0.0f;
}

}  // namespace aloha
