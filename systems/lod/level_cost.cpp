#include "systems/lod/level_cost.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace aloha {

namespace {

// Relative cost of a geometric level before anything is measured (scaled by the first measurement).
double geometry_prior(const GeomLevelDef& l) {
    const double grid = static_cast<double>(l.theta_steps) * static_cast<double>(l.phi_steps) / 48.0;
    switch (l.method) {
        case GeomMethod::Hidden: return 0.0;
        case GeomMethod::RigidProxy: return 0.1;
        case GeomMethod::Impostor: return 0.01;
        case GeomMethod::SkinnedMesh: return 0.3 + 0.5 * grid;
        case GeomMethod::Layered: return 1.0 + 3.0 * grid;
        case GeomMethod::Subdivided: return (1.0 + 3.0 * grid) * std::pow(3.0, l.subdiv_level);
    }
    return 1.0;
}

// Relative cost of an animation level before anything is measured, for a walker (its walk method
// runs) or not (a clip sample).
double animation_prior(const AnimLevelDef& l, bool walking) {
    const double walk = !walking ? 1.0 : l.walk == WalkMethod::Dynamic ? 40.0 : l.walk == WalkMethod::Kinematic ? 3.0 : 1.0;
    const double ik = l.ik == IkSolver::Dls ? 0.4 * l.ik_iterations : l.ik == IkSolver::Ccd ? 0.2 * l.ik_iterations : 0.0;
    return (walk + ik) / std::max<double>(1.0, l.update_interval);
}

}  // namespace

void LevelCostModel::set_levels(BudgetKind kind, const RuleTable& table, size_t classes) {
    classes = std::max<size_t>(1, classes);
    std::vector<double> prior;
    if (kind == BudgetKind::Geometry) {
        for (const auto& l : table.geom_levels)
            for (size_t c = 0; c < classes; ++c) prior.push_back(geometry_prior(l));
    } else {
        for (const auto& l : table.anim_levels)
            for (size_t c = 0; c < classes; ++c) prior.push_back(animation_prior(l, classes > 1 && c == 1));
    }
    if (prior.size() == prior_.size() && classes == classes_ && scaled_) return;  // same shape: keep what was learned
    classes_ = classes;
    prior_ = std::move(prior);
    cost_ = prior_;
    marginal_ = prior_;
    fits_.assign(prior_.size(), Fit{});
    scaled_ = false;
}

void LevelCostModel::observe(std::span<const uint32_t> counts, std::span<const double> slot_ms, double total_ms,
                             float weight) {
    if (counts.size() != cost_.size() || !std::isfinite(total_ms) || total_ms < 0.0) return;
    const bool per_slot = slot_ms.size() == counts.size();
    const double measured = per_slot ? std::accumulate(slot_ms.begin(), slot_ms.end(), 0.0) : total_ms;
    if (!scaled_) {
        double predicted = 0.0;
        for (size_t l = 0; l < counts.size(); ++l) predicted += counts[l] * prior_[l];
        if (!(predicted > 0.0 && measured > 0.0)) return;
        const double scale = measured / predicted;
        for (double& p : prior_) p *= scale;
        cost_ = marginal_ = prior_;
        scaled_ = true;
        return;
    }
    if (per_slot) {
        for (size_t l = 0; l < counts.size(); ++l) {
            if (!std::isfinite(slot_ms[l]) || slot_ms[l] < 0.0) continue;
            if (counts[l] > 0) cost_[l] += weight * (slot_ms[l] / counts[l] - cost_[l]);
            fit_marginal(l, counts[l], slot_ms[l], weight);
        }
        return;
    }
    double predicted = 0.0, norm = 0.0;
    for (size_t l = 0; l < counts.size(); ++l) {
        predicted += counts[l] * cost_[l];
        norm += static_cast<double>(counts[l]) * counts[l];
    }
    if (norm <= 0.0) return;
    const double error = total_ms - predicted;
    for (size_t l = 0; l < counts.size(); ++l)
        cost_[l] = marginal_[l] = std::max(0.01 * prior_[l], cost_[l] + weight * error * counts[l] / norm);
}

void LevelCostModel::fit_marginal(size_t l, uint32_t count, double ms, float weight) {
    // Moving least squares of the level's time against its count, over a window four times longer
    // than the average's (the count changes only when a controller steps). A level's time often has a
    // part that does not scale with its count (a parallel loop per body type, say): the slope is what
    // one more or one fewer character really costs.
    //
    // Ridge regression toward the average (the slope of a level with no fixed part): the slope is
    // (cov + lambda * average) / (var + lambda) with lambda = (kSpread * mean count)^2, at least 4 (a
    // count that moves by one or two characters tells nothing). Why: the machine's own speed drifts
    // while the count moves (this VM: 1.6x between runs, 15 -> 8 ms within one), so a time that is
    // (average * count) * (1 + d) has a covariance error up to d * mean time * count spread s, and the
    // slope error up to d * average * mean count * s / (s^2 + lambda) <= d * average / (2 * kSpread):
    // with kSpread 0.3, a 30% drift moves the marginal by at most half the average, however little the
    // count varied. A count spread of kSpread * mean gives the measured slope half the weight; a count
    // that ranges over the whole crowd (a fixed part that matters) gives it most.
    constexpr double kSpread = 0.3;
    Fit& f = fits_[l];
    const double w = 0.25 * weight, n = count;
    if (!f.seen) f = Fit{n, ms, n * n, n * ms, true};
    f.n += w * (n - f.n);
    f.t += w * (ms - f.t);
    f.nn += w * (n * n - f.nn);
    f.nt += w * (n * ms - f.nt);
    const double var = std::max(0.0, f.nn - f.n * f.n);
    const double lambda = std::max(4.0, kSpread * kSpread * f.n * f.n);
    const double slope = (f.nt - f.n * f.t + lambda * cost_[l]) / (var + lambda);
    marginal_[l] = std::clamp(slope, 0.0, 2.0 * std::max(cost_[l], prior_[l]));
}

double LevelCostModel::cost(size_t slot) const {
    if (cost_.empty()) return 0.0;
    return cost_[std::min(slot, cost_.size() - 1)];
}

double LevelCostModel::marginal(size_t slot) const {
    if (marginal_.empty()) return 0.0;
    return marginal_[std::min(slot, marginal_.size() - 1)];
}

double LevelCostModel::predict(std::span<const uint32_t> counts) const {
    double sum = 0.0;
    for (size_t l = 0; l < counts.size() && l < cost_.size(); ++l) sum += counts[l] * cost_[l];
    return sum;
}

}  // namespace aloha
