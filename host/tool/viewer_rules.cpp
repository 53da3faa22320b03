#include "host/tool/viewer_rules.hpp"

#include "systems/lod/resolver.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace aloha::tool {

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

size_t slot(LodAttribute a) { return static_cast<size_t>(a); }

}  // namespace

bool is_continuous(LodAttribute a) { return a != LodAttribute::Visible && a != LodAttribute::Tier; }

std::vector<RuleThreshold> editable_thresholds(const RuleTable& table) {
    std::vector<RuleThreshold> out;
    for (uint32_t r = 0; r < table.compiled.size(); ++r) {
        const CompiledRule& c = table.compiled[r];
        for (uint32_t b = c.first_box; b < c.first_box + c.box_count && b < table.boxes.size(); ++b) {
            const ConditionBox& box = table.boxes[b];
            for (int k = 0; k < kLodAttributeCount; ++k) {
                const auto a = static_cast<LodAttribute>(k);
                if (!is_continuous(a)) continue;
                if (std::isfinite(box.lo[k])) out.push_back({r, b, a, false});
                if (std::isfinite(box.hi[k])) out.push_back({r, b, a, true});
            }
        }
    }
    return out;
}

float threshold_value(const RuleTable& table, const RuleThreshold& t) {
    const ConditionBox& box = table.boxes[t.box];
    return t.upper ? box.hi[slot(t.attribute)] : box.lo[slot(t.attribute)];
}

void recompute_widened_bounds(RuleTable& table, uint32_t box) {
    widen_box(table.boxes[box], table.hysteresis.band);  // the parser's own formula
}

void recompute_widened_bounds(RuleTable& table) {
    for (uint32_t b = 0; b < table.boxes.size(); ++b) recompute_widened_bounds(table, b);
}

float set_threshold(RuleTable& table, const RuleThreshold& t, float value) {
    ConditionBox& box = table.boxes[t.box];
    const size_t k = slot(t.attribute);
    constexpr float kMax = std::numeric_limits<float>::max();
    if (!std::isfinite(value)) value = std::clamp(value, -kMax, kMax);  // +-inf -> +-max; NaN stays NaN
    if (std::isnan(value)) value = t.upper ? box.hi[k] : box.lo[k];
    if (t.upper) {
        box.hi[k] = std::max(value, box.lo[k]);
    } else {
        box.lo[k] = std::min(value, box.hi[k]);
    }
    recompute_widened_bounds(table, t.box);
    return t.upper ? box.hi[k] : box.lo[k];
}

void set_rule_levels(RuleTable& table, uint32_t rule, uint8_t geom_level, uint8_t anim_level) {
    table.rules[rule].geom_level = geom_level;
    table.rules[rule].anim_level = anim_level;
    table.compiled[rule].geom_level = geom_level;
    table.compiled[rule].anim_level = anim_level;
}

void set_hysteresis(RuleTable& table, float band, float min_seconds) {
    table.hysteresis.band = std::isfinite(band) ? std::clamp(band, 0.0f, 1.0f) : table.hysteresis.band;
    if (std::isfinite(min_seconds)) table.hysteresis.min_seconds = std::clamp(min_seconds, 0.0f, 600.0f);
    recompute_widened_bounds(table);
}

bool validate_edited_table(const RuleTable& table, std::vector<std::string>* errors) {
    size_t problems = 0;
    auto fail = [&](std::string message) {
        ++problems;
        if (errors) errors->push_back(std::move(message));
    };
    if (table.geom_levels.empty()) fail("no geometric levels");
    if (table.anim_levels.empty()) fail("no animation levels");
    if (table.rules.empty()) fail("no rules");
    if (table.compiled.size() != table.rules.size()) fail("compiled rules are not parallel to rules");
    const size_t n = std::min(table.rules.size(), table.compiled.size());
    for (size_t r = 0; r < n; ++r) {
        const RuleDef& d = table.rules[r];
        const CompiledRule& c = table.compiled[r];
        const std::string name = "rule '" + d.name + "'";
        if (d.geom_level >= table.geom_levels.size() || c.geom_level != d.geom_level)
            fail(name + ": geometric level " + std::to_string(d.geom_level) + " out of range or not compiled");
        if (d.anim_level >= table.anim_levels.size() || c.anim_level != d.anim_level)
            fail(name + ": animation level " + std::to_string(d.anim_level) + " out of range or not compiled");
        if (size_t(c.first_box) + c.box_count > table.boxes.size()) {
            fail(name + ": its boxes run past the end of the box list");
            continue;
        }
        for (uint32_t b = c.first_box; b < c.first_box + c.box_count; ++b) {
            const ConditionBox& box = table.boxes[b];
            for (int k = 0; k < kBoxSlots; ++k) {
                const std::string where = name + " box " + std::to_string(b - c.first_box) + " slot " +
                                          (k < kLodAttributeCount
                                               ? std::string(attribute_name(static_cast<LodAttribute>(k)))
                                               : std::to_string(k));
                if (std::isnan(box.lo[k]) || std::isnan(box.hi[k])) fail(where + ": bound is NaN");
                if (box.lo[k] > box.hi[k]) fail(where + ": lower bound above upper bound");
                if (box.lo_wide[k] > box.lo[k] || box.hi_wide[k] < box.hi[k])
                    fail(where + ": widened bounds do not contain the plain ones");
            }
        }
    }
    if (!table.compiled.empty()) {
        const CompiledRule& last = table.compiled.back();
        bool full = last.box_count >= 1 && size_t(last.first_box) + last.box_count <= table.boxes.size();
        if (full) {
            full = false;
            for (uint32_t b = last.first_box; b < last.first_box + last.box_count && !full; ++b) {
                const ConditionBox& box = table.boxes[b];
                bool all = true;
                for (int k = 0; k < kBoxSlots; ++k) all = all && box.lo[k] == -kInf && box.hi[k] == kInf;
                full = all;
            }
        }
        if (!full) fail("the last rule must be unconditional (a fallback)");
    }
    if (!std::isfinite(table.hysteresis.band) || table.hysteresis.band < 0.0f)
        fail("hysteresis band must be a finite number >= 0");
    return problems == 0;
}

Status apply_edited_table(RuleSet& rules, RuleTable edited) {
    std::vector<std::string> errors;
    if (!validate_edited_table(edited, &errors))
        return make_error(edited.source, "edited rule table rejected: " + errors.front());
    rules.set_table(std::move(edited));
    return {};
}

Status reload_rules_keep_state(RuleSet& rules, std::span<LodState> states) {
    if (Status s = rules.reload_from_file(); !s.ok()) return s;
    clamp_lod_states(rules.table(), states);
    return {};
}

}  // namespace aloha::tool
