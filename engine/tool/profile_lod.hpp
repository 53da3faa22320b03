// The profiler's view of the LOD controls: per-frame samples of the budget parts, level switches and
// occlusion, and their summary for report.json and the printed table.
#pragma once

#include "engine/scene/world.hpp"

#include <nlohmann/json.hpp>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace aloha::tool {

/// One frame's LOD-control figures.
struct LodSample {
    double animation_ms = 0;      ///< the animation part's measured time (motion)
    double geometry_ms = 0;       ///< the geometry part's measured time (muscle + spring_skin)
    uint32_t geom_switches = 0;   ///< characters that switched geometric level
    uint32_t anim_switches = 0;   ///< characters that switched animation level
    uint32_t visible = 0;         ///< characters in the view frustum
    uint32_t occluded = 0;        ///< of those, fully occluded by the crowd
    std::array<uint32_t, 5> occlusion_histogram{};  ///< visible characters by occluded: 0, <0.5, <0.9, <1, 1
};

/// Reads the figures of the frame `world` just ran.
[[nodiscard]] LodSample sample_lod(const World& world);

/// report.json's "tier", "budget", "level_changes_per_second" and "occlusion" members from the
/// measured frames (`dt` seconds each), added to `report`.
void add_lod_report(const World& world, const std::vector<LodSample>& samples, double dt, nlohmann::json& report);

/// Lines for the printed summary (tier, budget parts against their targets, switches, occlusion).
[[nodiscard]] std::string lod_summary(const nlohmann::json& report);

}  // namespace aloha::tool
