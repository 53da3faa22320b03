// The resolver system: turns rule requests into the levels characters actually use, with time
// hysteresis (a minimum time at a level, in seconds), budget demotion, marshalled transitions
// (geomorph, pose cross-fade) and a list of who changed so the host re-sorts only those.
#pragma once

#include "components/lod.hpp"
#include "systems/lod/rule_table.hpp"

#include <algorithm>
#include <span>
#include <string>
#include <vector>

namespace aloha {

/// Geometric level for request `requested` after removing `demotion` levels: never demotes a Hidden
/// level, never demotes into a Hidden level, clamps to the last level. Requires a non-empty table.
[[nodiscard]] inline uint8_t demoted_geom_level(const RuleTable& table, uint8_t requested, uint8_t demotion) {
    const int last = static_cast<int>(table.geom_levels.size()) - 1;
    const int req = std::min<int>(requested, last);
    if (table.geom_levels[req].method == GeomMethod::Hidden) return static_cast<uint8_t>(req);
    int target = std::min(req + demotion, last);
    while (target > req && table.geom_levels[target].method == GeomMethod::Hidden) --target;
    return static_cast<uint8_t>(target);
}
/// Animation level for request `requested` after removing `demotion` levels (clamped to the last).
[[nodiscard]] inline uint8_t demoted_anim_level(const RuleTable& table, uint8_t requested, uint8_t demotion) {
    const int last = static_cast<int>(table.anim_levels.size()) - 1;
    return static_cast<uint8_t>(std::min(requested + demotion, last));
}

/// The levels the resolver aims a character at this frame: the request demoted by the budget
/// (budget_demotion, anim_demotion), then no richer than the caps allow (cap_geom_level,
/// cap_anim_level; a Hidden request is never raised). Levels are clamped into the table.
struct LodTargets {
    uint8_t geom = 0;   ///< target geometric level
    uint8_t anim = 0;   ///< target animation level
};
/// See LodTargets. Requires a non-empty table.
[[nodiscard]] inline LodTargets lod_targets(const RuleTable& table, const LodRequest& request, const LodState& state) {
    LodTargets t;
    t.geom = demoted_geom_level(table, request.geom_level, state.budget_demotion);
    t.anim = demoted_anim_level(table, request.anim_level, state.anim_demotion);
    const uint8_t cap_geom = std::min<uint8_t>(state.cap_geom_level, static_cast<uint8_t>(table.geom_levels.size() - 1));
    if (cap_geom > t.geom && table.geom_levels[t.geom].method != GeomMethod::Hidden) t.geom = cap_geom;
    t.anim = std::max(t.anim, std::min<uint8_t>(state.cap_anim_level, static_cast<uint8_t>(table.anim_levels.size() - 1)));
    return t;
}

/// The levels a character will have after this frame's resolve (a step of `dt` seconds) if the caps
/// allowed everything: the uncapped target where the resolver may switch (held min_seconds, Hidden, or
/// `snap`), else the current.
[[nodiscard]] LodTargets uncapped_outcome(const RuleTable& table, const LodRequest& request, const LodState& state,
                                          bool snap, float dt);

/// True when a level held `held_s` seconds may switch under `table`'s hysteresis.min_seconds (a
/// microsecond of slack, so frame times summed in float do not cost a frame).
[[nodiscard]] inline bool held_long_enough(const RuleTable& table, float held_s) { return held_s + 1e-6f >= table.hysteresis.min_seconds; }

/// Seconds geometric level `target` has been asked for without a break, counting this frame: 0 on the
/// frame it is first asked for (it differs from `state.geom_wanted`), else the state's count + dt.
[[nodiscard]] inline float seconds_wanted(const LodState& state, uint8_t target, float dt) {
    return target == state.geom_wanted ? state.seconds_geom_wanted + dt : 0.0f;
}

/// True when a character asked for geometric level `target` for `wanted_s` seconds may enter it: its
/// `enter_after_s` has passed (with the same slack as held_long_enough).
[[nodiscard]] inline bool wanted_long_enough(const RuleTable& table, uint8_t target, float wanted_s) {
    return wanted_s + 1e-6f >= table.geom_levels[target].enter_after_s;
}

/// Frames a transition of `seconds` lasts at frame time `dt`: 0 for no transition, else
/// round(seconds / dt), at least 1 (at most 65535). For consumers that count frames (the geometric
/// controller's geomorph). Requires dt > 0 when seconds > 0.
[[nodiscard]] uint16_t transition_frames(float seconds, float dt);

/// LodRequest + LodState -> LodState, GeomLod, AnimLod for a contiguous range of characters.
///
/// Per character and frame (a step of `dt` simulated seconds): timers advance (seconds_at_* + dt,
/// geomorph_left_s and crossfade_left_s - dt down to 0); the target is lod_targets() (budget demotion
/// and level caps); a level switches to its target only when it has been held for
/// hysteresis.min_seconds (or the current geometric level is Hidden, so a character coming into view is
/// never held invisible), except that a level richer than its cap allows is left at once (caps are
/// never exceeded). Every time is in seconds, so the same attribute trajectory switches at the same
/// times at any frame rate (to within a frame). A geometric switch keeps the old level in
/// prev_geom_level, sets seconds_at_geom to 0 and geomorph_left_s to the entered level's geomorph_s
/// (morph progress = 1 - geomorph_left_s / geomorph_s); an animation switch sets prev_anim_level,
/// seconds_at_anim and crossfade_left_s likewise. state.rule_id takes the request's rule once both
/// levels equal the target. Levels out of range (after loading a smaller table) are clamped first.
struct LodResolveJob {
    const RuleTable* table = nullptr;           ///< required, outlives Run()
    std::span<const LodRequest> requests;       ///< n entries
    std::span<LodState> states;                 ///< n entries, read and written
    std::span<GeomLod> geom;                    ///< n entries, written
    std::span<AnimLod> anim;                    ///< n entries, written
    std::span<uint8_t> changed_flags;           ///< n entries (1 = level changed this frame) or empty
    std::span<uint32_t> changed_indices;        ///< n entries of room (first Run() filled) or empty
    uint32_t index_base = 0;                    ///< added to indices written to changed_indices
    float dt = 0.0f;                            ///< simulated seconds since the last Run(), finite and >= 0
    bool snap = false;                          ///< first frame / teleport: take targets at once, no transitions
    uint32_t* switch_counts = nullptr;          ///< optional [2]: geometric, animation switches (added to)

    /// Checks table and sizes; appends one message per failure to `errors` when given.
    bool Validate(std::vector<std::string>* errors = nullptr) const;
    /// Resolves every character; returns how many changed a level. Requires Validate().
    size_t Run() const;
};

/// Clamps levels, previous levels and rule ids of `states` into `table`'s ranges (after a reload).
void clamp_lod_states(const RuleTable& table, std::span<LodState> states);

}  // namespace aloha
