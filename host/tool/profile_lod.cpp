#include "host/tool/profile_lod.hpp"

#include "host/scene/character_runtime.hpp"
#include "host/tool/session.hpp"
#include "host/tool/stats.hpp"

#include <algorithm>
#include <cmath>
#include <span>
#include <iomanip>
#include <sstream>

namespace aloha::tool {

LodSample sample_lod(const World& world) {
    LodSample s;
    s.animation_ms = world.last_animation_ms();
    s.geometry_ms = world.last_geometry_ms();
    const auto switches = world.last_level_switches();
    s.geom_switches = switches[0];
    s.anim_switches = switches[1];
    s.causes = world.last_switch_causes();
    s.cpu_ms = world.last_cpu_ms();
    s.visible = world.lod_stats().visible;
    s.occluded = world.lod_stats().occluded;
    s.occlusion_histogram = world.lod_stats().occlusion_histogram;
    return s;
}

size_t settled_from(std::span<const double> values, double target, double tolerance, bool under) {
    double average = values.empty() ? 0.0 : values[0];
    for (size_t i = 0; i < values.size(); ++i) {
        average += 0.1 * (values[i] - average);
        const double off = average - target;
        if (off <= tolerance * target && (under || off >= -tolerance * target)) return i;
    }
    return values.size();
}

namespace {

constexpr double kSettled = 0.1;  // the criterion: within 10% of the target

// A series against a target: stats, mean / target, whether the mean is within 10%, frames within 10%.
nlohmann::json against_target(std::span<const double> v, double target) {
    nlohmann::json j = to_json(summarize(v));
    size_t within = 0;
    for (double x : v) within += std::fabs(x - target) <= kSettled * target;
    const double mean = j["mean"].get<double>();
    j["mean_over_target"] = target > 0 ? mean / target : 0.0;
    j["mean_within_10_percent"] = std::fabs(mean - target) <= kSettled * target;
    j["frames_within_10_percent"] = v.empty() ? 0.0 : double(within) / double(v.size());
    return j;
}

// A part's measured series against its target, over every frame and from where it settled (`from`).
nlohmann::json part_json(const std::vector<double>& v, size_t from, double dt, const BudgetStatus::Part& p) {
    nlohmann::json j = to_json(summarize(v));
    j["active"] = p.active;
    if (!p.active) return j;
    j = against_target(v, p.target_ms);
    j["active"] = true;
    j["target_ms"] = p.target_ms;
    j["band_ms_at_end"] = p.band_ms;
    j["trigger_band_ms_at_end"] = p.trigger_band_ms;
    j["noise_sigma_ms_at_end"] = p.noise_sigma_ms;
    // One list per cost class, each indexed by level (animation: walkers apart from the rest).
    auto by_class = [&](const std::vector<double>& slots, size_t c) {
        std::vector<double> out;
        for (size_t s = c; s < slots.size(); s += std::max<size_t>(1, p.classes)) out.push_back(slots[s]);
        return out;
    };
    const bool walkers_apart = p.classes == kAnimCostClasses;
    j["learned_cost_ms_per_character"] = by_class(p.level_cost_ms, walkers_apart ? 1 : 0);
    j["learned_marginal_ms_per_character"] = by_class(p.level_marginal_ms, walkers_apart ? 1 : 0);
    if (walkers_apart) {  // the lists above are the walkers'
        j["learned_cost_ms_per_character_not_walking"] = by_class(p.level_cost_ms, 0);
        j["learned_marginal_ms_per_character_not_walking"] = by_class(p.level_marginal_ms, 0);
    }
    if (from >= v.size()) {
        j["settled"] = nullptr;
        return j;
    }
    nlohmann::json settled = against_target(std::span<const double>(v).subspan(from), p.target_ms);
    settled["from_frame"] = from;
    settled["after_seconds"] = double(from) * dt;
    j["settled"] = settled;
    return j;
}

}  // namespace

nlohmann::json switch_cause_report(std::span<const LodSample> samples, double dt) {
    const double seconds = double(samples.size()) * dt;
    const size_t window = dt > 0 ? std::max<size_t>(1, size_t(std::lround(1.0 / dt))) : 1;
    nlohmann::json out = nlohmann::json::object();
    const char* kinds[2] = {"geometric", "animation"};
    SwitchCauseCounts sum;
    for (const LodSample& s : samples) sum.add(s.causes);
    for (size_t k = 0; k < 2; ++k) {
        double net = 0, swapped = 0, down = 0, up = 0;
        for (size_t i = 0; i < samples.size(); ++i) {
            down += samples[i].causes.budget_down[k], up += samples[i].causes.budget_up[k];
            if ((i + 1) % window == 0 || i + 1 == samples.size()) {
                net += std::fabs(down - up), swapped += 2.0 * std::min(down, up);
                down = up = 0;
            }
        }
        auto per_s = [&](double x) { return seconds > 0 ? x / seconds : 0.0; };
        out[kinds[k]] = {{"rules", per_s(sum.rules[k])},
                         {"budget_demotions", per_s(sum.budget_down[k])},
                         {"budget_promotions", per_s(sum.budget_up[k])},
                         {"budget_undone_within_1s", per_s(sum.undone[k])},
                         {"budget_net_per_1s_window", per_s(net)},
                         {"budget_swapped_per_1s_window", per_s(swapped)}};
    }
    return out;
}

void add_lod_report(const World& world, const std::vector<LodSample>& samples, double dt, nlohmann::json& report) {
    const RuleTable& table = world.rules().table();
    const TierChoice& tier = world.tier();
    report["tier"] = {{"name", tier.tier < table.tiers.size() ? table.tiers[tier.tier] : std::string("?")},
                      {"index", tier.tier},
                      {"reason", tier.reason}};
    const BudgetStatus b = world.budget_status();
    std::vector<double> anim, geom;
    double geom_switches = 0, anim_switches = 0, occluded_fraction = 0;
    uint64_t occluded = 0, visible = 0;
    std::array<double, 5> histogram{};
    for (const LodSample& s : samples) {
        for (size_t k = 0; k < histogram.size(); ++k) histogram[k] += double(s.occlusion_histogram[k]) / double(samples.size());
        anim.push_back(s.animation_ms);
        geom.push_back(s.geometry_ms);
        geom_switches += s.geom_switches;
        anim_switches += s.anim_switches;
        occluded += s.occluded;
        visible += s.visible;
        occluded_fraction += s.visible ? double(s.occluded) / double(s.visible) : 0.0;
    }
    std::vector<double> cpu;
    for (const LodSample& s : samples) cpu.push_back(s.cpu_ms);
    const size_t anim_from = b.animation.active ? settled_from(anim, b.animation.target_ms, kSettled) : 0;
    const size_t geom_from = b.geometry.active ? settled_from(geom, b.geometry.target_ms, kSettled) : 0;
    // Where every active controller had settled: both parts, or the single total (which aims under its
    // target and promotes only below target * (1 - deadband): settled once no more than 10% over).
    size_t from = 0;
    if (b.mode == BudgetStatus::Mode::Parts) from = std::max(anim_from, geom_from);
    if (b.mode == BudgetStatus::Mode::Total) from = settled_from(cpu, b.params.target_ms, kSettled, true);
    const char* mode = b.mode == BudgetStatus::Mode::Parts ? "parts" : b.mode == BudgetStatus::Mode::Total ? "total" : "off";
    nlohmann::json budget = {{"mode", mode}};
    if (b.mode == BudgetStatus::Mode::Total) budget["target_ms"] = b.params.target_ms;
    if (b.mode == BudgetStatus::Mode::Parts) {
        budget["trim_smoothing"] = b.params.trim_smoothing;
        budget["dwell"] = b.params.dwell;
        budget["confidence"] = b.params.confidence;
    }
    budget["animation"] = part_json(anim, anim_from, dt, b.animation);
    budget["geometry"] = part_json(geom, geom_from, dt, b.geometry);
    budget["settled_from_frame"] = from < samples.size() ? nlohmann::json(from) : nlohmann::json(nullptr);
    report["budget"] = budget;
    const double seconds = double(samples.size()) * dt;
    double settled_geom = 0, settled_anim = 0;
    for (size_t i = from; i < samples.size(); ++i) settled_geom += samples[i].geom_switches, settled_anim += samples[i].anim_switches;
    const double settled_seconds = from < samples.size() ? double(samples.size() - from) * dt : 0.0;
    report["level_changes_per_second"] = {{"geometric", seconds > 0 ? geom_switches / seconds : 0.0},
                                          {"animation", seconds > 0 ? anim_switches / seconds : 0.0}};
    report["level_changes_per_second_settled"] =
        settled_seconds > 0 ? nlohmann::json{{"geometric", settled_geom / settled_seconds},
                                             {"animation", settled_anim / settled_seconds},
                                             {"seconds", settled_seconds}}
                            : nlohmann::json(nullptr);
    report["level_change_causes_settled"] =
        settled_seconds > 0 ? switch_cause_report(std::span<const LodSample>(samples).subspan(from), dt) : nlohmann::json(nullptr);
    report["occlusion"] = {{"enabled", world.options().occlusion},
                           {"fully_occluded_per_frame", samples.empty() ? 0.0 : double(occluded) / double(samples.size())},
                           {"visible_per_frame", samples.empty() ? 0.0 : double(visible) / double(samples.size())},
                           {"fraction_of_visible", samples.empty() ? 0.0 : occluded_fraction / double(samples.size())},
                           {"visible_by_occluded_fraction_per_frame",
                            {{"0", histogram[0]}, {"below_0.5", histogram[1]}, {"0.5_to_0.9", histogram[2]},
                             {"0.9_to_1", histogram[3]}, {"1", histogram[4]}}}};
}

std::vector<GeometryWork> geometry_work(const World& world) {
    std::vector<GeometryWork> out(world.rules().table().geom_levels.size());
    for (size_t t = 0; t < world.type_count(); ++t) {
        const GeometryController* gc = world.runtime(t).geometry.get();
        if (!gc) continue;
        for (uint8_t l = 0; l < gc->level_count() && l < out.size(); ++l) {
            const GeometryWork w = gc->work(l);
            out[l].characters += w.characters;
            out[l].springs_stepped += w.springs_stepped;
            out[l].skin_vertices += w.skin_vertices;
        }
    }
    return out;
}

nlohmann::json geometry_work_report(const World& world, std::span<const GeometryWork> before, std::span<const GeometryWork> after,
                                    uint32_t frames) {
    nlohmann::json levels = nlohmann::json::array();
    const auto& names = world.rules().table().geom_levels;
    const double per = frames > 0 ? 1.0 / frames : 0.0;
    for (size_t l = 0; l < after.size() && l < before.size(); ++l) {
        const uint64_t characters = after[l].characters - before[l].characters;
        const uint64_t springs = after[l].springs_stepped - before[l].springs_stepped;
        const uint64_t vertices = after[l].skin_vertices - before[l].skin_vertices;
        levels.push_back({{"level", l < names.size() ? names[l].name : std::to_string(l)},
                          {"characters_updated", characters},
                          {"springs_stepped", springs},
                          {"skin_vertices", vertices},
                          {"per_frame", {{"characters_updated", characters * per}, {"springs_stepped", springs * per},
                                         {"skin_vertices", vertices * per}}}});
    }
    return levels;
}

std::string lod_summary(const nlohmann::json& r) {
    std::ostringstream o;
    o << std::fixed << std::setprecision(3);
    o << "tier " << r["tier"]["name"].get<std::string>() << " (" << r["tier"]["reason"].get<std::string>() << ")\n";
    const auto& b = r["budget"];
    o << "budget " << b["mode"].get<std::string>();
    if (b["mode"] == "total") o << ", target " << b["target_ms"].get<double>() << " ms (CPU systems)";
    o << "\n";
    for (const char* part : {"animation", "geometry"}) {
        const auto& p = b[part];
        o << "  " << std::left << std::setw(10) << part << std::right << " mean " << p["mean"].get<double>() << " ms";
        if (p["active"].get<bool>()) {
            o << ", target " << p["target_ms"].get<double>() << " ms, mean/target " << p["mean_over_target"].get<double>()
              << (p["mean_within_10_percent"].get<bool>() ? " (within 10%)" : " (NOT within 10%)") << ", frames within 10% "
              << p["frames_within_10_percent"].get<double>();
            const auto& st = p["settled"];
            if (st.is_null()) o << "\n             never settled (its moving average never within 10% of the target)";
            else
                o << "\n             settled after " << st["after_seconds"].get<double>() << " s: mean " << st["mean"].get<double>()
                  << " ms, p95 " << st["p95"].get<double>() << " ms, mean/target " << st["mean_over_target"].get<double>()
                  << (st["mean_within_10_percent"].get<bool>() ? " (within 10%)" : " (NOT within 10%)")
                  << ", frames within 10% " << st["frames_within_10_percent"].get<double>();
        }
        o << "\n";
    }
    o << std::setprecision(1) << "level changes per second: geometric " << r["level_changes_per_second"]["geometric"].get<double>()
      << ", animation " << r["level_changes_per_second"]["animation"].get<double>();
    if (const auto& st = r["level_changes_per_second_settled"]; !st.is_null() && b["mode"] != "off")
        o << "; settled (last " << st["seconds"].get<double>() << " s): geometric " << st["geometric"].get<double>()
          << ", animation " << st["animation"].get<double>();
    o << "\n";
    if (const auto& c = r["level_change_causes_settled"]; !c.is_null() && b["mode"] != "off")
        for (const char* kind : {"geometric", "animation"})
            o << "  " << kind << " settled by cause: rules " << c[kind]["rules"].get<double>() << ", budget down "
              << c[kind]["budget_demotions"].get<double>() << " / up " << c[kind]["budget_promotions"].get<double>()
              << " (undone within 1 s " << c[kind]["budget_undone_within_1s"].get<double>() << "; per 1 s window net "
              << c[kind]["budget_net_per_1s_window"].get<double>() << ", swapped " << c[kind]["budget_swapped_per_1s_window"].get<double>()
              << ")\n";
    const auto& occ = r["occlusion"];
    if (occ["enabled"].get<bool>())
        o << "occlusion: " << occ["fully_occluded_per_frame"].get<double>() << " of " << occ["visible_per_frame"].get<double>()
          << " visible characters fully occluded per frame (" << std::setprecision(3)
          << 100.0 * occ["fraction_of_visible"].get<double>() << "%)\n";
    return o.str();
}

nlohmann::json compare_lod_off(const CliOptions& options, const SeriesStats& lod_on, const std::function<void(size_t, size_t)>& on_frame) {
    CliOptions off = options;
    off.lod = false;
    off.no_render = true;
    auto opened = open_session(off, /*render=*/false);
    if (!opened.ok()) return {{"error", opened.error().to_string()}};
    World& world = *opened.value()->world;
    for (uint32_t f = 0; f < std::min<uint32_t>(options.warmup, 2); ++f) world.step();
    std::vector<double> cpu;
    for (uint32_t f = 0; f < options.compare_frames; ++f) {
        world.step();
        cpu.push_back(world.last_cpu_ms());
        on_frame(f + 1, options.compare_frames);
    }
    const SeriesStats st = summarize(cpu);
    return {{"frames", options.compare_frames},
            {"cpu_systems_ms", to_json(st)},
            {"ratio_mean", lod_on.mean > 0 ? st.mean / lod_on.mean : 0.0},
            {"ratio_p95", lod_on.p95 > 0 ? st.p95 / lod_on.p95 : 0.0},
            {"target_ratio", 20.0}};
}

}  // namespace aloha::tool
