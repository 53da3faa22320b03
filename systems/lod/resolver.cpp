#include "systems/lod/resolver.hpp"

#include <algorithm>
#include <cmath>

namespace aloha {

namespace {
// Time held at a level stops growing here (a day): far past any hysteresis, and float keeps sub-frame steps.
constexpr float kHeldCap = 86400.0f;
inline float advance(float held, float dt) { return std::min(held + dt, kHeldCap); }
inline float run_down(float left, float dt) { return std::max(left - dt, 0.0f); }
}  // namespace

uint16_t transition_frames(float seconds, float dt) {
    if (!(seconds > 0.0f) || !(dt > 0.0f)) return 0;
    return static_cast<uint16_t>(std::clamp(std::lround(seconds / dt), 1L, 65535L));
}

LodTargets uncapped_outcome(const RuleTable& table, const LodRequest& request, const LodState& state, bool snap,
                            float dt) {
    LodState uncapped = state;
    uncapped.cap_geom_level = uncapped.cap_anim_level = 0;
    const LodTargets target = lod_targets(table, request, uncapped);
    const uint8_t geom = std::min<uint8_t>(state.geom_level, static_cast<uint8_t>(table.geom_levels.size() - 1));
    const uint8_t anim = std::min<uint8_t>(state.anim_level, static_cast<uint8_t>(table.anim_levels.size() - 1));
    // Timers advance before the resolver compares them, hence + dt.
    const bool geom_free = snap || ((held_long_enough(table, state.seconds_at_geom + dt) ||
                                     table.geom_levels[geom].method == GeomMethod::Hidden) &&
                                    wanted_long_enough(table, target.geom, std::min(seconds_wanted(state, target.geom, dt), kHeldCap)));
    const bool anim_free = snap || held_long_enough(table, state.seconds_at_anim + dt);
    return {geom_free ? target.geom : geom, anim_free ? target.anim : anim};
}

bool LodResolveJob::Validate(std::vector<std::string>* errors) const {
    bool ok = true;
    auto fail = [&](std::string m) {
        ok = false;
        if (errors) errors->push_back("LodResolveJob: " + std::move(m));
    };
    const size_t n = requests.size();
    if (table == nullptr || table->geom_levels.empty() || table->anim_levels.empty())
        fail("needs a loaded rule table with levels");
    if (states.size() != n) fail("states size differs from requests");
    if (geom.size() != n) fail("geom size differs from requests");
    if (anim.size() != n) fail("anim size differs from requests");
    if (!changed_flags.empty() && changed_flags.size() != n) fail("changed_flags size differs from requests (and is not empty)");
    if (!changed_indices.empty() && changed_indices.size() < n) fail("changed_indices has room for fewer than n indices");
    if (!(dt >= 0.0f) || !std::isfinite(dt)) fail("dt must be finite and >= 0 (got " + std::to_string(dt) + ")");
    return ok;
}


size_t LodResolveJob::Run() const {
    const RuleTable& t = *table;
    const uint8_t last_geom = static_cast<uint8_t>(t.geom_levels.size() - 1);
    const uint8_t last_anim = static_cast<uint8_t>(t.anim_levels.size() - 1);
    size_t changed = 0;
    for (size_t i = 0; i < requests.size(); ++i) {
        const LodRequest& req = requests[i];
        LodState s = states[i];
        s.geom_level = std::min(s.geom_level, last_geom);
        s.anim_level = std::min(s.anim_level, last_anim);
        s.geom_wanted = std::min(s.geom_wanted, last_geom);
        s.prev_geom_level = std::min(s.prev_geom_level, last_geom);
        s.prev_anim_level = std::min(s.prev_anim_level, last_anim);
        s.cap_geom_level = std::min(s.cap_geom_level, last_geom);
        s.cap_anim_level = std::min(s.cap_anim_level, last_anim);
        s.seconds_at_geom = advance(s.seconds_at_geom, dt);
        s.seconds_at_anim = advance(s.seconds_at_anim, dt);
        s.geomorph_left_s = run_down(s.geomorph_left_s, dt);
        s.crossfade_left_s = run_down(s.crossfade_left_s, dt);

        const LodTargets target = lod_targets(t, req, s);
        const uint8_t target_geom = target.geom;
        const uint8_t target_anim = target.anim;
        bool level_changed = false;
        // Over a cap: leave at once, whatever the time hysteresis says.
        // A level with enter_after_s is entered only once it was asked for that long without a break.
        s.seconds_geom_wanted = std::min(seconds_wanted(s, target_geom, dt), kHeldCap);
        s.geom_wanted = target_geom;
        const bool geom_free = snap || ((held_long_enough(t, s.seconds_at_geom) || t.geom_levels[s.geom_level].method == GeomMethod::Hidden ||
                                         s.geom_level < s.cap_geom_level) &&
                                        wanted_long_enough(t, target_geom, s.seconds_geom_wanted));
        const bool anim_free = snap || held_long_enough(t, s.seconds_at_anim) || s.anim_level < s.cap_anim_level;
        if (target_geom != s.geom_level && geom_free) {
            s.prev_geom_level = snap ? target_geom : s.geom_level;
            s.geom_level = target_geom;
            s.geomorph_left_s = snap ? 0.0f : t.geom_levels[target_geom].geomorph_s;
            s.seconds_at_geom = 0.0f;
            level_changed = true;
            if (switch_counts) ++switch_counts[0];
        }
        if (target_anim != s.anim_level && anim_free) {
            s.prev_anim_level = snap ? target_anim : s.anim_level;
            s.anim_level = target_anim;
            s.crossfade_left_s = snap ? 0.0f : t.anim_levels[target_anim].crossfade_s;
            s.seconds_at_anim = 0.0f;
            level_changed = true;
            if (switch_counts) ++switch_counts[1];
        }
        if (s.geom_level == target_geom && s.anim_level == target_anim) s.rule_id = req.rule_id;
        states[i] = s;
        geom[i] = t.geom_lod(s.geom_level);
        anim[i] = t.anim_lod(s.anim_level);
        if (!changed_flags.empty()) changed_flags[i] = level_changed ? 1 : 0;
        if (level_changed) {
            if (!changed_indices.empty()) changed_indices[changed] = index_base + static_cast<uint32_t>(i);
            ++changed;
        }
    }
    return changed;
}

void clamp_lod_states(const RuleTable& table, std::span<LodState> states) {
    const uint8_t last_geom = static_cast<uint8_t>(table.geom_levels.size() - 1);
    const uint8_t last_anim = static_cast<uint8_t>(table.anim_levels.size() - 1);
    const uint16_t last_rule = static_cast<uint16_t>(table.rules.size() - 1);
    for (LodState& s : states) {
        s.geom_level = std::min(s.geom_level, last_geom);
        s.anim_level = std::min(s.anim_level, last_anim);
        s.geom_wanted = std::min(s.geom_wanted, last_geom);
        s.prev_geom_level = std::min(s.prev_geom_level, last_geom);
        s.prev_anim_level = std::min(s.prev_anim_level, last_anim);
        s.rule_id = std::min(s.rule_id, last_rule);
        s.cap_geom_level = std::min(s.cap_geom_level, last_geom);
        s.cap_anim_level = std::min(s.cap_anim_level, last_anim);
    }
}

}  // namespace aloha
