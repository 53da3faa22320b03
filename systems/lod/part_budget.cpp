#include "systems/lod/part_budget.hpp"

#include "systems/lod/resolver.hpp"

#include <algorithm>
#include <cmath>

namespace aloha {

float PartBudget::band_ms() const {
    // Gaussian noise of deviation s has mean absolute deviation 0.8 s, and an EMA of weight a has
    // deviation s * sqrt(a / (2 - a)); two of those keep noise from triggering steps.
    const float a = common_.smoothing;
    const float smoothed_noise = 1.25f * noise_ * std::sqrt(a / (2.0f - a));
    return std::max(part_.tolerance * part_.target_ms, 2.0f * smoothed_noise);
}

float PartBudget::trim_band_ms() const {
    // As band_ms(), for the noise left in the slow average.
    const float a = common_.trim_smoothing;
    const float smoothed_noise = a > 0.0f ? 1.25f * noise_ * std::sqrt(a / (2.0f - a)) : 0.0f;
    return std::max(part_.tolerance * part_.target_ms, 2.0f * smoothed_noise);
}

namespace {
// Weight of the noise variance's average over batch differences: an average of weight w of squared
// normal deviates has relative deviation sqrt(2 w / (2 - w)), its square root half that; 0.04 gives
// sigma_ms() to 10%, so k = 3 standard errors are 2.7-3.3 of the real ones.
constexpr double kNoiseWeight = 0.04;
}  // namespace

double PartBudget::sigma_ms() const {
    // Before the batch estimate has its own time constant of differences it may be a few lucky squares:
    // the spread of single frames (mean absolute deviation 0.8 s for Gaussian noise) bounds it from below.
    const int enough = static_cast<int>(std::ceil(1.0 / kNoiseWeight));
    const double white = 1.25 * noise_;
    return stats_.samples() >= enough ? stats_.sigma() : std::max(stats_.sigma(), white);
}

float PartBudget::trigger_band_ms() const {
    if (!(common_.confidence > 0.0f)) return band_ms();
    const double factor = slow_.empty() ? 1.0 : slow_.factor;
    return static_cast<float>(part_.tolerance * part_.target_ms + common_.confidence * sigma_ms() * std::sqrt(factor));
}

int PartBudget::dwell_updates() const {
    if (!(common_.dwell > 0.0f) || !(common_.smoothing > 0.0f)) return 0;
    return static_cast<int>(std::ceil(common_.dwell / common_.smoothing - 1e-4f));
}

int coarse_hold_updates(double step_ms, double band_ms, float smoothing) {
    // A step k bands coarse moves the smoothed time by k bands; after k of its time constants
    // (1 / smoothing updates each) what is left of it there is k e^-k bands, under one band for every
    // k (k e^-k <= 1/e): the time then shows where the step put it, and a step twice as coarse holds
    // twice as long.
    if (!(band_ms > 0.0) || !(step_ms > band_ms) || !(smoothing > 0.0f)) return 0;
    const double k = std::ceil(std::min(step_ms / band_ms, 1000.0));
    return static_cast<int>(k * std::ceil(1.0 / smoothing));
}

PartBudget::PartBudget(BudgetKind kind, const BudgetPartParams& part, const BudgetParams& common)
    : kind_(kind), part_(part), common_(common) {}

void PartBudget::set_params(const BudgetPartParams& part, const BudgetParams& common) {
    part_ = part;
    common_ = common;
}

void PartBudget::reset() {
    ema_ = trim_ = -1.0f;
    noise_ = 0.0f;
    ema_factor_ = 0.0;
    slow_ = TrackedMean();
    stats_.reset();
    settle_left_ = 0;
    held_under_ = 0;
    outside_ = 0;
    hold_demote_ = hold_promote_ = 0;
    held_demote_ms_ = held_promote_ms_ = 0.0;
    levels_ = 0;
    model_ = LevelCostModel();
}

BudgetStep PartBudget::update(float measured_ms, std::span<const double> level_ms,
                              std::span<const LodAttributes> attributes, std::span<const LodRequest> requests,
                              std::span<LodState> states, const RuleTable& table, std::span<const uint8_t> cost_classes) {
    BudgetStep step;
    hold_demote_ = std::max(0, hold_demote_ - 1);
    hold_promote_ = std::max(0, hold_promote_ - 1);
    const bool geometric = kind_ == BudgetKind::Geometry;
    const size_t levels = geometric ? table.geom_levels.size() : table.anim_levels.size();
    // Cost classes: walkers and the rest learn apart at each animation level when the host says which is which.
    const size_t classes = !geometric && cost_classes.size() == states.size() ? kAnimCostClasses : 1;
    if (levels != levels_ || classes != model_.classes())
        model_.set_levels(kind_, table, classes), levels_ = levels, last_level_.clear();
    auto level_of = [&](const LodState& s) -> size_t { return std::min<size_t>(geometric ? s.geom_level : s.anim_level, levels - 1); };
    // The model's slot of character i at level l (its level and cost class).
    auto slot = [&](size_t l, size_t i) { return l * classes + (classes > 1 && cost_classes[i] != 0 ? 1 : 0); };
    // What character i would cost (one more of its class) at level l.
    auto cost_at = [&](size_t l, size_t i) { return model_.marginal(slot(l, i)); };
    counts_.assign(levels * classes, 0);
    for (size_t i = 0; i < states.size(); ++i) ++counts_[slot(level_of(states[i]), i)];

    // Switches since the last update are in this measurement in full but in the average only by its
    // weight: move the average by their predicted effect first, so it does not lag behind them.
    double switched_ms = 0.0;
    const bool same_crowd = last_level_.size() == states.size();
    last_level_.resize(states.size());
    for (size_t i = 0; i < states.size(); ++i) {
        const size_t l = level_of(states[i]);
        if (same_crowd && l != last_level_[i]) switched_ms += cost_at(l, i) - cost_at(last_level_[i], i);
        last_level_[i] = static_cast<uint8_t>(l);
    }
    if (std::isfinite(measured_ms) && measured_ms >= 0.0f) {
        model_.observe(counts_, level_ms, measured_ms, common_.cost_smoothing);
        const float a = common_.smoothing;
        double y = measured_ms;  // this frame as the averages take it
        if (ema_ < 0.0f) {
            ema_ = trim_ = measured_ms;
            ema_factor_ = 1.0;
        } else {
            ema_ = std::max(0.0f, ema_ + static_cast<float>(switched_ms));
            trim_ = std::max(0.0f, trim_ + static_cast<float>(switched_ms));
            slow_.mean += switched_ms;
            stats_.shift(switched_ms);
            // A lone spike (another process took the core) moves the average by at most 3 noise widths:
            // a sustained change still gets through in a few frames, a one-frame outlier cannot trigger a step.
            const float limit = 3.0f * std::max(noise_, part_.tolerance * part_.target_ms);
            const float dev = std::clamp(measured_ms - ema_, -limit, limit);
            // y, what the slow mean and the noise statistics take, stays the measurement itself: over many
            // frames a spike is averaged, and clipping it would hold the slow mean under the true mean (the
            // plaza's geometry part settled 13-16% over target so).
            noise_ += a * (std::fabs(dev) - noise_);
            ema_ += a * dev;
            ema_factor_ = (1.0 - a) * (1.0 - a) * ema_factor_ + double(a) * a;
            trim_ += common_.trim_smoothing * std::clamp(measured_ms - trim_, -limit, limit);
        }
        // The slow mean gathers every frame while the time stays put; when the smoothed time leaves it by
        // more than k standard errors of their difference (taken as independent: an upper bound) the time
        // has moved, and it restarts from the smoothed time.
        if (common_.confidence > 0.0f) {
            stats_.observe(y, static_cast<int>(std::ceil(1.0f / a - 1e-4f)), kNoiseWeight);
            const double apart = common_.confidence * sigma_ms() * std::sqrt(ema_factor_ + slow_.factor);
            if (slow_.empty() || std::fabs(double(ema_) - slow_.mean) > apart) slow_ = {ema_, ema_factor_}, stats_.break_batches();
            else slow_.add_to_mean(y);
        }
    }
    step.smoothed_ms = ema_;
    if (ema_ < 0.0f || attributes.size() != states.size() || part_.target_ms <= 0.0f) return step;

    // Where each character is headed: the level the resolver aims it at (request, demotions, caps).
    // Switches still held back by time hysteresis are not in any measurement yet; their predicted
    // cost is added, so the budget acts before they land instead of after.
    const bool know_requests = requests.size() == states.size();
    auto headed = [&](size_t i) -> size_t {
        if (!know_requests) return level_of(states[i]);
        const LodTargets t = lod_targets(table, requests[i], states[i]);
        return std::min<size_t>(geometric ? t.geom : t.anim, levels - 1);
    };
    double pending_ms = 0.0;
    for (size_t i = 0; know_requests && i < states.size(); ++i)
        pending_ms += cost_at(headed(i), i) - cost_at(level_of(states[i]), i);
    // Two time scales when trimming is on: an error of the fast average beyond the reaction band (a
    // crowd that doubled, a camera cut) is answered from it at once; inside that band the slow average
    // steers, so swings of the measured time faster than its window are not chased.
    const double target = part_.target_ms;
    const double fast = ema_ + pending_ms;
    const bool trimming = common_.trim_smoothing > 0.0f &&
                          std::fabs(fast - target) <= std::max<double>(part_.react_tolerance * target, band_ms());
    // Beyond the reaction band the slow average's history is obsolete (the time moved for real): it
    // restarts from the fast one, so it does not drag the trimming back towards the old level.
    if (!trimming) trim_ = ema_;
    // Confidence: the slow mean steers, and a step needs it outside the tolerance band by k of its
    // standard errors (trigger_band_ms()); steps are composed against band_ms() as without.
    // Beyond the reaction band (react_tolerance, as for trimming: a crowd that doubled, a machine
    // under heavy load whose noise would hold the confidence test off) the smoothed time is answered at
    // once with the band test, and the slow mean restarts from it.
    const bool confident = common_.confidence > 0.0f && !trimming && !slow_.empty();
    const bool react = confident && std::fabs(fast - target) > std::max<double>(part_.react_tolerance * target, band_ms());
    if (react) slow_ = {ema_, ema_factor_}, stats_.break_batches();
    const double predicted = trimming ? trim_ + pending_ms : confident && !react ? slow_.mean + pending_ms : fast;
    const double band = trimming ? trim_band_ms() : band_ms();
    const double trigger = confident && !react ? double(trigger_band_ms()) : band;
    step.predicted_ms = static_cast<float>(predicted);
    // Dwell: how long the prediction has been outside the band on one side, counted every update.
    const int side = std::fabs(predicted - target) <= trigger ? 0 : predicted > target ? 1 : -1;
    outside_ = side == 0 ? 0 : outside_ * side > 0 ? std::clamp(outside_ + side, -(1 << 24), 1 << 24) : side;  // no overflow
    if (settle_left_ > 0) {
        --settle_left_;
        return step;
    }
    if (std::fabs(predicted - target) <= trigger) {
        held_under_ = 0;
        return step;
    }
    // A burst shorter than the dwell is not answered: its end would undo the step. (Not even a large
    // one: a burst of another process is often larger than any reaction band; a real change waits the
    // dwell once.)
    if (std::abs(outside_) < dwell_updates()) return step;
    const bool over = predicted > target;
    const double wanted = part_.gain * std::fabs(predicted - target);  // ms to save (over) or to spend (under)
    // A coarse step the other way is still being taken in (its hold): an error it could explain (its
    // size plus the band) is left alone, by fine steps too; answered in bulk, they would be undone
    // in bulk once the step shows as it is.
    if ((over ? hold_demote_ : hold_promote_) > 0 &&
        std::fabs(predicted - target) <= (over ? held_demote_ms_ : held_promote_ms_) + band)
        return step;

    // Candidates: (significance, index), each judged at the level it is headed for. Characters held
    // by time hysteresis at a level they keep are left alone (a change would not show); one whose
    // switch is pending may be retargeted. A demotion predicted to save under 1% of the band is not
    // worth a visible switch (a hundred of them would not move the time across the band): passed over.
    const double least_saving = 0.01 * band;
    auto one_poorer = [&](size_t l) -> size_t {
        if (!geometric) return std::min(l + 1, levels - 1);
        return demoted_geom_level(table, static_cast<uint8_t>(l), 1);
    };
    auto saving = [&](size_t i) {
        const size_t l = headed(i);
        return cost_at(l, i) - cost_at(one_poorer(l), i);
    };
    auto extra = [&](size_t i) {
        const size_t l = headed(i);
        return std::max(0.0, cost_at(l > 0 ? l - 1 : 0, i) - cost_at(l, i));
    };
    // What giving character i one level back really costs: the level it would then be headed for
    // (through lod_targets, so a cap or a demotion past the last level that swallows the step costs
    // nothing) against the one it is headed for. For the combined step below, which must not pay
    // demotions for a promotion that would not show.
    auto reached_extra = [&](size_t i) {
        const size_t l = headed(i);
        size_t up = l > 0 ? l - 1 : 0;
        if (know_requests) {
            LodState promoted = states[i];
            uint8_t& demotion = geometric ? promoted.budget_demotion : promoted.anim_demotion;
            demotion = static_cast<uint8_t>(demotion > 0 ? demotion - 1 : 0);
            const LodTargets t = lod_targets(table, requests[i], promoted);
            up = std::min<size_t>(geometric ? t.geom : t.anim, levels - 1);
        }
        return std::max(0.0, cost_at(up, i) - cost_at(l, i));
    };
    // Fills `out` with the characters that may be demoted (or promoted) one level, least (most)
    // significance per millisecond first: the least noticed detail for the time it saves goes first,
    // the most noticed for the time it costs comes back first (equal costs: plain significance order).
    auto rank = [&](bool demote, std::vector<std::pair<float, uint32_t>>& out) {
        out.clear();
        for (size_t i = 0; i < states.size(); ++i) {
            const LodState& s = states[i];
            const size_t l = headed(i);
            if (s.always_full || (geometric && table.geom_levels[l].method == GeomMethod::Hidden)) continue;
            if (l == level_of(s) && !held_long_enough(table, geometric ? s.seconds_at_geom : s.seconds_at_anim)) continue;
            const uint8_t demotion = geometric ? s.budget_demotion : s.anim_demotion;
            if (demote ? demotion >= part_.max_demotion || one_poorer(l) == l || saving(i) < least_saving : demotion == 0)
                continue;
            const double significance = std::max(0.0f, table.significance.evaluate(attributes[i]));
            const double ms = std::max(1e-9, demote ? saving(i) : extra(i));
            out.emplace_back(static_cast<float>(demote ? significance / ms : -significance / ms), static_cast<uint32_t>(i));
        }
        std::sort(out.begin(), out.end());
    };
    rank(over, ranked_);
    if (ranked_.empty()) return step;
    // Steps coarser than the band (a hero's dynamic walk, a subdivided body: a few times the band)
    // are units of their own, taken or passed over whole; the fine steps are the rest.
    // 1. A gap that one coarse unit closes by itself is closed by that unit, not by bulk fine steps
    //    that would be undone, in bulk again, when the unit moves back: the first in order that lands
    //    inside the band; over, else the demotion that lands nearest the target, under the band but
    //    nearer than now by more than the band (a hero sent to its dynamic walk by the rules while the
    //    time was just under the band: holding it back returns the time there).
    // 2. Otherwise in order until the wanted change is reached, a step that would carry the time beyond
    //    the far edge of the band passed over for the finer ones after it.
    // 3. Over, when the finer ones cannot reach the wanted change: the first passed-over step that lands
    //    nearer the target by more than the band (its undoing could never satisfy that too). Under, the
    //    only coarse promotion that lands outside the band is the combination below: a lone one would
    //    land over the band and be answered by bulk fine demotions, undone in bulk when it leaves.
    // After a coarse step, steps the other way that it could explain wait for its hold (above).
    const double sign = over ? -1.0 : 1.0;  // the way the time moves
    auto step_ms = [&](size_t i) { return over ? saving(i) : extra(i); };
    auto off_target = [&](double ms) { return predicted + sign * ms - target; };  // after changing by ms
    const double gap = std::fabs(predicted - target);
    double changed_ms = 0.0, coarse_ms = 0.0;  // coarse_ms: the coarsest step taken
    chosen_.clear();
    passed_.clear();
    size_t unit = ranked_.size();
    for (size_t k = 0; gap > band && k < ranked_.size(); ++k) {
        const double ms = step_ms(ranked_[k].second), off = std::fabs(off_target(ms));
        if (ms <= band) continue;
        if (off <= band) {
            unit = k;
            break;
        }
        const bool nearer = over && off + band < gap;
        const bool nearest = unit == ranked_.size() || off < std::fabs(off_target(step_ms(ranked_[unit].second)));
        if (nearer && nearest) unit = k;
    }
    if (unit < ranked_.size()) chosen_.push_back(ranked_[unit].second), changed_ms = coarse_ms = step_ms(ranked_[unit].second);
    const bool one_unit = !chosen_.empty();
    for (size_t k = 0; !one_unit && k < ranked_.size() && changed_ms < wanted; ++k) {
        const uint32_t i = ranked_[k].second;
        const double ms = step_ms(i);
        if (sign * off_target(changed_ms + ms) > band) passed_.push_back(i);
        else chosen_.push_back(i), changed_ms += ms, coarse_ms = std::max(coarse_ms, ms > band ? ms : 0.0);
    }
    const double left = std::fabs(off_target(changed_ms));
    for (size_t k = 0; over && changed_ms < wanted && left > band && k < passed_.size(); ++k) {
        const double ms = step_ms(passed_[k]);
        if (std::fabs(off_target(changed_ms + ms)) + band < left) {
            chosen_.push_back(passed_[k]), changed_ms += ms, coarse_ms = std::max(coarse_ms, ms);
            break;
        }
    }
    // Under the band with only coarse promotions left (each would carry the time past the far edge):
    // the finest of them is combined with demotions of others, least significance per millisecond
    // first, each finer than half the band, that bring the time back to the target. Taken only when
    // it lands inside the band, so the next update holds. Only for a shortfall that persists (held for
    // three time constants of the smoothed time, 3 / smoothing updates) and while the band is the
    // tolerance itself (not widened by noise): under load each passing dip below the band would
    // otherwise trade one coarse promotion for many demotions and back (measured: 2-3 times the
    // level changes).
    demoted_.clear();
    held_under_ = !over && chosen_.empty() ? held_under_ + 1 : 0;
    const bool persistent = static_cast<float>(held_under_) * common_.smoothing >= 3.0f;
    const bool steady = band <= part_.tolerance * part_.target_ms;
    if (!over && persistent && steady && left > band && !passed_.empty()) {
        uint32_t finest = 0;
        double finest_ms = 0.0;  // what it really costs; 0: no passed-over promotion would show
        for (uint32_t i : passed_) {
            const double ms = reached_extra(i);
            if (ms > 0.0 && (finest_ms == 0.0 || ms < finest_ms)) finest = i, finest_ms = ms;
        }
        double excess = off_target(finest_ms);  // over the target after it alone
        if (finest_ms > 0.0) {
            rank(true, demotable_);
            for (const auto& [score, i] : demotable_) {
                if (excess <= 0.0) break;
                const double ms = saving(i);
                if (i == finest || excess - ms < -0.5 * band) continue;  // itself, or too coarse to pull back with
                demoted_.push_back(i), excess -= ms;
            }
        }
        if (finest_ms > 0.0 && std::fabs(excess) <= band)
            chosen_.assign(1, finest), held_under_ = 0, coarse_ms = std::max(coarse_ms, finest_ms);
        else
            demoted_.clear();
    }
    // A coarse step holds steps the other way that it could explain until the smoothed time has taken
    // it in.
    if (coarse_ms > band) {
        (over ? hold_promote_ : hold_demote_) = coarse_hold_updates(coarse_ms, band, common_.smoothing);
        (over ? held_promote_ms_ : held_demote_ms_) = coarse_ms;
    }
    for (uint32_t i : chosen_) {
        uint8_t& demotion = geometric ? states[i].budget_demotion : states[i].anim_demotion;
        demotion = static_cast<uint8_t>(over ? demotion + 1 : demotion - 1);
    }
    for (uint32_t i : demoted_) ++(geometric ? states[i].budget_demotion : states[i].anim_demotion);
    const auto changed = static_cast<uint32_t>(chosen_.size() + demoted_.size());
    if (changed == 0) return step;
    // The effect shows as switches (anticipated at the next update) or as pending switches. The slow
    // mean restarts from the smoothed time: its older frames carry the step's predicted effect, and
    // what the prediction missed would stay in them.
    settle_left_ = common_.settle_frames;
    if (confident) slow_ = {ema_, ema_factor_}, stats_.break_batches();
    step.direction = over ? -1 : 1;
    step.changed = changed;
    return step;
}

}  // namespace aloha
