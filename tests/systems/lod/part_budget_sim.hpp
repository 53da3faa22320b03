// A synthetic world for the PartBudget tests: a crowd stepped through rules, caps and resolver, true
// per-level costs standing in for the measured times (with measurement noise), and the two part
// controllers fed with them each frame.
#pragma once

#include "systems/lod/part_budget.hpp"
#include "tests/systems/lod/lod_crowd_sim.hpp"

#include <cmath>
#include <cstdint>
#include <numeric>
#include <span>
#include <vector>

namespace aloha::lod_test {

// True cost in ms per character at each level (rich, mid, proxy, hidden; full, kin, clip).
inline constexpr double kGeomCost[] = {0.050, 0.012, 0.002, 0.0};
inline constexpr double kAnimCost[] = {0.030, 0.006, 0.001};
// Measurements are the truth times (1 + noise), noise uniform in +-kNoise.
inline constexpr double kNoise = 0.02;

/// The crowd, the two controllers and the true costs; frame() runs one frame of it.
struct BudgetSim {
    RuleTable table = must_parse(small_rules());
    CrowdSim crowd{table, 0};
    BudgetParams common;
    PartBudget anim{BudgetKind::Animation, {}, {}};
    PartBudget geom{BudgetKind::Geometry, {}, {}};
    Lcg rnd;
    std::vector<double> geom_cost{std::begin(kGeomCost), std::end(kGeomCost)};  // truth, ms per character per level
    std::vector<double> anim_cost{std::begin(kAnimCost), std::end(kAnimCost)};
    bool anim_per_level = false;                // animation told its per-level times too (as the World does)
    std::vector<uint8_t> walking;               // per character: 1 walks, 0 costs anim_still_cost; empty: all walk
    std::vector<double> anim_still_cost;        // truth for characters not walking, ms per level (with `walking`)
    bool tell_classes = true;                   // with `walking`: the part is told each character's cost class
    double geom_truth = 0, anim_truth = 0;      // noise-free cost of the last frame
    double geom_ms = -1, anim_ms = -1;          // what the controllers are told
    double load = 1.0;                          // the machine's slowdown: every measured time is the truth times this
    double noise = kNoise;                      // measurement noise: uniform in +-noise of the truth
    int spike_every = 0;                        // every n-th frame's measured totals are spike_factor x (0: none)
    double spike_factor = 1.0;
    int spike_clock = 0;
    std::vector<double> geom_level_ms, anim_level_ms;
    std::vector<int> anim_steps, geom_steps;    // direction of every step, in order

    // Adds n characters at near..far m with random importance.
    void add(size_t n, float near = 2.0f, float far = 40.0f) {
        const size_t old = crowd.attrs.size();
        crowd.resize(old + n);
        for (size_t i = old; i < crowd.attrs.size(); ++i) {
            crowd.attrs[i] = at_distance(near + (far - near) * rnd.next());
            crowd.attrs[i].importance = rnd.next();
        }
    }
    void set_targets(double anim_target, double geom_target) {
        common.settle_frames = 2;
        BudgetPartParams a, g;
        a.target_ms = static_cast<float>(anim_target);
        g.target_ms = static_cast<float>(geom_target);
        anim.set_params(a, common);
        geom.set_params(g, common);
    }
    void frame() {
        if (anim.params().target_ms > 0) {
            const std::span<const double> per_level = anim_per_level ? std::span<const double>(anim_level_ms) : std::span<const double>();
            const std::span<const uint8_t> classes = tell_classes ? std::span<const uint8_t>(walking) : std::span<const uint8_t>();
            const BudgetStep s = anim.update(static_cast<float>(anim_ms), per_level, crowd.attrs, crowd.req, crowd.states, table, classes);
            if (s.direction) anim_steps.push_back(s.direction);
        }
        if (geom.params().target_ms > 0) {
            const BudgetStep s = geom.update(static_cast<float>(geom_ms), geom_level_ms, crowd.attrs, crowd.req, crowd.states, table);
            if (s.direction) geom_steps.push_back(s.direction);
        }
        crowd.frame();
        geom_level_ms.assign(geom_cost.size(), 0.0);
        const bool tell = !walking.empty() && tell_classes;
        anim_level_ms.assign(anim_cost.size() * (tell ? kAnimCostClasses : 1), 0.0);
        anim_truth = geom_truth = 0.0;
        for (size_t i = 0; i < crowd.states.size(); ++i) {
            const LodState& s = crowd.states[i];
            const bool walks = walking.empty() || walking[i] != 0;
            geom_level_ms[s.geom_level] += geom_cost[s.geom_level];
            anim_level_ms[tell ? anim_cost_slot(s.anim_level, walks) : s.anim_level] +=
                walks ? anim_cost[s.anim_level] : anim_still_cost[s.anim_level];
        }
        for (double& l : geom_level_ms) geom_truth += l, l *= 1.0 + noise * (2.0 * rnd.next() - 1.0);
        for (double& l : anim_level_ms) anim_truth += l, l *= anim_per_level ? 1.0 + noise * (2.0 * rnd.next() - 1.0) : 1.0;
        geom_ms = geom_truth * (1.0 + noise * (2.0 * rnd.next() - 1.0));
        anim_ms = anim_per_level ? std::accumulate(anim_level_ms.begin(), anim_level_ms.end(), 0.0)
                                 : anim_truth * (1.0 + noise * (2.0 * rnd.next() - 1.0));
        geom_ms *= load, anim_ms *= load;
        if (spike_every > 0 && ++spike_clock % spike_every == 0) geom_ms *= spike_factor, anim_ms *= spike_factor;
        for (double& l : geom_level_ms) l *= load;
        for (double& l : anim_level_ms) l *= load;
    }
};

/// The last frame (of 300) at which the true animation time was more than 10% off its target after a
/// crowd of 500 doubled (-1: never), the target at 0.6 of the first crowd's full cost, the animation
/// part settled 300 frames before, with `trim_smoothing`, `dwell` and `confidence` in its settings.
inline int frames_to_reconverge(float trim_smoothing, float dwell = 0.0f, float confidence = 0.0f) {
    BudgetSim sim;
    sim.common.confidence = confidence;
    sim.add(500);
    sim.frame();
    const double target = 0.6 * sim.anim_truth;
    sim.common.trim_smoothing = trim_smoothing;
    sim.common.dwell = dwell;
    sim.set_targets(target, 0.0);
    for (int f = 0; f < 300; ++f) sim.frame();
    sim.add(500);
    int last_out = -1;
    for (int f = 0; f < 300; ++f) {
        sim.frame();
        if (std::fabs(sim.anim_truth - target) > 0.1 * target) last_out = f;
    }
    return last_out;
}

/// How often consecutive steps changed direction.
inline int direction_changes(const std::vector<int>& steps) {
    int n = 0;
    for (size_t i = 1; i < steps.size(); ++i) n += steps[i] != steps[i - 1];
    return n;
}

}  // namespace aloha::lod_test
