#include "host/tool/fidelity_popping.hpp"

#include "host/tool/pop_statistics.hpp"

#include <algorithm>

namespace aloha::tool {

std::vector<FidelityFrame> with_changes_after(const std::vector<FidelityFrame>& measured) {
    std::vector<FidelityFrame> frames = measured;
    for (size_t k = 0; k < frames.size(); ++k)
        for (const FidelityFrame::LaterChange& c : measured[k].later_changes)
            if (c.frames_back >= 1 && c.frames_back <= k && c.pair < frames[k - c.frames_back].by_pair.size())
                frames[k - c.frames_back].by_pair[c.pair].after.push_back(c.change);
    return frames;
}

nlohmann::json popping_by_kind(const std::vector<FidelityFrame>& frames, const std::vector<std::string>& names) {
    auto name = [&](uint8_t l) { return l < names.size() ? names[l] : std::to_string(l); };
    auto kind_json = [&](const SwitchPairChange& p) {
        return nlohmann::json{{"from", name(p.from)}, {"to", name(p.to)}, {"characters", p.characters}, {"change", p.change},
                              {"change_before", p.change_before}, {"excess", p.change - p.change_before},
                              {"rect_px", {p.x0, p.y0, p.x1, p.y1}}};
    };
    struct Sum {
        uint32_t frames = 0, characters = 0;
        double change = 0, excess = 0, max_excess = -1e300;
    };
    std::vector<std::pair<std::pair<uint8_t, uint8_t>, Sum>> sums;
    size_t worst = frames.size();
    for (size_t k = 1; k < frames.size(); ++k) {
        const FidelityFrame& f = frames[k];
        if (f.switches == 0) continue;
        if (worst == frames.size() || f.changed_fraction > frames[worst].changed_fraction) worst = k;
        for (const SwitchPairChange& p : f.by_pair) {
            auto it = std::find_if(sums.begin(), sums.end(), [&](const auto& s) { return s.first == std::pair{p.from, p.to}; });
            if (it == sums.end()) it = sums.insert(sums.end(), {{p.from, p.to}, Sum{}});
            Sum& s = it->second;
            ++s.frames;
            s.characters += p.characters;
            s.change += p.change;
            s.excess += p.change - p.change_before;
            s.max_excess = std::max(s.max_excess, p.change - p.change_before);
        }
    }
    std::sort(sums.begin(), sums.end(), [](const auto& a, const auto& b) { return a.second.excess > b.second.excess; });
    nlohmann::json kinds = nlohmann::json::array();
    for (const auto& [key, s] : sums)
        kinds.push_back({{"from", name(key.first)}, {"to", name(key.second)}, {"frames", s.frames}, {"characters", s.characters},
                         {"change_sum", s.change}, {"excess_sum", s.excess}, {"excess_max", s.max_excess}});
    nlohmann::json j;
    j["kinds"] = kinds;
    if (worst < frames.size()) {
        nlohmann::json parts = nlohmann::json::array();
        for (const SwitchPairChange& p : frames[worst].by_pair) parts.push_back(kind_json(p));
        j["worst_switch_frame"] = {{"frame", worst}, {"change", frames[worst].changed_fraction}, {"kinds", parts}};
    }
    j["note"] = "Each kind's change is the image change inside the union of its switching characters' screen rectangles "
                "(bounds boxes), in changed_fraction units; excess = that minus the same pixels' change one frame earlier "
                "(their ordinary motion): an estimate of what the switch added. Rectangles of different kinds may overlap.";
    return j;
}

namespace {

// One local test (pop_statistics.hpp) over every kind of switch on every switch frame: one event each, its
// rectangles' change against theirs on up to kPopHistoryFrames frames before (centred = false) or before
// and after (centred = true: at least kMinSide frames each side, else the event counts as short).
// The events above their history are listed (frame, kind, change, the history's largest), at most 20.
nlohmann::json local_test(const std::vector<FidelityFrame>& frames, const std::vector<std::string>& names, bool centred) {
    constexpr size_t kMinSide = 4, kListed = 20;
    auto name = [&](uint8_t l) { return l < names.size() ? names[l] : std::to_string(l); };
    std::vector<LocalPopEvent> raw, shares;
    nlohmann::json above = nlohmann::json::array();
    for (size_t k = 0; k < frames.size(); ++k)
        for (const SwitchPairChange& p : frames[k].by_pair) {
            LocalPopEvent event{p.change, p.history};
            std::vector<double> whole;  // the compared frames' whole change: frames k - 1, k - 2, ..., then k + 1, ...
            for (size_t h = 0; h < p.history.size() && h < k; ++h) whole.push_back(frames[k - 1 - h].changed_fraction);
            if (centred) {
                const bool both_sides = p.history.size() >= kMinSide && p.after.size() >= kMinSide;
                for (size_t h = 0; h < p.after.size() && k + 1 + h < frames.size(); ++h) {
                    event.history.push_back(p.after[h]);
                    whole.push_back(frames[k + 1 + h].changed_fraction);
                }
                if (!both_sides) event.history.clear(), whole.clear();
            }
            raw.push_back(event);
            shares.push_back(share_of_frame(raw.back(), frames[k].changed_fraction, whole));
            const LocalPopEvent& e = shares.back();
            const double largest = e.history.empty() ? 0.0 : *std::max_element(e.history.begin(), e.history.end());
            if (e.history.size() >= kMinSide && e.change > largest && above.size() < kListed)
                above.push_back({{"frame", k}, {"from", name(p.from)}, {"to", name(p.to)}, {"characters", p.characters},
                                 {"share", e.change}, {"history_max_share", largest}, {"change", p.change},
                                 {"rect_px", {p.x0, p.y0, p.x1, p.y1}}});
        }
    const LocalPopSummary s = local_pop_summary(shares, kMinSide), r = local_pop_summary(raw, kMinSide);
    return {{"history_frames", kPopHistoryFrames},
            {"min_history_frames", kMinSide},
            {"events", s.events},
            {"invisible", s.invisible},
            {"short_history", s.short_history},
            {"above_history", s.above},
            {"expected_above_without_pops", s.expected_above},
            {"p_value", s.p_value},
            {"worst_ratio_to_history_max", s.worst_ratio},
            {"no_more_pops_than_chance", s.no_more_than_chance},
            {"above_history_events", above},
            {"raw", {{"events", r.events}, {"above_history", r.above}, {"expected_above_without_pops", r.expected_above},
                     {"p_value", r.p_value}, {"worst_ratio_to_history_max", r.worst_ratio}}}};
}

}  // namespace

nlohmann::json local_popping(const std::vector<FidelityFrame>& frames, const std::vector<std::string>& names) {
    nlohmann::json j = local_test(frames, names, false);
    j["note"] = "One event per kind of switch per switch frame: the share of the frame's image change inside its "
                "characters' rectangles, against the same pixels' share on each of the frames before (a trend of the "
                "whole picture cancels; `raw` is the test on the changes themselves). Without pops the switch frame is "
                "the largest of h + 1 with probability 1 / (h + 1); p_value is the chance of at least above_history "
                "such events (Poisson-binomial). Events without change now or before (hidden, off-screen) are not tested.";
    j["centred"] = local_test(frames, names, true);
    j["centred"]["note"] =
        "The same test against the frames before and after the switch (at least 4 each side): a pop is a transient, "
        "so its frame stands above both sides, while change that keeps rising in the rectangles (a nearer character "
        "moving across them, or a character walking in) is above the frames before but not the frames after. A "
        "cross-fade spreads a switch over its fade frames, which then count as ordinary frames after it.";
    return j;
}

nlohmann::json switch_frames_over_p95(const std::vector<FidelityFrame>& frames, double ordinary_p95) {
    size_t over = 0, still_over = 0;
    nlohmann::json listed = nlohmann::json::array();
    for (size_t k = 1; k < frames.size(); ++k) {
        const FidelityFrame& f = frames[k];
        if (f.switches == 0 || f.changed_fraction <= ordinary_p95) continue;
        double in_switches = 0;
        for (const SwitchPairChange& p : f.by_pair) in_switches += p.change;
        ++over;
        // A switching character without a rectangle (crossing the near plane) may hold any part of the
        // change: such a frame is never said to be over without its switches.
        const bool without = f.switches_without_rect == 0 && f.changed_fraction - in_switches > ordinary_p95;
        still_over += without ? 1 : 0;
        if (listed.size() < 20)
            listed.push_back({{"frame", k}, {"change", f.changed_fraction}, {"change_in_switching_characters", in_switches},
                              {"over_without_them", without}});
    }
    return {{"switch_frames_over", over}, {"over_even_without_the_switching_characters", still_over}, {"frames", listed}};
}

SwitchBar switch_bar(std::span<const double> series, std::span<const uint8_t> switch_frame) {
    std::vector<double> ordinary, at_switch;
    for (size_t k = 1; k < series.size() && k < switch_frame.size(); ++k) (switch_frame[k] ? at_switch : ordinary).push_back(series[k]);
    return {summarize(ordinary), summarize(at_switch), switch_frame_test(series, switch_frame)};
}

nlohmann::json switch_bar_verdict(const SwitchBar& bar) {
    if (bar.at_switch.count > 0 && bar.ordinary.count == 0) return nullptr;
    return bar.at_switch.count == 0 || bar.at_switch.max <= bar.ordinary.p95;
}

nlohmann::json detrended_json(const SwitchFrameTest& t) {
    return {{"switch_frames", t.switch_frames},
            {"ordinary_frames", t.ordinary_frames},
            {"switch_residual_max", t.switch_residual_max},
            {"ordinary_residual_p95", t.ordinary_residual_p95},
            {"p_value", t.p_value},
            // Null when one side is empty: nothing to compare.
            {"no_worse_than_ordinary", t.switch_frames > 0 && t.ordinary_frames == 0 ? nlohmann::json(nullptr) : nlohmann::json(t.no_worse)}};
}

nlohmann::json error_change_popping(const std::vector<FidelityFrame>& frames) {
    std::vector<double> series;
    std::vector<uint8_t> flags;
    double switch_total = 0, switch_inside = 0;
    for (size_t k = 0; k < frames.size(); ++k) {
        const FidelityFrame& f = frames[k];
        series.push_back(f.error_change);
        flags.push_back(f.switches > 0 ? 1 : 0);
        if (k > 0 && f.switches > 0) switch_total += f.error_change, switch_inside += f.error_change_in_switches;
    }
    const SwitchBar bar = switch_bar(series, flags);
    return {{"ordinary_frames", bar.ordinary.count},
            {"switch_frames", bar.at_switch.count},
            {"ordinary_error_change_p95", bar.ordinary.p95},
            {"ordinary_error_change_mean", bar.ordinary.mean},
            {"switch_error_change_max", bar.at_switch.max},
            {"switch_error_change_mean", bar.at_switch.mean},
            {"switch_no_worse_than_ordinary_p95", switch_bar_verdict(bar)},
            {"share_inside_switching_characters", switch_total > 0 ? nlohmann::json(switch_inside / switch_total) : nlohmann::json(nullptr)},
            {"detrended", detrended_json(bar.detrended)},
            {"note", "error change: per pixel and channel |(LOD - reference) - (the same on the frame before)|, mean over the "
                     "frame as a fraction of full scale. The reference draws every visible character at full detail with the "
                     "same camera, poses and light, so the picture's own motion cancels and what is left is what the LOD "
                     "changed: a switch that pops raises it on its frame, inside the switching characters' rectangles."}};
}

nlohmann::json reference_change_control(const std::vector<FidelityFrame>& frames) {
    std::vector<double> reference, raw_less;
    std::vector<uint8_t> flags;
    for (const FidelityFrame& f : frames) {
        reference.push_back(f.reference_changed_fraction);
        raw_less.push_back(f.changed_fraction - f.reference_changed_fraction);
        flags.push_back(f.switches > 0 ? 1 : 0);
    }
    const SwitchBar bar = switch_bar(reference, flags);
    return {{"ordinary_frames", bar.ordinary.count},
            {"switch_frames", bar.at_switch.count},
            {"ordinary_change_p95", bar.ordinary.p95},
            {"switch_change_max", bar.at_switch.max},
            {"switch_no_worse_than_ordinary_p95", switch_bar_verdict(bar)},
            {"detrended", detrended_json(bar.detrended)},
            {"raw_less_control", {{"detrended", detrended_json(switch_frame_test(raw_less, flags))}}},
            {"note", "The reference picture draws every visible character at full detail with the same camera, poses and "
                     "light, and switches nothing: its change on the LOD run's switch frames is the picture's own motion "
                     "there. A whole-frame bar that the control fails as well measures when switches happen, not what they "
                     "draw. raw_less_control: each frame's LOD change less the reference's change, detrended and ranked "
                     "the same way."}};
}

}  // namespace aloha::tool
