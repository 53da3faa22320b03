#include "host/scene/world_diagnostics.hpp"
#include "host/tool/fidelity.hpp"

#include "host/tool/fidelity_popping.hpp"
#include "host/tool/image_compare.hpp"
#include "host/tool/session.hpp"
#include "host/tool/stats.hpp"
#include "host/tool/switch_frames.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <deque>
#include <optional>
#include <span>

namespace aloha::tool {

namespace {

// The kinds of switch (from, to) among `rects`, sorted: the order of a frame's by_pair.
std::vector<std::pair<uint8_t, uint8_t>> switch_kinds(std::span<const SwitchRect> rects) {
    std::vector<std::pair<uint8_t, uint8_t>> kinds;
    for (const SwitchRect& r : rects)
        if (std::find(kinds.begin(), kinds.end(), std::pair{r.from, r.to}) == kinds.end()) kinds.emplace_back(r.from, r.to);
    std::sort(kinds.begin(), kinds.end());
    return kinds;
}

// The rectangles of `rects` whose switch is `kind` (from, to), or all of them without a kind: their pixels
// (each counted once, `stamp` marking them with a fresh id) summed in `maps` (the result has one sum per
// map) and their bounding rectangle. `stamp` is scratch with one entry per pixel.
struct RectSums {
    std::vector<double> sums;
    uint32_t characters = 0;
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};
RectSums sum_in_rects(std::span<const SwitchRect> rects, std::optional<std::pair<uint8_t, uint8_t>> kind, uint32_t width,
                      std::span<const std::vector<uint16_t>* const> maps, std::vector<uint32_t>& stamp, uint32_t& stamp_id) {
    RectSums out;
    out.sums.assign(maps.size(), 0.0);
    const uint32_t id = ++stamp_id;
    for (const SwitchRect& r : rects) {
        if (kind && (r.from != kind->first || r.to != kind->second)) continue;
        if (out.characters++ == 0) out.x0 = r.x0, out.y0 = r.y0, out.x1 = r.x1, out.y1 = r.y1;
        out.x0 = std::min(out.x0, r.x0), out.y0 = std::min(out.y0, r.y0), out.x1 = std::max(out.x1, r.x1), out.y1 = std::max(out.y1, r.y1);
        for (int y = r.y0; y < r.y1; ++y)
            for (int x = r.x0; x < r.x1; ++x) {
                const size_t p = size_t(y) * width + size_t(x);
                if (p >= stamp.size() || stamp[p] == id) continue;
                stamp[p] = id;
                for (size_t m = 0; m < maps.size(); ++m)
                    if (p < maps[m]->size()) out.sums[m] += (*maps[m])[p];
            }
    }
    return out;
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
    std::vector<const std::vector<uint16_t>*> maps{&now};
    for (const auto& h : history) maps.push_back(&h);
    for (const auto& [from, to] : switch_kinds(rects)) {
        const RectSums sums = sum_in_rects(rects, std::pair{from, to}, width, maps, stamp, stamp_id);
        SwitchPairChange pc;
        pc.from = from;
        pc.to = to;
        pc.characters = sums.characters;
        pc.x0 = sums.x0, pc.y0 = sums.y0, pc.x1 = sums.x1, pc.y1 = sums.y1;
        pc.change = sums.sums[0] * scale;
        for (size_t h = 1; h < sums.sums.size(); ++h) pc.history.push_back(sums.sums[h] * scale);
        pc.change_before = pc.history.empty() ? 0.0 : pc.history.front();
        out.push_back(pc);
    }
    return out;
}

// Per geometric level, one frame's mean of a summed deviation (-1 where the level had no vertex), and the
// mean over all levels' vertices (`none` when there is no vertex at all).
double level_means(std::span<const double> sums, std::span<const uint64_t> counts, std::vector<double>& per_level, double none) {
    double sum = 0.0;
    uint64_t count = 0;
    per_level.clear();
    for (size_t l = 0; l < sums.size(); ++l) {
        per_level.push_back(counts[l] ? sums[l] / double(counts[l]) : -1.0);
        sum += sums[l];
        count += counts[l];
    }
    return count ? sum / double(count) : none;
}

// Per geometric level, a figure averaged over the frames where that level had one (>= 0).
struct LevelAverage {
    std::vector<double> sum;
    std::vector<size_t> frames;
    void add(std::span<const double> per_level) {
        if (sum.size() < per_level.size()) sum.resize(per_level.size(), 0.0), frames.resize(per_level.size(), 0);
        for (size_t l = 0; l < per_level.size(); ++l)
            if (per_level[l] >= 0) sum[l] += per_level[l], ++frames[l];
    }
    [[nodiscard]] nlohmann::json at(size_t l) const {
        return l < frames.size() && frames[l] ? nlohmann::json(sum[l] / double(frames[l])) : nlohmann::json(nullptr);
    }
};

class Probe final : public FidelityProbe {
public:
    explicit Probe(Session& s) : s_(s) {}

