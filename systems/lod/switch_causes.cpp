#include "systems/lod/switch_causes.hpp"

#include "systems/lod/resolver.hpp"

namespace aloha {

void SwitchCauseCounts::add(const SwitchCauseCounts& o) {
    for (size_t k = 0; k < 2; ++k) {
        rules[k] += o.rules[k];
        budget_down[k] += o.budget_down[k];
        budget_up[k] += o.budget_up[k];
        undone[k] += o.undone[k];
    }
}

bool SwitchCauseJob::Validate(std::vector<std::string>* errors) const {
    bool ok = true;
    auto fail = [&](std::string m) {
        ok = false;
        if (errors) errors->push_back("SwitchCauseJob: " + std::move(m));
    };
    if (table == nullptr || table->geom_levels.empty() || table->anim_levels.empty()) fail("needs a loaded rule table with levels");
    if (out == nullptr) fail("needs an output");
    const size_t n = states.size();
    if (requests.size() != n) fail("requests size differs from states");
    if (keys.size() != changed.size()) fail("keys size differs from changed");
    for (uint32_t i : changed)
        if (i >= n) {
            fail("changed index " + std::to_string(i) + " out of range (" + std::to_string(n) + " characters)");
            break;
        }
    for (uint32_t k : keys)
        if (k >= records.size()) {
            fail("key " + std::to_string(k) + " out of range (" + std::to_string(records.size()) + " records)");
            break;
        }
    return ok;
}

void SwitchCauseJob::Run() const {
    const RuleTable& t = *table;
    for (size_t c = 0; c < changed.size(); ++c) {
        const uint32_t i = changed[c];
        const LodState& s = states[i];
        SwitchRecord& r = records[keys[c]];
        const uint8_t demotion[2] = {s.budget_demotion, s.anim_demotion};
        const bool switched[2] = {s.seconds_at_geom == 0.0f, s.seconds_at_anim == 0.0f};
        // Where the character would have gone with the demotions of its last switches.
        LodState before = s;
        before.budget_demotion = r.demotion[0];
        before.anim_demotion = r.demotion[1];
        const LodTargets then = lod_targets(t, requests[i], before);
        const uint8_t level[2] = {s.geom_level, s.anim_level};
        const uint8_t level_then[2] = {then.geom, then.anim};
        for (size_t k = 0; k < 2; ++k) {
            if (!switched[k]) continue;
            if (level[k] == level_then[k]) {
                ++out->rules[k];
            } else {
                const int8_t way = demotion[k] > r.demotion[k] ? 1 : -1;
                ++(way > 0 ? out->budget_down[k] : out->budget_up[k]);
                if (r.last_budget_way[k] == -way && frame - r.last_budget_frame[k] <= undo_frames) ++out->undone[k];
                r.last_budget_way[k] = way;
                r.last_budget_frame[k] = frame;
            }
            r.demotion[k] = demotion[k];
        }
    }
}

}  // namespace aloha
