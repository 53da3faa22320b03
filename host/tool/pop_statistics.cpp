#include "host/tool/pop_statistics.hpp"

#include <algorithm>
#include <cassert>

namespace aloha::tool {

double poisson_binomial_at_least(std::span<const double> p, size_t k) {
    if (k == 0) return 1.0;
    if (k > p.size()) return 0.0;
    // dist[j]: P(j successes among the trials so far), built one trial at a time (exact, O(n^2)).
    std::vector<double> dist(p.size() + 1, 0.0);
    dist[0] = 1.0;
    for (size_t i = 0; i < p.size(); ++i) {
        assert(p[i] >= 0.0 && p[i] <= 1.0);
        for (size_t j = i + 1; j > 0; --j) dist[j] = dist[j] * (1.0 - p[i]) + dist[j - 1] * p[i];
        dist[0] *= 1.0 - p[i];
    }
    double tail = 0.0;
    for (size_t j = k; j < dist.size(); ++j) tail += dist[j];
    return std::min(1.0, tail);
}

LocalPopEvent share_of_frame(const LocalPopEvent& raw, double frame_change, std::span<const double> history_frame_change) {
    LocalPopEvent out;
    out.change = frame_change > 0.0 ? raw.change / frame_change : 0.0;
    for (size_t h = 0; h < raw.history.size() && h < history_frame_change.size(); ++h)
        if (history_frame_change[h] > 0.0) out.history.push_back(raw.history[h] / history_frame_change[h]);
    return out;
}

LocalPopSummary local_pop_summary(std::span<const LocalPopEvent> events, size_t min_history) {
    assert(min_history >= 1);
    LocalPopSummary s;
    std::vector<double> chance;
    for (const LocalPopEvent& e : events) {
        if (e.history.size() < min_history) {
            ++s.short_history;
            continue;
        }
        const double largest = *std::max_element(e.history.begin(), e.history.end());
        if (e.change <= 0.0 && largest <= 0.0) {
            ++s.invisible;
            continue;
        }
        ++s.events;
        chance.push_back(1.0 / double(e.history.size() + 1));
        if (e.change > largest) ++s.above;
        if (largest > 0.0) s.worst_ratio = std::max(s.worst_ratio, e.change / largest);
    }
    for (const double c : chance) s.expected_above += c;
    s.p_value = poisson_binomial_at_least(chance, s.above);
    s.no_more_than_chance = s.p_value >= 0.05;
    return s;
}

}  // namespace aloha::tool