    Status init() {
        auto target = gpu::OffscreenTarget::create(*s_.context, s_.scene.width, s_.scene.height);
        if (!target.ok()) return target.error();
        reference_target_ = std::move(target.value());
        s_.world->set_reference_springs(true);  // the deviation against the full-detail body with its fat moving
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
        // A frame without mesh vertices reads 0 on each figure; the moving one reads -1 (not measured) when
        // there were vertices but no reference springs (level 0 without fat springs).
        out.mean_deviation_px = level_means(frame_.deviation_sum, frame_.deviation_count, out.mean_deviation_per_level, 0.0);
        out.mean_rest_deviation_px = level_means(frame_.rest_deviation_sum, frame_.rest_deviation_count, out.mean_rest_deviation_per_level, 0.0);
        out.mean_moving_deviation_px = level_means(frame_.moving_deviation_sum, frame_.moving_deviation_count, out.mean_moving_deviation_per_level,
                                                   out.mean_deviation_px > 0.0 ? -1.0 : 0.0);
        for (size_t l = 0; l < frame_.deviation_sum.size(); ++l) {
            out.max_deviation_per_level.push_back(frame_.deviation_count[l] ? frame_.deviation_max[l] : -1.0);
            out.max_deviation_px = std::max(out.max_deviation_px, frame_.deviation_max[l]);
        }
        const std::span<const uint8_t> now = lod.value().pixels, now_reference = reference.value().pixels;
        out.psnr_db = psnr_db(now, now_reference);
        const SilhouetteCoverage cover = silhouette_coverage(now, now_reference, lod.value().width);
        out.silhouette_ratio = cover.reference_pixels > 0 ? double(cover.pixels) / double(cover.reference_pixels) : 1.0;
        out.silhouette_covered = cover.covered;
        out.silhouette_on_reference = cover.on_reference;
        out.switches = frame_.switches;
        for (const SwitchRect& r : frame_.switch_rects) out.switches_without_rect += (r.x1 <= r.x0 || r.y1 <= r.y0) ? 1u : 0u;
        out.changed_fraction = change_map(now, previous_.pixels, change_now_);  // 0 and no map on the first frame
        out.reference_changed_fraction = change_map(now_reference, previous_reference_.pixels, reference_change_now_);
        out.error_change = error_change(now, now_reference, previous_.pixels, previous_reference_.pixels, error_change_now_);
        if (!error_change_now_.empty()) {
            stamp_.resize(error_change_now_.size(), 0);
            const std::vector<uint16_t>* error_map[1] = {&error_change_now_};
            out.error_change_in_switches = sum_in_rects(frame_.switch_rects, std::nullopt, lod.value().width, error_map, stamp_, stamp_id_).sums[0] /
                                           (255.0 * 3.0 * double(error_change_now_.size()));
        }
        if (out.switches > 0) out.by_pair = pair_changes(frame_.switch_rects, lod.value().width, change_now_, history_, stamp_, stamp_id_);
        follow_earlier_switches(lod.value().width, out);
        if (!change_now_.empty()) {  // the first frame has no change map: no history yet
            if (history_.size() == kPopHistoryFrames) history_.pop_back();
            history_.push_front(std::move(change_now_));
            change_now_ = {};
        }
        previous_ = std::move(lod.value());
        previous_reference_ = std::move(reference.value());
        return out;
    }

private:
    // An earlier frame's kind of switch whose pixels' change is still followed (for the centred test).
    struct Followed {
        uint32_t frame = 0;  ///< the measured frame of the switch
        uint32_t pair = 0;   ///< its index in that frame's by_pair
        std::vector<SwitchRect> rects;
        size_t frames_seen = 0;
    };

