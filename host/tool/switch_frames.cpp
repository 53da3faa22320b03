// The detrended whole-frame switch comparison (see switch_frames.hpp).
#include "host/tool/switch_frames.hpp"

#include "host/tool/stats.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>

namespace aloha::tool {

std::vector<double> detrended(std::span<const double> values, size_t half_window) {
    std::vector<double> out(values.size(), std::numeric_limits<double>::quiet_NaN()), around;
    for (size_t k = 0; k < values.size(); ++k) {
        const size_t h = std::min({half_window, k, values.size() - 1 - k});  // the same number each side
        if (h == 0) continue;
        around.clear();
        for (size_t j = k - h; j <= k + h; ++j)
            if (j != k) around.push_back(values[j]);
        const size_t mid = around.size() / 2;
        std::nth_element(around.begin(), around.begin() + static_cast<std::ptrdiff_t>(mid), around.end());
        double median = around[mid];
        if (around.size() % 2 == 0) median = 0.5 * (median + *std::max_element(around.begin(), around.begin() + static_cast<std::ptrdiff_t>(mid)));
        out[k] = values[k] - median;
    }
    return out;
}

double rank_test_greater(std::span<const double> x, std::span<const double> y, size_t relabellings, uint64_t seed) {
    if (x.empty() || y.empty()) return 1.0;
    const size_t n = x.size() + y.size();
    std::vector<double> all(x.begin(), x.end());
    all.insert(all.end(), y.begin(), y.end());
    // Mean ranks (ties share theirs).
    std::vector<size_t> order(n);
    std::iota(order.begin(), order.end(), size_t{0});
    std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return all[a] < all[b]; });
    std::vector<double> rank(n);
    for (size_t i = 0; i < n;) {
        size_t j = i;
        while (j + 1 < n && all[order[j + 1]] == all[order[i]]) ++j;
        for (size_t t = i; t <= j; ++t) rank[order[t]] = 0.5 * double(i + j) + 1.0;
        i = j + 1;
    }
    const auto sum_first = [&](std::span<const double> r) { return std::accumulate(r.begin(), r.begin() + static_cast<std::ptrdiff_t>(x.size()), 0.0); };
    const double seen = sum_first(rank);
    std::mt19937_64 rng(seed);
    size_t at_least = 1;  // the observed labelling
    for (size_t r = 0; r < relabellings; ++r) {
        // The first |x| of a partial Fisher-Yates shuffle are a uniformly random subset.
        for (size_t i = 0; i < x.size(); ++i) std::swap(rank[i], rank[i + std::uniform_int_distribution<size_t>(0, n - 1 - i)(rng)]);
        if (sum_first(rank) >= seen - 1e-9) ++at_least;
    }
    return double(at_least) / double(relabellings + 1);
}

SwitchFrameTest switch_frame_test(std::span<const double> change, std::span<const uint8_t> switch_frame, size_t half_window) {
    SwitchFrameTest out;
    if (change.size() < 2 || switch_frame.size() != change.size()) return out;
    const std::vector<double> residual = detrended(change.subspan(1), half_window);
    std::vector<double> at_switch, ordinary;
    for (size_t k = 0; k < residual.size(); ++k)
        if (!std::isnan(residual[k])) (switch_frame[k + 1] ? at_switch : ordinary).push_back(residual[k]);
    out.switch_frames = at_switch.size();
    out.ordinary_frames = ordinary.size();
    if (!at_switch.empty()) out.switch_residual_max = *std::max_element(at_switch.begin(), at_switch.end());
    out.ordinary_residual_p95 = summarize(ordinary).p95;  // the same percentile as the raw bar's
    out.p_value = rank_test_greater(at_switch, ordinary);
    out.no_worse = out.p_value >= 0.05;
    return out;
}

}  // namespace aloha::tool
