// The single-total frame-budget controller (a rule file's budget with one `target_ms`): keeps the
// measured CPU time of the systems under a target by demoting the least significant characters one
// level (geometric and animation together) at a time, and promoting the most significant demoted
// ones back when there is room. Anti-oscillation: EMA smoothing, a deadband between the demote and
// promote thresholds, proportional steps, and settle frames after every step. The separate
// animation/geometry budgets are PartBudget (part_budget.hpp).
#pragma once

#include "components/lod.hpp"
#include "systems/lod/rule_table.hpp"

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

namespace aloha {

/// The default significance (kDefaultSignificance): 0 when not visible; otherwise
/// projected_height_px * (0.25 + importance) / (1 + eccentricity^2): small, peripheral, unimportant
/// characters score lowest. Rule files may define their own (RuleTable::significance).
[[nodiscard]] float noticeability(const LodAttributes& a);

/// What one FrameBudget::update did.
struct BudgetStep {
    int direction = 0;        ///< -1 demoted, +1 promoted, 0 nothing
    uint32_t changed = 0;     ///< characters whose budget_demotion changed
    float smoothed_ms = 0.0f; ///< the EMA of the measured time after this update
    float predicted_ms = 0.0f;///< part budgets: the smoothed time plus the pending switches' predicted cost
};

/// Single-total controller. Call update() once per frame before the resolver, with the measured
/// time of the last frame; it edits LodState::budget_demotion and anim_demotion (always equal here),
/// which the resolver applies. Only characters whose levels may switch now (held >=
/// hysteresis.min_seconds) and not `always_full` are touched, so every change takes effect on
/// the same frame.
class FrameBudget {
public:
    /// A controller with `params` (target_ms > 0, smoothing in (0, 1]).
    explicit FrameBudget(const BudgetParams& params = {});
    /// Replaces the parameters (e.g. after a rule reload); keeps the smoothed time.
    void set_params(const BudgetParams& params) { params_ = params; }
    /// The parameters in use.
    [[nodiscard]] const BudgetParams& params() const { return params_; }
    /// Smoothed frame time (ms); negative before the first update.
    [[nodiscard]] float smoothed_ms() const { return ema_; }
    /// Forgets the smoothed time and the settle countdown.
    void reset();

    /// Feeds `measured_ms` (last frame) and, when outside the deadband and settled, demotes or
    /// promotes characters of `states` ranked by the table's significance of `attributes` (same size).
    /// Allocates only when the crowd grows. Requires table levels non-empty.
    BudgetStep update(float measured_ms, std::span<const LodAttributes> attributes, std::span<LodState> states,
                      const RuleTable& table);

private:
    BudgetParams params_;
    float ema_ = -1.0f;
    int settle_left_ = 0;
    std::vector<std::pair<float, uint32_t>> ranked_;  // (score, index) scratch
};

}  // namespace aloha