    // Adds this frame's change inside each followed switch's rectangles to `out`.later_changes, drops those
    // followed for kPopHistoryFrames frames, then follows this frame's own switches (out.by_pair's order).
    void follow_earlier_switches(uint32_t width, FidelityFrame& out) {
        if (!change_now_.empty()) {
            stamp_.resize(change_now_.size(), 0);
            const double scale = 1.0 / (255.0 * 3.0 * double(change_now_.size()));
            const std::vector<uint16_t>* now[1] = {&change_now_};
            for (Followed& f : followed_) {
                const auto kind = std::pair{f.rects.front().from, f.rects.front().to};
                const RectSums sums = sum_in_rects(f.rects, kind, width, now, stamp_, stamp_id_);
                out.later_changes.push_back({frame_index_ - f.frame, f.pair, sums.sums[0] * scale});
                ++f.frames_seen;
            }
            std::erase_if(followed_, [](const Followed& f) { return f.frames_seen >= kPopHistoryFrames; });
        }
        for (uint32_t i = 0; i < out.by_pair.size(); ++i) {
            Followed f{frame_index_, i, {}, 0};
            for (const SwitchRect& r : frame_.switch_rects)
                if (r.from == out.by_pair[i].from && r.to == out.by_pair[i].to) f.rects.push_back(r);
            followed_.push_back(std::move(f));
        }
        ++frame_index_;
    }

