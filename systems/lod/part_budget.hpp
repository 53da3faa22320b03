// Separate frame budgets for animation and geometry. Each part steers on its own measured time (the
// motion system; the muscle + spring_skin systems) with per-level costs learned online, so a step
// demotes (or promotes) just enough characters to close the predicted gap: it converges in a few
// frames and, inside a tolerance band around the target, leaves everyone alone.
#pragma once

#include "components/lod.hpp"
#include "systems/lod/budget_noise.hpp"
#include "systems/lod/frame_budget.hpp"
#include "systems/lod/level_cost.hpp"
#include "systems/lod/rule_table.hpp"

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

namespace aloha {

/// Updates a coarse step of `step_ms` (more than `band_ms`) holds coarse steps the other way:
/// ceil(step / band) time constants (1 / smoothing updates each) of the smoothed time; 0 for a step
/// within the band.
[[nodiscard]] int coarse_hold_updates(double step_ms, double band_ms, float smoothing);

/// One part's controller. Call update() once per frame before the resolver with the part's measured
/// time of the last frame; it edits LodState::budget_demotion (geometry) or anim_demotion (animation).
///
/// Each frame:
/// 1. The smoothed time (EMA) is first moved by the predicted effect of the switches since the last
///    update (they are in this measurement in full), then takes the measurement, each frame's
///    deviation clipped to three noise widths so a lone spike cannot trigger a step.
/// 2. Prediction: smoothed time + the predicted cost of pending switches (characters whose resolver
///    target differs from their level, held back by time hysteresis), so the budget acts before an
///    expensive switch lands rather than after.
/// 3. When the prediction is outside target +- band_ms() (the tolerance, widened when measurements
///    are noisier than it, so noise alone never steps) and no settle frames are left, the controller
///    wants to change the time by gain * |target - prediction|. Over: it demotes characters one level,
///    in order of significance per millisecond saved (least first), summing the predicted saving
///    (marginal cost of the level it is headed for - that of one level poorer) until the wanted saving
///    is reached; characters whose demotion would save under 1% of the band are passed over. Under: it
///    promotes demoted characters, most significance per millisecond first, until the wanted extra cost
///    is reached. Steps coarser than the band (one character whose level step costs more: a hero's
///    dynamic walk) are units of their own: a gap that one of them closes by itself (landing inside
///    the band) is closed by it, not by bulk fine steps; otherwise a step that would carry the time
///    beyond the far edge of the band is passed over for finer ones, and only over the band, when
///    those cannot reach the wanted change, is the first passed-over step taken that lands nearer the
///    target by more than the band (its undoing never could, so coarse steps do not oscillate). Under
///    the band with only such coarse promotions left, the finest of them is combined with demotions of
///    others (least significance per millisecond first, each finer than half the band) when together
///    they land inside the band, the shortfall has persisted 3 / smoothing updates and noise has not
///    widened the band (that promotion costed at the level it would really reach: a cap or the last
///    level may swallow it); else the part holds. After any coarse step no coarse step the other way
///    is taken for coarse_hold_updates(). Then it waits settle_frames.
/// With BudgetParams::confidence k > 0 (the default) the part steers on the mean of its measured time
/// since the time last changed (the slow mean: restarted from the smoothed time at each step and
/// whenever the smoothed time leaves it by more than k standard errors of their difference; between,
/// the plain mean of every frame, moved by the predicted effect of each switch like the smoothed time)
/// and steps only when that mean (+ pending) is outside target +- target * tolerance by more than k of
/// its standard errors, sigma_ms() * sqrt(its variance factor): stationary noise then makes a false step
/// with probability under that of a normal beyond k, less and less often as the mean gathers frames.
/// Steps are composed (3. above) against band_ms() as without. While the smoothed time (+ pending) is
/// beyond target * (1 +- react_tolerance) it is answered at once with the band test (a crowd that
/// doubled; noise so wide that k standard errors would hold the part far off), the slow mean
/// restarting from it. Otherwise (k = 0) the band test above.
/// With BudgetParams::dwell > 0 a step waits until the prediction has been outside the band on the
/// same side for dwell_updates() updates in a row (counted through the settle frames), however large.
/// With BudgetParams::trim_smoothing > 0 a slow average steers steps 3 and after whenever the fast
/// one is within target * (1 +- react_tolerance) (the fast one beyond it, restarting the slow one
/// from itself): swings faster than the slow window are left alone, the mean is still held.
/// Only characters not `always_full`, not headed for Hidden, and either held min_seconds at their level
/// or with a switch pending are touched; at most max_demotion levels each.
class PartBudget {
public:
    /// A controller for `kind` with `part` and the section-wide `common` settings.
    PartBudget(BudgetKind kind, const BudgetPartParams& part, const BudgetParams& common);
    /// Replaces the settings (after a reload or an override); keeps the smoothed time and the costs.
    void set_params(const BudgetPartParams& part, const BudgetParams& common);
    /// The part's settings in use.
    [[nodiscard]] const BudgetPartParams& params() const { return part_; }
    /// Which kind of level it removes.
    [[nodiscard]] BudgetKind kind() const { return kind_; }
    /// Smoothed measured time (ms); negative before the first update.
    [[nodiscard]] float smoothed_ms() const { return ema_; }
    /// Mean absolute deviation of single measurements from the smoothed time (ms), a running average.
    [[nodiscard]] float noise_ms() const { return noise_; }
    /// Half-width of the band around the target inside which no step is taken (ms): target *
    /// tolerance, or twice the noise left in the smoothed time when that is larger.
    [[nodiscard]] float band_ms() const;
    /// Half-width of the trimming band (trim_smoothing > 0): target * tolerance, or twice the noise
    /// left in the slow average when that is larger.
    [[nodiscard]] float trim_band_ms() const;
    /// Long-run standard deviation of one frame's measured time (ms): from batch means (BudgetNoise,
    /// batches of ceil(1 / smoothing) frames, averaged with weight 0.04: to 10%) once 25 batch
    /// differences are in, before that the larger of it and the spread of single frames (1.25 * noise_ms());
    /// with confidence 0 (no batches kept) the latter.
    [[nodiscard]] double sigma_ms() const;
    /// The slow mean (confidence > 0): the mean of the measured time since it last changed (ms).
    [[nodiscard]] const TrackedMean& slow_mean() const { return slow_; }
    /// Half-width around the target inside which no step is taken now: with confidence k > 0,
    /// target * tolerance + k * sigma_ms() * sqrt(the slow mean's variance factor); else band_ms().
    [[nodiscard]] float trigger_band_ms() const;
    /// Slow (trim) average of the measured time (ms); negative before the first update.
    [[nodiscard]] float trim_ms() const { return trim_; }
    /// Updates in a row the prediction must stay outside the band on one side before a step (dwell):
    /// ceil(dwell / smoothing), 0 when off.
    [[nodiscard]] int dwell_updates() const;
    /// The learned per-level costs.
    [[nodiscard]] const LevelCostModel& costs() const { return model_; }
    /// Forgets the smoothed time, the settle countdown and the learned costs.
    void reset();

