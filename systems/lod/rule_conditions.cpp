#include "systems/lod/rule_conditions.hpp"

#include <cmath>
#include <limits>
#include <string_view>

namespace aloha::lod_detail {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

void report(const ConditionContext& ctx, const std::string& path, std::string message) {
    ctx.errors->push_back(make_error(*ctx.source, std::move(message), 0, 0, path));
}

int attribute_index(std::string_view key) {
    for (int k = 0; k < kLodAttributeCount; ++k) {
        if (attribute_name(static_cast<LodAttribute>(k)) == key) return k;
    }
    return -1;
}

std::string known_keys() {
    std::string out;
    for (int k = 0; k < kLodAttributeCount; ++k) {
        out += std::string(attribute_name(static_cast<LodAttribute>(k))) + ", ";
    }
    return out + "all, any, not";
}

// AND of two DNFs: pairwise intersections, empty ones dropped.
bool and_dnf(const std::vector<RawBox>& a, const std::vector<RawBox>& b, std::vector<RawBox>* out,
             const ConditionContext& ctx, const std::string& path) {
    out->clear();
    for (const RawBox& x : a) {
        for (const RawBox& y : b) {
            RawBox r;
            for (int k = 0; k < kBoxSlots; ++k) {
                r.lo[k] = std::max(x.lo[k], y.lo[k]);
                r.hi[k] = std::min(x.hi[k], y.hi[k]);
            }
            if (box_empty(r)) continue;
            if (out->size() >= kMaxBoxesPerRule) {
                report(ctx, path, "condition too complex: it expands to more than " +
                                      std::to_string(kMaxBoxesPerRule) + " alternatives");
                return false;
            }
            out->push_back(r);
        }
    }
    return true;
}

// NOT of a DNF by De Morgan: AND over boxes of (OR over constrained slots of the two half-lines).
bool not_dnf(const std::vector<RawBox>& a, std::vector<RawBox>* out, const ConditionContext& ctx,
             const std::string& path) {
    std::vector<RawBox> acc{full_box()};
    std::vector<RawBox> tmp;
    for (const RawBox& x : a) {
        std::vector<RawBox> neg;
        for (int k = 0; k < kBoxSlots; ++k) {
            if (x.lo[k] > -kInf) {
                RawBox r = full_box();
                r.hi[k] = std::nextafter(x.lo[k], -kInf);
                neg.push_back(r);
            }
            if (x.hi[k] < kInf) {
                RawBox r = full_box();
                r.lo[k] = std::nextafter(x.hi[k], kInf);
                neg.push_back(r);
            }
        }
        if (!and_dnf(acc, neg, &tmp, ctx, path)) return false;
        acc.swap(tmp);
    }
    *out = std::move(acc);
    return true;
}

// Reads a comparison operand: a number, a boolean (visible), or a tier name (tier).
bool operand(const nlohmann::json& v, int slot, const std::string& path, const ConditionContext& ctx,
             float* out) {
    if (v.is_number()) {
        const double d = v.get<double>();
        if (!std::isfinite(d) || std::abs(d) > 3.0e38) {  // would become +-inf as a float
            report(ctx, path, "threshold " + v.dump() + " is not a finite number a float can hold");
            return false;
        }
        *out = static_cast<float>(d);
        return true;
    }
    if (v.is_boolean() && slot == static_cast<int>(LodAttribute::Visible)) {
        *out = v.get<bool>() ? 1.0f : 0.0f;
        return true;
    }
    if (v.is_string() && slot == static_cast<int>(LodAttribute::Tier)) {
        const std::string name = v.get<std::string>();
        for (size_t t = 0; t < ctx.tiers->size(); ++t) {
            if ((*ctx.tiers)[t] == name) {
                *out = static_cast<float>(t);
                return true;
            }
        }
        report(ctx, path, "unknown tier '" + name + "' (declare it in \"tiers\")");
        return false;
    }
    report(ctx, path, std::string("expected a number") +
                          (slot == static_cast<int>(LodAttribute::Visible) ? " or a boolean"
                           : slot == static_cast<int>(LodAttribute::Tier) ? " or a tier name"
                                                                            : "") +
                          ", got " + v.type_name());
    return false;
}

// One attribute's condition: a comparison object, a bare value (eq), or a list of tier names (any).
bool attribute_condition(const nlohmann::json& v, int slot, const std::string& path,
                         const ConditionContext& ctx, std::vector<RawBox>* out) {
    out->clear();
    if (v.is_array() && slot == static_cast<int>(LodAttribute::Tier)) {
        bool ok = true;
        for (size_t i = 0; i < v.size(); ++i) {
            float t = 0.0f;
            if (!operand(v[i], slot, path + "/" + std::to_string(i), ctx, &t)) {
                ok = false;
                continue;
            }
            RawBox b = full_box();
            b.lo[slot] = b.hi[slot] = t;
            out->push_back(b);
        }
        if (v.empty()) report(ctx, path, "empty tier list: the condition can never be true");
        return ok && !v.empty();
    }
    RawBox b = full_box();
    if (!v.is_object()) {
        float x = 0.0f;
        if (!operand(v, slot, path, ctx, &x)) return false;
        b.lo[slot] = b.hi[slot] = x;
        out->push_back(b);
        return true;
    }
    if (v.empty()) {
        report(ctx, path, "empty comparison: use min, max, lt, le, gt, ge or eq");
        return false;
    }
    bool ok = true;
    for (const auto& [key, operand_json] : v.items()) {
        float x = 0.0f;
        const std::string p = path + "/" + key;
        if (key != "min" && key != "max" && key != "lt" && key != "le" && key != "gt" && key != "ge" &&
            key != "eq") {
            report(ctx, p, "unknown comparison '" + key + "' (known: min, max, lt, le, gt, ge, eq)");
            ok = false;
            continue;
        }
        if (!operand(operand_json, slot, p, ctx, &x)) {
            ok = false;
            continue;
        }
        if (key == "min" || key == "ge") b.lo[slot] = std::max(b.lo[slot], x);
        if (key == "gt") b.lo[slot] = std::max(b.lo[slot], std::nextafter(x, kInf));
        if (key == "max" || key == "le") b.hi[slot] = std::min(b.hi[slot], x);
        if (key == "lt") b.hi[slot] = std::min(b.hi[slot], std::nextafter(x, -kInf));
        if (key == "eq") {
            b.lo[slot] = std::max(b.lo[slot], x);
            b.hi[slot] = std::min(b.hi[slot], x);
        }
    }
    if (!ok) return false;
    if (box_empty(b)) {
        report(ctx, path, "impossible range: lower bound " + std::to_string(b.lo[slot]) +
                              " is above upper bound " + std::to_string(b.hi[slot]) +
                              ", so the condition can never be true");
        return false;
    }
    out->push_back(b);
    return true;
}

}  // namespace

