// What each level of detail costs, learned online from measured times: the average per character and
// the marginal cost (the slope of a level's time against how many characters are at it), which the
// part budgets (part_budget.hpp) use to predict the effect of a step before taking it.
#pragma once

#include "systems/lod/rule_table.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace aloha {

/// Which kind of level a part budget removes.
enum class BudgetKind : uint8_t { Animation, Geometry };

/// Learned milliseconds per character at each level of one kind.
///
/// Priors come from the level definitions (tessellation, method; walk, IK, update interval) and are
/// scaled by the first measurement. With per-level times (the World times the geometry loop of each
/// level, and the motion controller each character's pose by its animation level) each level's
/// average is a moving average of measured ms / characters, and its marginal cost a moving
/// least-squares slope of its time against its count; with only a total, both follow the total by
/// normalised least mean squares (the error spread over the levels in proportion to their counts),
/// never below 1% of their prior.
class LevelCostModel {
public:
    /// Priors for the levels of `kind` in `table`; forgets what was learned when the level count changed.
    void set_levels(BudgetKind kind, const RuleTable& table);
    /// Learns from one frame: `counts[l]` characters at level l cost `level_ms[l]` each level (when
    /// given, same size as counts) or `total_ms` in all. `weight` in (0, 1] is the averaging weight.
    void observe(std::span<const uint32_t> counts, std::span<const double> level_ms, double total_ms, float weight);
    /// Average ms per character at `level` (clamped to the last level).
    [[nodiscard]] double cost(size_t level) const;
    /// What one character more or fewer at `level` costs (ms): the slope of the level's time against
    /// its count, learned as counts change (the average until then). Steps are planned with it.
    [[nodiscard]] double marginal(size_t level) const;
    /// Predicted total ms for `counts`.
    [[nodiscard]] double predict(std::span<const uint32_t> counts) const;
    /// Every level's average cost (ms per character).
    [[nodiscard]] const std::vector<double>& costs() const { return cost_; }
    /// Every level's marginal cost (ms per character).
    [[nodiscard]] const std::vector<double>& marginals() const { return marginal_; }

private:
    struct Fit {  // moving averages of count, time, count^2, count * time
        double n = 0, t = 0, nn = 0, nt = 0;
        bool seen = false, fitted = false;
    };
    void fit_marginal(size_t level, uint32_t count, double ms, float weight);
    std::vector<double> prior_, cost_, marginal_;
    std::vector<Fit> fits_;
    bool scaled_ = false;
};

}  // namespace aloha
