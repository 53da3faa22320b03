#include "host/scene/world_diagnostics.hpp"
#include "host/tool/fidelity.hpp"

#include "host/tool/pop_statistics.hpp"
#include "host/tool/session.hpp"
#include "host/tool/stats.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <cstdio>
#include <span>

namespace aloha::tool {

namespace {

// PSNR of two RGBA8 images over RGB (dB); identical images give 99.
double psnr(const gpu::Rgba8Image& a, const gpu::Rgba8Image& b) {
    double se = 0.0;
    size_t n = 0;
    for (size_t i = 0; i + 3 < a.pixels.size() && i + 3 < b.pixels.size(); i += 4)
        for (int c = 0; c < 3; ++c) {
            const double d = double(a.pixels[i + c]) - double(b.pixels[i + c]);
            se += d * d;
            ++n;
        }
    if (n == 0 || se == 0.0) return 99.0;
    const double mse = se / double(n);
    return 10.0 * std::log10(255.0 * 255.0 / mse);
}

// Mean absolute RGB change between two frames, as a fraction of full scale.
double mean_change(const gpu::Rgba8Image& a, const gpu::Rgba8Image& b) {
    double sum = 0.0;
    size_t n = 0;
    for (size_t i = 0; i + 3 < a.pixels.size() && i + 3 < b.pixels.size(); i += 4)
        for (int c = 0; c < 3; ++c) sum += std::abs(double(a.pixels[i + c]) - double(b.pixels[i + c])), ++n;
    return n ? sum / (255.0 * double(n)) : 0.0;
}

// Per pixel, the summed |RGB change| between two frames of the same size (0..765); empty when they differ.
void change_map(const gpu::Rgba8Image& a, const gpu::Rgba8Image& b, std::vector<uint16_t>& out) {
    out.clear();
    if (a.pixels.size() != b.pixels.size() || a.width != b.width || a.height != b.height) return;
    out.resize(a.pixels.size() / 4);
    for (size_t p = 0; p < out.size(); ++p) {
        int sum = 0;
        for (int c = 0; c < 3; ++c) sum += std::abs(int(a.pixels[4 * p + c]) - int(b.pixels[4 * p + c]));
        out[p] = static_cast<uint16_t>(sum);
    }
}

// The switch frame's change attributed to each kind of switch (SwitchPairChange): the union of the
// rectangles of that kind's characters, read in this frame's and the previous frame's change maps.
// `stamp` is scratch (one entry per pixel) marking the pixels already counted for a kind.
// `history` holds the change maps of the frames before, most recent first (history[0]: the frame before).
std::vector<SwitchPairChange> pair_changes(std::span<const SwitchRect> rects, uint32_t width, const std::vector<uint16_t>& now,
                                           const std::deque<std::vector<uint16_t>>& history, std::vector<uint32_t>& stamp,
                                           uint32_t& stamp_id) {
    std::vector<SwitchPairChange> out;
    if (now.empty() || width == 0) return out;
    stamp.resize(now.size(), 0);
    const double scale = 1.0 / (255.0 * 3.0 * double(now.size()));
    std::vector<std::pair<uint8_t, uint8_t>> kinds;
    for (const SwitchRect& r : rects)
        if (std::find(kinds.begin(), kinds.end(), std::pair{r.from, r.to}) == kinds.end()) kinds.emplace_back(r.from, r.to);
    std::sort(kinds.begin(), kinds.end());
    for (const auto& [from, to] : kinds) {
        SwitchPairChange pc;
        pc.from = from;
        pc.to = to;
        const uint32_t id = ++stamp_id;
        double sum = 0.0;
        std::vector<double> sum_history(history.size(), 0.0);
        for (const SwitchRect& r : rects) {
            if (r.from != from || r.to != to) continue;
            if (pc.characters++ == 0) pc.x0 = r.x0, pc.y0 = r.y0, pc.x1 = r.x1, pc.y1 = r.y1;
            pc.x0 = std::min(pc.x0, r.x0), pc.y0 = std::min(pc.y0, r.y0), pc.x1 = std::max(pc.x1, r.x1), pc.y1 = std::max(pc.y1, r.y1);
            for (int y = r.y0; y < r.y1; ++y)
                for (int x = r.x0; x < r.x1; ++x) {
                    const size_t p = size_t(y) * width + size_t(x);
                    if (p >= now.size() || stamp[p] == id) continue;
                    stamp[p] = id;
                    sum += now[p];
                    for (size_t h = 0; h < history.size(); ++h)
                        if (p < history[h].size()) sum_history[h] += history[h][p];
                }
        }
        pc.change = sum * scale;
        for (const double h : sum_history) pc.history.push_back(h * scale);
        pc.change_before = pc.history.empty() ? 0.0 : pc.history.front();
        out.push_back(pc);
    }
    return out;
}

class Probe final : public FidelityProbe {
public:
    explicit Probe(Session& s) : s_(s) {}

