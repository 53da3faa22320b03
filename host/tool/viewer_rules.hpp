// Live rule editing for the viewer: which numbers of a RuleTable a user may change (each finite
// threshold of a continuous attribute, the target levels of each rule, the hysteresis band and minimum
// frames), how a changed copy is kept consistent (widened bounds recomputed with the parser's formula)
// and swapped in with RuleSet::set_table, and a reload from file that keeps every character's state
// (levels only clamped into the new table's range). No ImGui here.
#pragma once

#include "components/lod.hpp"
#include "engine/core/result.hpp"
#include "systems/lod/rule_set.hpp"
#include "systems/lod/rule_table.hpp"

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace aloha::tool {

/// One editable bound: slot `attribute` of box `box` (index into RuleTable::boxes) of rule `rule`,
/// its upper (hi) or lower (lo) end.
struct RuleThreshold {
    uint32_t rule = 0;                             ///< index into RuleTable::rules
    uint32_t box = 0;                              ///< index into RuleTable::boxes
    LodAttribute attribute = LodAttribute::Distance;///< slot
    bool upper = false;                            ///< true: hi[slot], false: lo[slot]
};

/// True for attributes whose bounds are widened by the hysteresis band (all but visible and tier).
[[nodiscard]] bool is_continuous(LodAttribute a);

/// Every finite bound of a continuous attribute in `table`, in rule, box, slot, lower-then-upper order.
[[nodiscard]] std::vector<RuleThreshold> editable_thresholds(const RuleTable& table);

/// Current value of threshold `t`; requires t to come from editable_thresholds(table).
[[nodiscard]] float threshold_value(const RuleTable& table, const RuleThreshold& t);

/// Recomputes lo_wide/hi_wide of box `box` from lo/hi and table.hysteresis.band, exactly as the rule
/// parser does (x -/+ band * |x| for finite bounds of continuous attributes). Requires box < boxes.size().
void recompute_widened_bounds(RuleTable& table, uint32_t box);
/// Same for every box (after changing hysteresis.band).
void recompute_widened_bounds(RuleTable& table);

/// Sets threshold `t` to `value`, clamped so the slot keeps lo <= hi (a box never becomes empty) and
/// finite; recomputes that box's widened bounds. Returns the value stored.
float set_threshold(RuleTable& table, const RuleThreshold& t, float value);

/// Points rule `rule` at levels (geom, anim) in both rules[] and compiled[]; requires indices in range.
void set_rule_levels(RuleTable& table, uint32_t rule, uint8_t geom_level, uint8_t anim_level);

/// Sets the hysteresis band (clamped to [0, 1]) and minimum seconds at a level (clamped to [0, 600];
/// a non-finite value keeps the old one), recomputing every widened bound.
void set_hysteresis(RuleTable& table, float band, float min_seconds);

/// Checks the RuleTable invariants an edit could break (level indices in range, compiled parallel to
/// rules, box ranges inside boxes, lo <= hi, widened bounds containing the plain ones, last rule
/// unconditional); appends one message per problem. True when none.
bool validate_edited_table(const RuleTable& table, std::vector<std::string>* errors = nullptr);

/// Swaps `edited` into `rules` with set_table when validate_edited_table passes; otherwise returns an
/// error naming the table's source and the first problem. Character state is not touched.
Status apply_edited_table(RuleSet& rules, RuleTable edited);

/// Re-reads the rule file (RuleSet::reload_from_file); on success clamps `states` into the new table's
/// level range (nothing else about them changes). On failure the old table stays and the error returns.
Status reload_rules_keep_state(RuleSet& rules, std::span<LodState> states);

}  // namespace aloha::tool
