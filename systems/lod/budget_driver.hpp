// The frame budget as a host runs it: the rule file's "budget" section (plus command-line style
// overrides) decides between no budget, the single-total controller (FrameBudget) and separate
// animation and geometry controllers (PartBudget); configure() again after a rule reload applies the
// new settings while keeping what the controllers learned.
#pragma once

#include "components/lod.hpp"
#include "systems/lod/frame_budget.hpp"
#include "systems/lod/part_budget.hpp"
#include "systems/lod/rule_table.hpp"

#include <optional>
#include <span>
#include <vector>

namespace aloha {

/// Host overrides of a rule file's budget (each absent: as the file says).
struct BudgetOverrides {
    std::optional<bool> enabled;          ///< force the budget on or off
    std::optional<double> total_ms;       ///< total CPU budget: the file's parts scaled to sum to it, or one total
    std::optional<double> single_total_ms;///< one total for the single-total controller, whatever the file says
    std::optional<double> animation_ms;   ///< the animation part's target
    std::optional<double> geometry_ms;    ///< the geometry part's target
};

/// What the frame budget is doing.
struct BudgetStatus {
    enum class Mode : uint8_t { Off, Total, Parts } mode = Mode::Off;  ///< no budget, one total, separate parts
    BudgetParams params;                  ///< the settings in use (rule file + overrides)
    float total_smoothed_ms = -1.0f;      ///< Total: the controller's smoothed CPU time
    /// One part (Parts mode): its target, its smoothed time and its learned costs.
    struct Part {
        bool active = false;              ///< the part has a target
        float target_ms = 0.0f;           ///< what it steers to
        float smoothed_ms = -1.0f;        ///< its smoothed measured time
        float band_ms = 0.0f;             ///< no step while the smoothed time is within target +- this
        float trigger_band_ms = 0.0f;     ///< no step while the time it steers on is within target +- this
        float noise_sigma_ms = 0.0f;      ///< long-run standard deviation of one frame's measured time
        std::vector<double> level_cost_ms;///< learned ms per character per level (average)
        std::vector<double> level_marginal_ms;  ///< learned ms of one character more per level (slope)
        size_t classes = 1;               ///< cost classes per level: entries are level * classes + class
    };
    Part animation;                       ///< the motion system
    Part geometry;                        ///< the muscle + spring_skin systems
};

/// The last frame's measured times the controllers steer on.
struct BudgetMeasurement {
    float total_ms = -1.0f;                   ///< every CPU system (single total)
    float animation_ms = -1.0f;               ///< the animation part
    float geometry_ms = -1.0f;                ///< the geometry part
    std::span<const double> geometry_level_ms;///< the geometry part's time per geometric level, or empty
    /// The animation part's time per animation level and cost class (anim_cost_slot), or empty.
    std::span<const double> animation_level_ms;
    /// Each character's animation cost class (0: not walking, 1: walking), the size of the crowd, or
    /// empty (every character class 0).
    std::span<const uint8_t> animation_classes;
};

/// Owns the controllers and their mode.
class LodBudget {
public:
    /// Applies `table`'s budget with `overrides`. When the budget turns off or changes mode, every
    /// character's budget demotion in `states` is cleared (they return to their rule levels); the
    /// controllers' smoothed times and learned costs are kept while the mode stays.
    void configure(const RuleTable& table, const BudgetOverrides& overrides, std::span<LodState> states);
    /// Steps the active controllers with the last frame's `m`. `attributes`, `requests` (the last
    /// frame's rule requests, or empty) and `states` have equal size.
    void update(const BudgetMeasurement& m, std::span<const LodAttributes> attributes,
                std::span<const LodRequest> requests, std::span<LodState> states, const RuleTable& table);
    /// Mode, settings and controller state.
    [[nodiscard]] BudgetStatus status() const;
    /// True when a controller runs.
    [[nodiscard]] bool active() const { return mode_ != BudgetStatus::Mode::Off; }

private:
    BudgetStatus::Mode mode_ = BudgetStatus::Mode::Off;
    BudgetParams params_;
    FrameBudget total_;
    PartBudget animation_{BudgetKind::Animation, {}, {}};
    PartBudget geometry_{BudgetKind::Geometry, {}, {}};
};

}  // namespace aloha