    Status init() {
        auto target = gpu::OffscreenTarget::create(*s_.context, s_.scene.width, s_.scene.height);
        if (!target.ok()) return target.error();
        reference_target_ = std::move(target.value());
        return {};
    }

    Result<FidelityFrame> measure() override {
        World& world = *s_.world;
        auto lod = s_.target.read_back(*s_.context);
        if (!lod.ok()) return lod.error();
        if (Status st = reference_frame(world, frame_); !st.ok()) return st.error();
        FrameInput input;
        world.frame_settings(input);
        input.meshes = frame_.meshes;
        if (Status st = s_.renderer->render(input, reference_target_); !st.ok()) return st.error();
        if (Status st = s_.renderer->finish(); !st.ok()) return st.error();
        auto reference = reference_target_.read_back(*s_.context);
        if (!reference.ok()) return reference.error();
        FidelityFrame out;
        double sum = 0.0;
        uint64_t count = 0;
        for (size_t l = 0; l < frame_.deviation_sum.size(); ++l) {
            const uint64_t n = frame_.deviation_count[l];
            out.mean_deviation_per_level.push_back(n ? frame_.deviation_sum[l] / double(n) : -1.0);
            out.max_deviation_per_level.push_back(n ? frame_.deviation_max[l] : -1.0);
            sum += frame_.deviation_sum[l];
            count += n;
            out.max_deviation_px = std::max(out.max_deviation_px, frame_.deviation_max[l]);
        }
        out.mean_deviation_px = count ? sum / double(count) : 0.0;
        out.psnr_db = psnr(lod.value(), reference.value());
        out.changed_fraction = previous_.pixels.empty() ? 0.0 : mean_change(lod.value(), previous_);
        out.switches = frame_.switches;
        change_map(lod.value(), previous_, change_now_);
        if (out.switches > 0) out.by_pair = pair_changes(frame_.switch_rects, lod.value().width, change_now_, history_, stamp_, stamp_id_);
        if (!change_now_.empty()) {  // the first frame has no change map: no history yet
            if (history_.size() == kPopHistoryFrames) history_.pop_back();
            history_.push_front(std::move(change_now_));
            change_now_ = {};
        }
        previous_ = std::move(lod.value());
        return out;
    }

private:
    Session& s_;
    gpu::OffscreenTarget reference_target_;
    ReferenceFrame frame_;
    gpu::Rgba8Image previous_;
    std::vector<uint16_t> change_now_;                   ///< per-pixel change map of this frame
    std::deque<std::vector<uint16_t>> history_;          ///< the maps of up to kPopHistoryFrames frames before, newest first
    std::vector<uint32_t> stamp_;                       ///< pair_changes' scratch
    uint32_t stamp_id_ = 0;
};

}  // namespace

Result<std::unique_ptr<FidelityProbe>> FidelityProbe::create(Session& session) {
    if (!session.context || !session.renderer) return make_error("", "--fidelity needs the renderer");
    auto probe = std::make_unique<Probe>(session);
    if (Status s = probe->init(); !s.ok()) return s.error();
    return std::unique_ptr<FidelityProbe>(std::move(probe));
}

namespace {

// The switch frames' change by kind of switch: per kind, the frames and characters, the change inside
// its rectangles and the excess over the frame before (summed and largest); and the worst switch frame's
// own breakdown. Levels are named by `names` where it has them.
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

// The local pop test (pop_statistics.hpp) over every kind of switch on every switch frame: one event each,
// its rectangles' change against theirs on up to kPopHistoryFrames frames before.
// The events above their history are listed (frame, kind, change, the history's largest), at most 20.
nlohmann::json local_popping(const std::vector<FidelityFrame>& frames, const std::vector<std::string>& names) {
    constexpr size_t kMinHistory = 4, kListed = 20;
    auto name = [&](uint8_t l) { return l < names.size() ? names[l] : std::to_string(l); };
    std::vector<LocalPopEvent> raw, shares;
    nlohmann::json above = nlohmann::json::array();
    for (size_t k = 0; k < frames.size(); ++k)
        for (const SwitchPairChange& p : frames[k].by_pair) {
            raw.push_back({p.change, p.history});
            std::vector<double> whole;  // the history frames' whole change: frames k - 1, k - 2, ...
            for (size_t h = 0; h < p.history.size() && h < k; ++h) whole.push_back(frames[k - 1 - h].changed_fraction);
            shares.push_back(share_of_frame(raw.back(), frames[k].changed_fraction, whole));
            const LocalPopEvent& e = shares.back();
            const double largest = e.history.empty() ? 0.0 : *std::max_element(e.history.begin(), e.history.end());
            if (e.history.size() >= kMinHistory && e.change > largest && above.size() < kListed)
                above.push_back({{"frame", k}, {"from", name(p.from)}, {"to", name(p.to)}, {"characters", p.characters},
                                 {"share", e.change}, {"history_max_share", largest}, {"change", p.change},
                                 {"rect_px", {p.x0, p.y0, p.x1, p.y1}}});
        }
    const LocalPopSummary s = local_pop_summary(shares, kMinHistory), r = local_pop_summary(raw, kMinHistory);
    return {{"history_frames", kPopHistoryFrames},
            {"min_history_frames", kMinHistory},
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
                     {"p_value", r.p_value}, {"worst_ratio_to_history_max", r.worst_ratio}}},
            {"note", "One event per kind of switch per switch frame: the share of the frame's image change inside its "
                     "characters' rectangles, against the same pixels' share on each of the frames before (a trend of the "
                     "whole picture cancels; `raw` is the test on the changes themselves). Without pops the switch frame is "
                     "the largest of h + 1 with probability 1 / (h + 1); p_value is the chance of at least above_history "
                     "such events (Poisson-binomial). Events without change now or before (hidden, off-screen) are not tested."}};
}

}  // namespace

