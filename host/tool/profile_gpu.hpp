// The profiler's view of the renderer: per frame the upload (CPU copies into mapped buffers), draw calls and,
// with --gpu-passes, each GPU pass's timestamps; summarised for report.json, trace.json and the printed table.
#pragma once

#include "engine/scheduler/timing.hpp"
#include "systems/render/crowd_renderer.hpp"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace aloha::tool {

/// One frame's render figures.
struct GpuSample {
    double upload_ms = 0;            ///< CPU time copying the frame into the mapped buffers
    uint64_t upload_bytes = 0;       ///< bytes copied
    uint32_t draws = 0;              ///< draw calls recorded
    uint32_t drawn_twice = 0;        ///< characters drawn at two levels (cross-fades: RenderLists::drawn_twice)
    double gpu_ms = -1;              ///< whole-frame GPU time (first to last timestamp)
    std::vector<GpuPassTime> passes; ///< per pass (empty without --gpu-passes)
};

/// Reads the figures of the frame `renderer` last completed.
[[nodiscard]] GpuSample sample_gpu(const CrowdRenderer& renderer);

/// report.json's "render_passes": {"upload_ms", "upload_mib", "draws", "drawn_twice"} statistics and, per pass name, the
/// statistics of its ms over the frames it ran in, with its mean draws, instances and triangles.
[[nodiscard]] nlohmann::json gpu_report(const std::vector<GpuSample>& samples);

/// Lines for the printed table (same columns as the systems: mean p50 p95 p99 max), upload first.
[[nodiscard]] std::string gpu_table(const nlohmann::json& render_passes);

/// report.json's "renderer": the settings `resolved` (CrowdRenderer::resolved_options) draws with and the atlases'
/// bands of views, each default resolved for the device, so that reports from different machines say what was drawn:
/// far_layer_px, far_layer_meshes_px, distant_layer_px (0: off), far_layer_alpha_test, texture_mips and
/// impostor_views (their words on the command line), max_texture_side, constant_fragments, impostor_elevations.
[[nodiscard]] nlohmann::json renderer_report(const RendererOptions& resolved, uint32_t impostor_elevations);

/// The printed line for a "renderer" report ("renderer: far layer under 70 px, ...").
[[nodiscard]] std::string renderer_line(const nlohmann::json& renderer);

/// Appends TraceKind::Gpu events for each sampled frame's passes to `trace`, naming them after `names`
/// (pass names are appended to it). GPU timestamps have no common clock with the CPU here, so each frame's
/// passes are placed to end when frame `frame`'s run of system `render_system` ended (the renderer waits for
/// the GPU inside it): a pass's length is exact, its position within a few tens of µs.
void add_gpu_trace(const std::vector<GpuSample>& samples, uint32_t render_system, std::vector<TraceEvent>& trace,
                   std::vector<std::string>& names);

}  // namespace aloha::tool
