// The profiler's view of the LOD controls: per-frame samples of the budget parts, level switches and
// occlusion, and their summary for report.json and the printed table.
#pragma once

#include "host/scene/world.hpp"
#include "host/tool/cli_args.hpp"
#include "host/tool/stats.hpp"

#include <nlohmann/json.hpp>

#include <array>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

namespace aloha::tool {

/// One frame's LOD-control figures.
struct LodSample {
    double animation_ms = 0;      ///< the animation part's measured time (motion)
    double geometry_ms = 0;       ///< the geometry part's measured time (muscle + spring_skin)
    uint32_t geom_switches = 0;   ///< characters that switched geometric level
    uint32_t anim_switches = 0;   ///< characters that switched animation level
    SwitchCauseCounts causes;     ///< those switches by cause (the rules, the budget's demotions / promotions)
    double cpu_ms = 0;            ///< the CPU systems' time (what a single-total budget steers)
    uint32_t visible = 0;         ///< characters in the view frustum
    uint32_t occluded = 0;        ///< of those, fully occluded by the crowd
    std::array<uint32_t, 5> occlusion_histogram{};  ///< visible characters by occluded: 0, <0.5, <0.9, <1, 1
};

/// Where a series of measured times has settled on `target`: the first index at which its moving
/// average (weight 0.1 per frame, starting at the first value) is within `tolerance` * `target` of
/// the target, or (with `under`) no more than that above it; `values.size()` when it never is.
[[nodiscard]] size_t settled_from(std::span<const double> values, double target, double tolerance, bool under = false);

/// Reads the figures of the frame `world` just ran.
[[nodiscard]] LodSample sample_lod(const World& world);

/// report.json's "tier", "budget", "level_changes_per_second" and "occlusion" members from the
/// measured frames (`dt` seconds each), added to `report`. Each active budget part gets its time over
/// every measured frame and, under "settled", over the frames from where its controller settled
/// (settled_from, 10% of the target); level changes per second are given over every measured frame
/// and over the settled frames (from where every active controller had settled), the settled ones
/// also by cause (level_change_causes_settled: switch_cause_report).
void add_lod_report(const World& world, const std::vector<LodSample>& samples, double dt, nlohmann::json& report);

/// Per second over `samples` (`dt` seconds each): switches by cause per kind (the rules; the budget's
/// demotions, promotions, and those that undid the same character's last budget switch within a second),
/// and the budget's switches split over windows of one second into net (|demotions - promotions|) and
/// swapped (2 min(demotions, promotions)): characters traded at an unchanged count.
[[nodiscard]] nlohmann::json switch_cause_report(std::span<const LodSample> samples, double dt);

/// The geometric controllers' work counters (GeometryController::work) per geometric level, summed
/// over the character types: counters only grow, so the work of a run is the difference of two reads.
[[nodiscard]] std::vector<GeometryWork> geometry_work(const World& world);

/// report.json's "geometry_work": per geometric level the work done from `before` to `after` (two
/// geometry_work() reads) over `frames` frames: characters whose skin stage ran, fat springs stepped
/// and control-surface vertices placed, in all and per frame.
[[nodiscard]] nlohmann::json geometry_work_report(const World& world, std::span<const GeometryWork> before,
                                                  std::span<const GeometryWork> after, uint32_t frames);

/// Lines for the printed summary (tier, budget parts against their targets, switches, occlusion).
[[nodiscard]] std::string lod_summary(const nlohmann::json& report);

/// Runs the scene of `options` again with LOD off (CPU systems only, `options.compare_frames` frames after at
/// most 2 warm-up frames) and compares its CPU systems' time with `lod_on`'s: {frames, cpu_systems_ms,
/// ratio_mean, ratio_p95, target_ratio}, or {error} when the scene cannot be opened. `on_frame(done, total)`
/// is called after each frame (progress).
[[nodiscard]] nlohmann::json compare_lod_off(const CliOptions& options, const SeriesStats& lod_on,
                                             const std::function<void(size_t, size_t)>& on_frame);

}  // namespace aloha::tool
