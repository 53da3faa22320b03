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

/// Learned milliseconds per character at each level of one kind, apart for each cost class (kinds of
/// work that cost differently at the same level: a walker and a character playing a clip at the
/// same animation level, say). Entries are kept per slot, level * classes() + class.
///
/// Priors come from the level definitions (tessellation, method; walk, IK, update interval) and are
/// scaled by the first measurement. With per-slot times (the World times the geometry loop of each
/// level, and the motion controller each character's pose by its animation level and whether it
/// walks) each slot's average is a moving average of measured ms / characters, and its marginal
/// cost a moving least-squares slope of its time against its count shrunk toward the average (ridge);
/// with only a total, both follow
/// the total by normalised least mean squares (the error spread over the slots in proportion to
/// their counts), never below 1% of their prior.
class LevelCostModel {
public:
    /// Priors for the levels of `kind` in `table`, `classes` cost classes each (animation: 1 or
    /// kAnimCostClasses, class 1 walking; geometry: 1); forgets what was learned when the shape changed.
    void set_levels(BudgetKind kind, const RuleTable& table, size_t classes = 1);
    /// Learns from one frame: `counts[s]` characters in slot s cost `slot_ms[s]` each slot (when
    /// given, same size as counts) or `total_ms` in all. `weight` in (0, 1] is the averaging weight.
    void observe(std::span<const uint32_t> counts, std::span<const double> slot_ms, double total_ms, float weight);
    /// Average ms per character in `slot` (clamped to the last slot).
    [[nodiscard]] double cost(size_t slot) const;
    /// What one character more or fewer in `slot` costs (ms): the slope of the slot's time against
    /// its count, shrunk toward the average as far as the count has varied too little to tell (ridge
    /// regression, see fit_marginal). Steps are planned with it.
    [[nodiscard]] double marginal(size_t slot) const;
    /// Predicted total ms for `counts` (per slot).
    [[nodiscard]] double predict(std::span<const uint32_t> counts) const;
    /// Every slot's average cost (ms per character).
    [[nodiscard]] const std::vector<double>& costs() const { return cost_; }
    /// Every slot's marginal cost (ms per character).
    [[nodiscard]] const std::vector<double>& marginals() const { return marginal_; }
    /// Cost classes per level.
    [[nodiscard]] size_t classes() const { return classes_; }

private:
    struct Fit {  // moving averages of count, time, count^2, count * time
        double n = 0, t = 0, nn = 0, nt = 0;
        bool seen = false;
    };
    void fit_marginal(size_t level, uint32_t count, double ms, float weight);
    std::vector<double> prior_, cost_, marginal_;
    std::vector<Fit> fits_;
    size_t classes_ = 1;
    bool scaled_ = false;
};

}  // namespace aloha
