#include "systems/lod/rule_eval.hpp"

namespace aloha {

bool RuleEvalJob::Validate(std::vector<std::string>* errors) const {
    bool ok = true;
    auto fail = [&](std::string m) {
        ok = false;
        if (errors) errors->push_back("RuleEvalJob: " + std::move(m));
    };
    if (table == nullptr || table->compiled.empty()) fail("needs a loaded rule table with at least one rule");
    if (output.size() != attributes.size()) fail("output size differs from attributes");
    if (!states.empty() && states.size() != attributes.size()) fail("states size differs from attributes (and is not empty)");
    if (table != nullptr && tier >= table->tiers.size()) fail("tier " + std::to_string(tier) + " out of range");
    return ok;
}

namespace {

// True when every slot of v lies in [lo, hi]; written without early exits so it vectorises.
// A NaN value fails (both comparisons are false).
inline bool in_box(const float* v, const float* lo, const float* hi) {
    int fail = 0;
    for (int k = 0; k < kBoxSlots; ++k) fail |= static_cast<int>(!(v[k] >= lo[k])) | static_cast<int>(!(v[k] <= hi[k]));
    return fail == 0;
}

}  // namespace

void RuleEvalJob::Run() const {
    const CompiledRule* rules = table->compiled.data();
    const ConditionBox* boxes = table->boxes.data();
    const uint32_t rule_count = static_cast<uint32_t>(table->compiled.size());
    const uint32_t fallback = rule_count - 1;
    alignas(32) float v[kBoxSlots];
    v[6] = static_cast<float>(tier);
    for (size_t i = 0; i < attributes.size(); ++i) {
        const LodAttributes& a = attributes[i];
        v[0] = a.distance;
        v[1] = a.projected_height_px;
        v[2] = a.eccentricity;
        v[3] = a.speed;
        v[4] = static_cast<float>(a.visible);
        v[5] = a.importance;
        v[7] = a.occluded;
        const uint32_t current = states.empty() ? 0xFFFFFFFFu : states[i].rule_id;
        uint32_t fired = fallback;
        for (uint32_t r = 0; r < fallback; ++r) {
            const CompiledRule& rule = rules[r];
            const bool wide = r == current;
            bool hit = false;
            for (uint32_t b = 0; b < rule.box_count; ++b) {
                const ConditionBox& box = boxes[rule.first_box + b];
                hit |= wide ? in_box(v, box.lo_wide.data(), box.hi_wide.data())
                            : in_box(v, box.lo.data(), box.hi.data());
            }
            if (hit) {
                fired = r;
                break;
            }
        }
        LodRequest& out = output[i];
        out.geom_level = rules[fired].geom_level;
        out.anim_level = rules[fired].anim_level;
        out.rule_id = static_cast<uint16_t>(fired);
    }
}

}  // namespace aloha