RawBox full_box() {
    RawBox b;
    b.lo.fill(-kInf);
    b.hi.fill(kInf);
    return b;
}

bool box_empty(const RawBox& b) {
    for (int k = 0; k < kBoxSlots; ++k) {
        if (b.lo[k] > b.hi[k]) return true;
    }
    return false;
}

bool box_full(const RawBox& b) {
    for (int k = 0; k < kBoxSlots; ++k) {
        if (b.lo[k] > -kInf || b.hi[k] < kInf) return false;
    }
    return true;
}

bool box_contains(const RawBox& outer, const RawBox& inner) {
    for (int k = 0; k < kBoxSlots; ++k) {
        if (inner.lo[k] < outer.lo[k] || inner.hi[k] > outer.hi[k]) return false;
    }
    return true;
}

bool compile_condition(const nlohmann::json& when, const std::string& path, const ConditionContext& ctx,
                       std::vector<RawBox>* out) {
    if (!when.is_object()) {
        report(ctx, path, std::string("expected an object of conditions, got ") + when.type_name());
        return false;
    }
    std::vector<RawBox> acc{full_box()};
    std::vector<RawBox> part;
    std::vector<RawBox> tmp;
    bool ok = true;
    for (const auto& [key, value] : when.items()) {
        const std::string p = path + "/" + key;
        part.clear();
        if (key == "all" || key == "any") {
            if (!value.is_array() || value.empty()) {
                report(ctx, p, "'" + key + "' needs a non-empty array of condition objects");
                ok = false;
                continue;
            }
            if (key == "any") {
                for (size_t i = 0; i < value.size(); ++i) {
                    if (!compile_condition(value[i], p + "/" + std::to_string(i), ctx, &tmp)) {
                        ok = false;
                        continue;
                    }
                    part.insert(part.end(), tmp.begin(), tmp.end());
                }
            } else {
                part.push_back(full_box());
                std::vector<RawBox> child;
                for (size_t i = 0; i < value.size(); ++i) {
                    if (!compile_condition(value[i], p + "/" + std::to_string(i), ctx, &child) ||
                        !and_dnf(part, child, &tmp, ctx, p)) {
                        ok = false;
                        continue;
                    }
                    part.swap(tmp);
                }
            }
        } else if (key == "not") {
            std::vector<RawBox> child;
            if (!compile_condition(value, p, ctx, &child) || !not_dnf(child, &part, ctx, p)) {
                ok = false;
                continue;
            }
        } else {
            const int slot = attribute_index(key);
            if (slot < 0) {
                report(ctx, p, "unknown attribute '" + key + "' (known: " + known_keys() + ")");
                ok = false;
                continue;
            }
            if (!attribute_condition(value, slot, p, ctx, &part)) {
                ok = false;
                continue;
            }
        }
        if (!ok) continue;
        if (!and_dnf(acc, part, &tmp, ctx, path)) return false;
        acc.swap(tmp);
    }
    if (!ok) return false;
    if (acc.size() > kMaxBoxesPerRule) {
        report(ctx, path, "condition too complex: more than " + std::to_string(kMaxBoxesPerRule) +
                              " alternatives");
        return false;
    }
    *out = std::move(acc);
    return true;
}

}  // namespace aloha::lod_detail
