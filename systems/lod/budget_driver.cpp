#include "systems/lod/budget_driver.hpp"

namespace aloha {

void LodBudget::configure(const RuleTable& table, const BudgetOverrides& o, std::span<LodState> states) {
    BudgetParams p = table.budget.value_or(BudgetParams{});
    bool on = table.budget.has_value() && p.enabled;
    if (o.total_ms) {
        on = true;
        if (p.has_parts()) {  // keep the file's split, scaled to the asked total
            const double sum = double(p.animation.target_ms) + double(p.geometry.target_ms);
            p.animation.target_ms = static_cast<float>(p.animation.target_ms * *o.total_ms / sum);
            p.geometry.target_ms = static_cast<float>(p.geometry.target_ms * *o.total_ms / sum);
        } else {
            p.target_ms = static_cast<float>(*o.total_ms);
        }
    }
    if (o.animation_ms || o.geometry_ms) {
        on = true;
        if (!p.has_parts()) p.animation.max_demotion = p.geometry.max_demotion = p.max_demotion;
        if (o.animation_ms) p.animation.target_ms = static_cast<float>(*o.animation_ms);
        if (o.geometry_ms) p.geometry.target_ms = static_cast<float>(*o.geometry_ms);
        p.target_ms = 0.0f;
    }
    if (o.single_total_ms) {  // the original controller, for comparison: both kinds of level together
        on = true;
        p.target_ms = static_cast<float>(*o.single_total_ms);
        p.animation.target_ms = p.geometry.target_ms = 0.0f;
    }
    if (o.enabled) on = *o.enabled;
    BudgetStatus::Mode mode = BudgetStatus::Mode::Off;
    if (on && p.has_parts()) mode = BudgetStatus::Mode::Parts;
    else if (on && p.target_ms > 0.0f) mode = BudgetStatus::Mode::Total;
    if (mode != mode_) {
        for (LodState& s : states) s.budget_demotion = s.anim_demotion = 0;
        total_.reset();
        animation_.reset();
        geometry_.reset();
    } else if (mode == BudgetStatus::Mode::Parts) {  // a part that lost its target gives its levels back
        for (LodState& s : states) {
            if (p.animation.target_ms <= 0.0f) s.anim_demotion = 0;
            if (p.geometry.target_ms <= 0.0f) s.budget_demotion = 0;
        }
    }
    mode_ = mode;
    params_ = p;
    total_.set_params(p);
    animation_.set_params(p.animation, p);
    geometry_.set_params(p.geometry, p);
}

void LodBudget::update(const BudgetMeasurement& m, std::span<const LodAttributes> attributes,
                       std::span<const LodRequest> requests, std::span<LodState> states, const RuleTable& table) {
    if (mode_ == BudgetStatus::Mode::Total) {
        total_.update(m.total_ms, attributes, states, table);
    } else if (mode_ == BudgetStatus::Mode::Parts) {
        if (params_.animation.target_ms > 0.0f)
            animation_.update(m.animation_ms, m.animation_level_ms, attributes, requests, states, table, m.animation_classes);
        if (params_.geometry.target_ms > 0.0f)
            geometry_.update(m.geometry_ms, m.geometry_level_ms, attributes, requests, states, table);
    }
}

BudgetStatus LodBudget::status() const {
    BudgetStatus s;
    s.mode = mode_;
    s.params = params_;
    s.total_smoothed_ms = total_.smoothed_ms();
    auto part = [](const PartBudget& b) {
        BudgetStatus::Part p;
        p.active = b.params().target_ms > 0.0f;
        p.target_ms = b.params().target_ms;
        p.smoothed_ms = b.smoothed_ms();
        p.band_ms = b.band_ms();
        p.trigger_band_ms = b.trigger_band_ms();
        p.noise_sigma_ms = static_cast<float>(b.sigma_ms());
        p.level_cost_ms = b.costs().costs();
        p.level_marginal_ms = b.costs().marginals();
        p.classes = b.costs().classes();
        return p;
    };
    if (mode_ == BudgetStatus::Mode::Parts) s.animation = part(animation_), s.geometry = part(geometry_);
    return s;
}

}  // namespace aloha
