#include "systems/lod/frame_budget.hpp"

#include "systems/lod/resolver.hpp"

#include <algorithm>
#include <cmath>

namespace aloha {

float noticeability(const LodAttributes& a) {
    static const SignificanceExpr kDefault;
    return kDefault.evaluate(a);
}

FrameBudget::FrameBudget(const BudgetParams& params) : params_(params) {}

void FrameBudget::reset() {
    ema_ = -1.0f;
    settle_left_ = 0;
}

BudgetStep FrameBudget::update(float measured_ms, std::span<const LodAttributes> attributes,
                               std::span<LodState> states, const RuleTable& table) {
    BudgetStep step;
    if (std::isfinite(measured_ms) && measured_ms >= 0.0f) {
        ema_ = ema_ < 0.0f ? measured_ms : ema_ + params_.smoothing * (measured_ms - ema_);
    }
    step.smoothed_ms = ema_;
    if (ema_ < 0.0f || attributes.size() != states.size()) return step;
    if (settle_left_ > 0) {
        --settle_left_;
        return step;
    }
    const float target = params_.target_ms;
    const bool over = ema_ > target;
    const bool room = ema_ < target * (1.0f - params_.deadband);
    if (!over && !room) return step;

    const uint8_t last_anim = static_cast<uint8_t>(table.anim_levels.size() - 1);
    ranked_.clear();
    uint32_t active = 0;
    for (size_t i = 0; i < states.size(); ++i) {
        const LodState& s = states[i];
        const bool hidden = table.geom_levels[std::min<size_t>(s.geom_level, table.geom_levels.size() - 1)].method ==
                            GeomMethod::Hidden;
        active += hidden ? 0u : 1u;
        const bool settled = held_long_enough(table, s.seconds_at_geom) && held_long_enough(table, s.seconds_at_anim);
        if (!settled || hidden || s.always_full) continue;
        if (over) {
            const bool can_go_lower =
                demoted_geom_level(table, s.geom_level, 1) != s.geom_level || s.anim_level < last_anim;
            if (s.budget_demotion < params_.max_demotion && can_go_lower)
                ranked_.emplace_back(table.significance.evaluate(attributes[i]), static_cast<uint32_t>(i));
        } else if (s.budget_demotion > 0) {
            // Promote the most significant first: rank by negated score.
            ranked_.emplace_back(-table.significance.evaluate(attributes[i]), static_cast<uint32_t>(i));
        }
    }
    if (ranked_.empty()) return step;
    // Proportional step: the relative overshoot (or headroom) times the gain, of the active crowd
    // (demotion) or of the demoted characters (promotion); at least one character.
    const float fraction = over ? params_.demote_gain * (ema_ - target) / ema_
                                : params_.promote_gain * (target * (1.0f - params_.deadband) - ema_) / target;
    const float base = over ? static_cast<float>(active) : static_cast<float>(ranked_.size());
    const size_t k = std::min(ranked_.size(), static_cast<size_t>(std::max(1.0f, std::ceil(fraction * base))));
    std::nth_element(ranked_.begin(), ranked_.begin() + static_cast<std::ptrdiff_t>(k - 1), ranked_.end());
    for (size_t j = 0; j < k; ++j) {
        LodState& s = states[ranked_[j].second];
        s.budget_demotion = static_cast<uint8_t>(over ? s.budget_demotion + 1 : s.budget_demotion - 1);
        s.anim_demotion = s.budget_demotion;
    }
    settle_left_ = params_.settle_frames;
    step.direction = over ? -1 : 1;
    step.changed = static_cast<uint32_t>(k);
    return step;
}

}  // namespace aloha