nlohmann::json fidelity_report(const std::vector<FidelityFrame>& frames, const std::vector<std::string>& level_names) {
    nlohmann::json j;
    std::vector<double> mean, max, psnr_values, ordinary, at_switch;
    size_t levels = 0;
    for (const auto& f : frames) levels = std::max(levels, f.mean_deviation_per_level.size());
    std::vector<double> level_sum(levels, 0.0), level_max(levels, 0.0);
    std::vector<size_t> level_frames(levels, 0);
    for (size_t k = 0; k < frames.size(); ++k) {
        const FidelityFrame& f = frames[k];
        mean.push_back(f.mean_deviation_px);
        max.push_back(f.max_deviation_px);
        psnr_values.push_back(f.psnr_db);
        if (k > 0) (f.switches > 0 ? at_switch : ordinary).push_back(f.changed_fraction);
        for (size_t l = 0; l < f.mean_deviation_per_level.size(); ++l) {
            if (f.mean_deviation_per_level[l] < 0) continue;
            level_sum[l] += f.mean_deviation_per_level[l];
            level_max[l] = std::max(level_max[l], f.max_deviation_per_level[l]);
            ++level_frames[l];
        }
    }
    j["mean_deviation_px"] = to_json(summarize(mean));
    j["max_deviation_px"] = to_json(summarize(max));
    j["psnr_db"] = to_json(summarize(psnr_values));
    nlohmann::json per_level = nlohmann::json::array();
    for (size_t l = 0; l < levels; ++l)
        per_level.push_back(level_frames[l] ? nlohmann::json{{"level", l}, {"mean_px", level_sum[l] / double(level_frames[l])},
                                                             {"max_px", level_max[l]}}
                                            : nlohmann::json{{"level", l}, {"mean_px", nullptr}, {"max_px", nullptr}});
    j["deviation_per_level"] = per_level;
    const SeriesStats ord = summarize(ordinary), sw = summarize(at_switch);
    j["popping"] = {{"ordinary_frames", ord.count},
                    {"switch_frames", sw.count},
                    {"ordinary_change_p95", ord.p95},
                    {"switch_change_max", sw.max},
                    {"switch_no_worse_than_ordinary_p95", sw.count == 0 || sw.max <= ord.p95},
                    {"by_kind", popping_by_kind(frames, level_names)},
                    {"local", local_popping(frames, level_names)}};
    const double overall_mean = mean.empty() ? 0.0 : summarize(mean).mean;
    j["target_mean_deviation_under_1px"] = overall_mean < 1.0;
    j["note"] = "Deviation compares each mesh-level character's displayed control surface with its level-0 control "
                "surface (springs at rest), projected to pixels; rigid proxies and hidden characters have no skin to "
                "compare and count only in the PSNR, whose reference renders every visible character at the richest "
                "layered level.";
    return j;
}

std::string fidelity_summary(const nlohmann::json& report) {
    if (!report.contains("popping")) return {};
    const nlohmann::json& p = report["popping"];
    const nlohmann::json& l = p["local"];
    char line[512];
    std::snprintf(line, sizeof line,
                  "fidelity: PSNR %.2f dB (min %.2f), mean deviation %.2f px; switch frames' largest change %.6f against the "
                  "ordinary p95 %.6f (%s); local: %zu of %zu switches' shares of the change above their pixels' last ones, %.1f expected "
                  "without pops, p = %.3f (%s)\n",
                  report["psnr_db"]["mean"].get<double>(), report["psnr_db"]["min"].get<double>(),
                  report["mean_deviation_px"]["mean"].get<double>(), p["switch_change_max"].get<double>(),
                  p["ordinary_change_p95"].get<double>(), p["switch_no_worse_than_ordinary_p95"].get<bool>() ? "ok" : "OVER",
                  l["above_history"].get<size_t>(), l["events"].get<size_t>(), l["expected_above_without_pops"].get<double>(),
                  l["p_value"].get<double>(), l["no_more_pops_than_chance"].get<bool>() ? "ok" : "POPS");
    return line;
}

}  // namespace aloha::tool
