#include "systems/lod/resolver.hpp"

#include <algorithm>

namespace aloha {

uint8_t demoted_geom_level(const RuleTable& table, uint8_t requested, uint8_t demotion) {
    const int last = static_cast<int>(table.geom_levels.size()) - 1;
    const int req = std::min<int>(requested, last);
    if (table.geom_levels[req].method == GeomMethod::Hidden) return static_cast<uint8_t>(req);
    int target = std::min(req + demotion, last);
    while (target > req && table.geom_levels[target].method == GeomMethod::Hidden) --target;
    return static_cast<uint8_t>(target);
}

uint8_t demoted_anim_level(const RuleTable& table, uint8_t requested, uint8_t demotion) {
    const int last = static_cast<int>(table.anim_levels.size()) - 1;
    return static_cast<uint8_t>(std::min(requested + demotion, last));
}

LodTargets lod_targets(const RuleTable& table, const LodRequest& request, const LodState& state) {
    LodTargets t;
    t.geom = demoted_geom_level(table, request.geom_level, state.budget_demotion);
    t.anim = demoted_anim_level(table, request.anim_level, state.anim_demotion);
    const uint8_t cap_geom = std::min<uint8_t>(state.cap_geom_level, static_cast<uint8_t>(table.geom_levels.size() - 1));
    if (cap_geom > t.geom && table.geom_levels[t.geom].method != GeomMethod::Hidden) t.geom = cap_geom;
    t.anim = std::max(t.anim, std::min<uint8_t>(state.cap_anim_level, static_cast<uint8_t>(table.anim_levels.size() - 1)));
    return t;
}

LodTargets uncapped_outcome(const RuleTable& table, const LodRequest& request, const LodState& state, bool snap) {
    LodState uncapped = state;
    uncapped.cap_geom_level = uncapped.cap_anim_level = 0;
    const LodTargets target = lod_targets(table, request, uncapped);
    const uint8_t geom = std::min<uint8_t>(state.geom_level, static_cast<uint8_t>(table.geom_levels.size() - 1));
    const uint8_t anim = std::min<uint8_t>(state.anim_level, static_cast<uint8_t>(table.anim_levels.size() - 1));
    // Timers advance before the resolver compares them, hence + 1.
    const uint32_t need = table.hysteresis.min_frames;
    const bool geom_free = snap || state.frames_at_geom + 1u >= need || table.geom_levels[geom].method == GeomMethod::Hidden;
    const bool anim_free = snap || state.frames_at_anim + 1u >= need;
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
    return ok;
}

namespace {
inline uint16_t inc_sat(uint16_t v) { return v == 0xFFFF ? v : static_cast<uint16_t>(v + 1); }
inline uint16_t dec_zero(uint16_t v) { return v == 0 ? 0 : static_cast<uint16_t>(v - 1); }
}  // namespace

size_t LodResolveJob::Run() const {
    const RuleTable& t = *table;
    const uint8_t last_geom = static_cast<uint8_t>(t.geom_levels.size() - 1);
    const uint8_t last_anim = static_cast<uint8_t>(t.anim_levels.size() - 1);
    const uint16_t min_frames = t.hysteresis.min_frames;
    size_t changed = 0;
    for (size_t i = 0; i < requests.size(); ++i) {
        const LodRequest& req = requests[i];
        LodState s = states[i];
        s.geom_level = std::min(s.geom_level, last_geom);
        s.anim_level = std::min(s.anim_level, last_anim);
        s.prev_geom_level = std::min(s.prev_geom_level, last_geom);
        s.prev_anim_level = std::min(s.prev_anim_level, last_anim);
        s.cap_geom_level = std::min(s.cap_geom_level, last_geom);
        s.cap_anim_level = std::min(s.cap_anim_level, last_anim);
        s.frames_at_geom = inc_sat(s.frames_at_geom);
        s.frames_at_anim = inc_sat(s.frames_at_anim);
        s.geomorph_left = dec_zero(s.geomorph_left);
        s.crossfade_left = dec_zero(s.crossfade_left);

        const LodTargets target = lod_targets(t, req, s);
        const uint8_t target_geom = target.geom;
        const uint8_t target_anim = target.anim;
        bool level_changed = false;
        // Over a cap: leave at once, whatever the time hysteresis says.
        const bool geom_free = snap || s.frames_at_geom >= min_frames ||
                               t.geom_levels[s.geom_level].method == GeomMethod::Hidden || s.geom_level < s.cap_geom_level;
        const bool anim_free = snap || s.frames_at_anim >= min_frames || s.anim_level < s.cap_anim_level;
        if (target_geom != s.geom_level && geom_free) {
            s.prev_geom_level = snap ? target_geom : s.geom_level;
            s.geom_level = target_geom;
            s.geomorph_left = snap ? 0 : t.geom_levels[target_geom].geomorph_frames;
            s.frames_at_geom = 0;
            level_changed = true;
            if (switch_counts) ++switch_counts[0];
        }
        if (target_anim != s.anim_level && anim_free) {
            s.prev_anim_level = snap ? target_anim : s.anim_level;
            s.anim_level = target_anim;
            s.crossfade_left = snap ? 0 : t.anim_levels[target_anim].crossfade_frames;
            s.frames_at_anim = 0;
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
        s.prev_geom_level = std::min(s.prev_geom_level, last_geom);
        s.prev_anim_level = std::min(s.prev_anim_level, last_anim);
        s.rule_id = std::min(s.rule_id, last_rule);
        s.cap_geom_level = std::min(s.cap_geom_level, last_geom);
        s.cap_anim_level = std::min(s.cap_anim_level, last_anim);
    }
}

}  // namespace aloha