    /// Feeds the last frame's `measured_ms` (and, when available, `level_ms`: the time spent at each
    /// level of this kind and cost class, size = level count * classes) and steps when needed.
    /// `attributes` and `states` have the same size; `requests` (the last frame's, same size) enables
    /// the prediction of pending switches, empty disables it. `cost_classes` (animation only, same
    /// size, 1 = walking) makes the part learn and predict walkers' and other characters' costs apart
    /// at each level (kAnimCostClasses; level_ms then per anim_cost_slot); empty: one class. Allocates
    /// only when the crowd or the level count grows.
    BudgetStep update(float measured_ms, std::span<const double> level_ms, std::span<const LodAttributes> attributes,
                      std::span<const LodRequest> requests, std::span<LodState> states, const RuleTable& table,
                      std::span<const uint8_t> cost_classes = {});

private:
    BudgetKind kind_;
    BudgetPartParams part_;
    BudgetParams common_;
    LevelCostModel model_;
    float ema_ = -1.0f;
    float trim_ = -1.0f;                              // slow average (trim_smoothing), same adjustments as ema_
    float noise_ = 0.0f;
    double ema_factor_ = 0.0;                         // variance of ema_ / one frame's (white noise)
    TrackedMean slow_;                                // confidence > 0: the mean since the time last changed
    BudgetNoise stats_;                               // long-run noise of the measured time
    int settle_left_ = 0;
    int outside_ = 0;                                 // updates in a row the prediction was outside the band: > 0 over, < 0 under
    int held_under_ = 0;                              // updates in a row held under the band with only coarse promotions
    int hold_demote_ = 0;                             // updates left of a coarse promotion's hold on demotions
    int hold_promote_ = 0;                            // updates left of a coarse demotion's hold on promotions
    double held_demote_ms_ = 0.0;                     // that promotion's size (ms): a larger excess is not held
    double held_promote_ms_ = 0.0;                    // that demotion's size (ms): a larger shortfall is not held
    size_t levels_ = 0;
    std::vector<uint32_t> counts_;
    std::vector<uint8_t> last_level_;                 // each character's level at the last update
    std::vector<std::pair<float, uint32_t>> ranked_;  // (score, index) scratch
    std::vector<std::pair<float, uint32_t>> demotable_;  // (score, index) of demotions to combine with (scratch)
    std::vector<uint32_t> passed_;                    // candidates passed over as too coarse (scratch)
    std::vector<uint32_t> chosen_;                    // the step's characters, in the step's direction (scratch)
    std::vector<uint32_t> demoted_;                   // demotions combined with a coarse promotion (scratch)
};

}  // namespace aloha