    Session& s_;
    gpu::OffscreenTarget reference_target_;
    ReferenceFrame frame_;
    gpu::Rgba8Image previous_;
    gpu::Rgba8Image previous_reference_;
    std::vector<uint16_t> error_change_now_;             ///< per-pixel change of the LOD's error, this frame
    std::vector<uint16_t> change_now_;                   ///< per-pixel change map of this frame
    std::vector<uint16_t> reference_change_now_;         ///< the reference picture's change map (scratch)
    std::deque<std::vector<uint16_t>> history_;          ///< the maps of up to kPopHistoryFrames frames before, newest first
    std::vector<uint32_t> stamp_;                       ///< pair_changes' scratch
    uint32_t stamp_id_ = 0;
    std::vector<Followed> followed_;                     ///< switches of the last kPopHistoryFrames frames
    uint32_t frame_index_ = 0;                           ///< measured frames so far
};

}  // namespace

Result<std::unique_ptr<FidelityProbe>> FidelityProbe::create(Session& session) {
    if (!session.context || !session.renderer) return make_error("", "--fidelity needs the renderer");
    auto probe = std::make_unique<Probe>(session);
    if (Status s = probe->init(); !s.ok()) return s.error();
    return std::unique_ptr<FidelityProbe>(std::move(probe));
}

nlohmann::json fidelity_report(const std::vector<FidelityFrame>& measured, const std::vector<std::string>& level_names) {
    const std::vector<FidelityFrame> frames = with_changes_after(measured);
    nlohmann::json j;
    std::vector<double> mean, rest_mean, moving_mean, max, psnr_values, changes;  // per frame
    std::vector<double> silhouette_ratio, silhouette_covered, silhouette_on_reference;
    std::vector<uint8_t> switch_flags;
    size_t levels = 0;
    for (const auto& f : frames) levels = std::max(levels, f.mean_deviation_per_level.size());
    LevelAverage literal, at_rest, moving;
    std::vector<double> level_max(levels, 0.0);
    for (size_t k = 0; k < frames.size(); ++k) {
        const FidelityFrame& f = frames[k];
        mean.push_back(f.mean_deviation_px);
        rest_mean.push_back(f.mean_rest_deviation_px);
        moving_mean.push_back(f.mean_moving_deviation_px);  // -1: not measured on that frame
        max.push_back(f.max_deviation_px);
        psnr_values.push_back(f.psnr_db);
        silhouette_ratio.push_back(f.silhouette_ratio);
        silhouette_covered.push_back(f.silhouette_covered);
        silhouette_on_reference.push_back(f.silhouette_on_reference);
        changes.push_back(f.changed_fraction);
        switch_flags.push_back(f.switches > 0 ? 1 : 0);
        literal.add(f.mean_deviation_per_level);
        at_rest.add(f.mean_rest_deviation_per_level);
        moving.add(f.mean_moving_deviation_per_level);
        for (size_t l = 0; l < f.max_deviation_per_level.size(); ++l) level_max[l] = std::max(level_max[l], f.max_deviation_per_level[l]);
    }
    j["mean_deviation_px"] = to_json(summarize(mean));
    // The levels' geometric error alone: the displayed level's springs at rest (as the reference's are).
    j["mean_rest_deviation_px"] = to_json(summarize(rest_mean));
    // Against the full-detail body with its own fat springs moving (World::set_reference_springs): the fat
    // motion on both sides, what the design bar's "full skin" moves like. Null when a frame had mesh vertices
    // but no reference springs to measure them against.
    const bool moving_measured = std::none_of(moving_mean.begin(), moving_mean.end(), [](double v) { return v < 0.0; });
    j["mean_moving_reference_deviation_px"] = moving_measured ? to_json(summarize(moving_mean)) : nlohmann::json(nullptr);
    j["max_deviation_px"] = to_json(summarize(max));
    j["psnr_db"] = to_json(summarize(psnr_values));
    // Silhouettes: what PSNR over the whole frame hardly sees (a far crowd drawn too small, or not at all).
    j["silhouettes"] = {{"pixels_over_reference", to_json(summarize(silhouette_ratio))},
                        {"reference_covered_within_1px", to_json(summarize(silhouette_covered))},
                        {"drawn_on_reference_within_1px", to_json(summarize(silhouette_on_reference))},
                        {"note", "A pixel is a character's where it differs from the reference's most common colour (the "
                                 "background) by more than 24 levels summed over RGB (host/tool/image_compare.hpp)."}};
    nlohmann::json per_level = nlohmann::json::array();
    for (size_t l = 0; l < levels; ++l) {
        const bool any = !literal.at(l).is_null();
        per_level.push_back({{"level", l}, {"mean_px", literal.at(l)}, {"rest_mean_px", at_rest.at(l)}, {"moving_reference_mean_px", moving.at(l)},
                             {"max_px", any ? nlohmann::json(level_max[l]) : nlohmann::json(nullptr)}});
    }
    j["deviation_per_level"] = per_level;
    const SwitchBar bar = switch_bar(changes, switch_flags);
    nlohmann::json detrended = detrended_json(bar.detrended);
    detrended["note"] = "Each frame's change less the median of its neighbours (up to 4 each side, as many on both), "
                        "which a smooth trend of the whole picture cancels; p_value: the chance, if switch and "
                        "ordinary frames were exchangeable, that the switch frames rank at least this high on "
                        "average (20,000 random relabellings, fixed seed). no_worse_than_ordinary: p >= 0.05.";
    j["popping"] = {{"ordinary_frames", bar.ordinary.count},
                    {"switch_frames", bar.at_switch.count},
                    {"ordinary_change_p95", bar.ordinary.p95},
                    {"switch_change_max", bar.at_switch.max},
                    // No ordinary frame (a switch on every frame after the first): nothing to compare with, null.
                    {"switch_no_worse_than_ordinary_p95", switch_bar_verdict(bar)},
                    // The same comparison with the scene's trend taken out, over all switch frames at once
                    // (host/tool/switch_frames.hpp).
                    {"detrended", std::move(detrended)},
                    {"over_p95", switch_frames_over_p95(frames, bar.ordinary.p95)},
                    {"against_reference", error_change_popping(frames)},
                    {"control", reference_change_control(frames)},
                    {"by_kind", popping_by_kind(frames, level_names)},
                    {"local", local_popping(frames, level_names)}};
    const double overall_mean = mean.empty() ? 0.0 : summarize(mean).mean;
    j["target_mean_deviation_under_1px"] = overall_mean < 1.0;
    j["target_mean_deviation_under_1px_against_moving_reference"] =
        moving_measured ? nlohmann::json(summarize(moving_mean).mean < 1.0) : nlohmann::json(nullptr);
    j["note"] = "Deviation compares each mesh-level character's displayed control surface with its level-0 control "
                "surface (springs at rest), projected to pixels; mean_rest_deviation_px (and rest_mean_px per level) "
                "puts the displayed level's own springs at rest too, leaving the level's geometric error without the fat "
                "springs' motion, which the full-detail body has as well; mean_moving_reference_deviation_px (and "
                "moving_reference_mean_px per level) compares with the level-0 surface whose own fat springs moved with the "
                "character since it reached a mesh level (started at rest then, as a level's springs start when it is "
                "entered): the fat motion on both sides; rigid proxies, impostors and hidden characters have no skin to "
                "compare and count only in the PSNR, whose reference renders every visible character at the richest "
                "layered level.";
    return j;
}

std::string fidelity_summary(const nlohmann::json& report) {
    if (!report.contains("popping")) return {};
    const nlohmann::json& p = report["popping"];
    const nlohmann::json& l = p["local"];
    const nlohmann::json& c = l["centred"];
    const nlohmann::json& d = p["detrended"];
    char moving_text[32] = "no";
    if (report.contains("mean_moving_reference_deviation_px") && !report["mean_moving_reference_deviation_px"].is_null())
        std::snprintf(moving_text, sizeof moving_text, "%.2f", report["mean_moving_reference_deviation_px"]["mean"].get<double>());
    const std::string moving = moving_text;
    char line[1280];
    std::snprintf(line, sizeof line,
                  "fidelity: PSNR %.2f dB (min %.2f), mean deviation %.2f px (%.2f px with the shown level's springs at rest too, %s px against "
                  "the full-detail body with its fat springs moving); switch frames' largest change %.6f against the "
                  "ordinary p95 %.6f (%s); detrended (against neighbours, all switch frames ranked against the ordinary): "
                  "p = %.3f (%s); local: %zu of %zu switches' shares of the change above their pixels' last ones, %.1f expected "
                  "without pops, p = %.3f (%s); centred (frames before and after): %zu of %zu above, %.1f expected, p = %.3f (%s)\n",
                  report["psnr_db"]["mean"].get<double>(), report["psnr_db"]["min"].get<double>(),
                  report["mean_deviation_px"]["mean"].get<double>(), report["mean_rest_deviation_px"]["mean"].get<double>(),
                  moving.c_str(),
                  p["switch_change_max"].get<double>(),
                  p["ordinary_change_p95"].get<double>(),
                  p["switch_no_worse_than_ordinary_p95"].is_null() ? "no ordinary frame to compare"
                  : p["switch_no_worse_than_ordinary_p95"].get<bool>() ? "ok" : "OVER",
                  d["p_value"].get<double>(),
                  d["no_worse_than_ordinary"].is_null() ? "no ordinary frame to compare" : d["no_worse_than_ordinary"].get<bool>() ? "ok" : "WORSE",
                  l["above_history"].get<size_t>(), l["events"].get<size_t>(), l["expected_above_without_pops"].get<double>(),
                  l["p_value"].get<double>(), l["no_more_pops_than_chance"].get<bool>() ? "ok" : "POPS",
                  c["above_history"].get<size_t>(), c["events"].get<size_t>(), c["expected_above_without_pops"].get<double>(),
                  c["p_value"].get<double>(), c["no_more_pops_than_chance"].get<bool>() ? "ok" : "POPS");
    std::string out = line;
    if (report.contains("silhouettes")) {
        const nlohmann::json& s = report["silhouettes"];
        std::snprintf(line, sizeof line,
                      "fidelity silhouettes: characters drawn on %.2fx the reference's pixels, %.1f%% of the reference's within 1 px "
                      "of them, %.1f%% of them within 1 px of the reference's (means over the frames)\n",
                      s["pixels_over_reference"]["mean"].get<double>(), 100.0 * s["reference_covered_within_1px"]["mean"].get<double>(),
                      100.0 * s["drawn_on_reference_within_1px"]["mean"].get<double>());
        out += line;
    }
    const nlohmann::json& o = p["over_p95"];
    if (o["switch_frames_over"].get<size_t>() > 0) {
        std::snprintf(line, sizeof line,
                      "fidelity: %zu switch frame(s) over the ordinary p95, %zu of them still over with their switching "
                      "characters' pixels taken out\n",
                      o["switch_frames_over"].get<size_t>(), o["over_even_without_the_switching_characters"].get<size_t>());
        out += line;
    }
    const nlohmann::json& e = p["against_reference"];
    const auto verdict = [](const nlohmann::json& v, const char* bad) { return v.is_null() ? "no ordinary frame to compare" : v.get<bool>() ? "ok" : bad; };
    std::snprintf(line, sizeof line,
                  "fidelity against the reference (the change of the LOD's error, the picture's own motion cancelled): switch "
                  "frames' largest %.6f against the ordinary p95 %.6f (%s), detrended p = %.3f (%s); %.1f%% of the switch "
                  "frames' error change inside the switching characters\n",
                  e["switch_error_change_max"].get<double>(), e["ordinary_error_change_p95"].get<double>(),
                  verdict(e["switch_no_worse_than_ordinary_p95"], "OVER"), e["detrended"]["p_value"].get<double>(),
                  verdict(e["detrended"]["no_worse_than_ordinary"], "WORSE"),
                  e["share_inside_switching_characters"].is_null() ? 0.0 : 100.0 * e["share_inside_switching_characters"].get<double>());
    out += line;
    const nlohmann::json& r = p["control"];
    std::snprintf(line, sizeof line,
                  "fidelity control (the reference picture, which switches nothing, on the same frames: the picture's own "
                  "motion): switch frames' largest change %.6f against the ordinary p95 %.6f (%s), detrended p = %.3f (%s); "
                  "the LOD picture's change less the reference's, detrended: p = %.3f (%s)\n",
                  r["switch_change_max"].get<double>(), r["ordinary_change_p95"].get<double>(),
                  verdict(r["switch_no_worse_than_ordinary_p95"], "OVER"), r["detrended"]["p_value"].get<double>(),
                  verdict(r["detrended"]["no_worse_than_ordinary"], "WORSE"),
                  r["raw_less_control"]["detrended"]["p_value"].get<double>(),
                  verdict(r["raw_less_control"]["detrended"]["no_worse_than_ordinary"], "WORSE"));
    return out + line;
}

}  // namespace aloha::tool
