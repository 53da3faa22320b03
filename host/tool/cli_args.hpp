// Command-line parsing for the aloha tool: GNU-style long options, every problem reported with the
// argument that caused it; no silent defaults for malformed values.
#pragma once

#include "engine/core/result.hpp"
#include "systems/frame/gpu_overlap_policy.hpp"
#include "systems/render/impostor_types.hpp"

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace aloha::tool {

/// Options shared by the subcommands (each subcommand uses the ones that apply to it).
struct CliOptions {
    std::string command;               ///< render | view | profile | scale | export | validate | help
    std::string scene;                 ///< scene file
    std::string out;                   ///< output file (render, export's .glb) or folder (profile)
    std::optional<uint32_t> frames;    ///< --frames N
    uint32_t warmup = 30;              ///< --warmup W
    std::optional<uint32_t> frame;     ///< --frame N (render; export --out)
    std::optional<uint32_t> width, height;
    std::optional<uint64_t> seed;
    bool lod = true;                   ///< --lod on|off
    std::optional<double> budget_ms;   ///< --budget-ms X: total CPU budget (the rule file's parts scaled to it)
    std::optional<double> budget_single_ms;     ///< --budget-single-ms X: one total, single-total controller
    std::optional<double> budget_animation_ms;  ///< --budget-animation-ms X: the animation part's target
    std::optional<double> budget_geometry_ms;   ///< --budget-geometry-ms X: the geometry part's target
    std::optional<bool> budget;        ///< --budget on|off: force the rule file's budget on or off
    std::string tier;                  ///< --tier NAME: hardware tier (default: the rule file's, or auto)
    bool occlusion = true;             ///< --occlusion on|off: estimate occlusion by the crowd
    uint32_t threads = 0;              ///< --threads T (0 = all cores)
    bool cache = true;                 ///< --cache on|off: reuse load-time bakes from the bake cache
    std::string cache_dir;             ///< --cache-dir DIR: the bake cache's directory ("" = the default)
    std::optional<uint64_t> cache_max_bytes;  ///< --cache-max-mb N: the bake cache's size limit (unset: the default)
    std::optional<uint32_t> characters;///< --characters N: rescale the scene's crowds to N characters
    bool fidelity = false;             ///< --fidelity
    bool no_render = false;            ///< --no-render: CPU systems only
    bool force = false;                ///< --force: allow overwriting existing outputs
    std::string colour = "shaded";     ///< --colour shaded|level|rule|method
    std::string device;                ///< --device lavapipe|gpu|INDEX
    std::string overlay;               ///< --overlay bones,muscles,springs (comma list)
    bool validation = false;           ///< --validation: Vulkan validation layers on
    bool help = false;
    bool quiet = false;                ///< --quiet: no progress bar
    bool compare_lod = false;          ///< --compare-lod: also time the scene with LOD off (profile)
    uint32_t compare_frames = 10;      ///< --compare-frames K: frames of the LOD-off run
    std::vector<uint32_t> counts;      ///< --counts A,B,...: crowd sizes (scale)
    bool motion_metrics = false;       ///< --motion-metrics: foot skate and pops per animation level (profile)
    bool gpu_passes = false;           ///< --gpu-passes: per-pass GPU timestamps (profile)
    bool constant_fragments = false;   ///< --constant-fragments: unlit constant-colour fragments (profile)
    std::optional<float> far_layer_px;  ///< --far-layer PX: RendererOptions::far_layer_below_px (unset: far_layer_default)
    std::optional<float> far_layer_meshes_px;  ///< --far-layer-meshes PX: RendererOptions::far_layer_meshes_below_px
                                               ///< (unset: far_layer_meshes_default)
    std::optional<bool> blend_texture_mips;  ///< --texture-mips blend|nearest: RendererOptions::blend_texture_mips (unset: by device)
    std::optional<ImpostorViews> impostor_views;  ///< --impostor-views blend|pick|nearest: RendererOptions::impostor_views (unset: by device)
    std::optional<float> far_layer_alpha_test;  ///< --far-layer-alpha PERCENT / 100: RendererOptions::far_layer_alpha_test (unset: its default)
    std::optional<uint32_t> max_texture_side;  ///< --texture-max PX: RendererOptions::max_texture_side (unset: its default)
    std::optional<float> impostor_share_px;  ///< --impostor-share PX: WorldOptions::impostor_share_px
    std::optional<uint32_t> impostor_elevations;  ///< --impostor-elevations N: WorldOptions::impostor_elevations
    std::optional<float> distant_layer_px;  ///< --distant-layer PX: RendererOptions::distant_layer_below_px (unset: 0)
    GpuOverlap gpu_overlap = GpuOverlap::Auto;  ///< --gpu-overlap on|off|auto: GPU frame overlapped with the next CPU systems (profile)
    std::string joints;                ///< --joints FILE.csv: where export writes joint positions
    /// export --characters LIST: inclusive ranges of spawn indices ("0,5,10-20"); empty = every character
    std::vector<std::pair<uint32_t, uint32_t>> character_ranges;
    /// export --frames A:B: frames A..B-1 (0 = the first frame run); without it 0 to the scene's frames
    std::optional<std::pair<uint32_t, uint32_t>> frame_range;
    std::optional<uint32_t> character;  ///< export --character I: the character whose skin --out writes (spawn index)
    std::optional<uint32_t> level;      ///< export --level L: hold that character at geometric level L
};

/// Parses argv (without argv[0]). Errors name the offending argument.
Result<CliOptions> parse_cli(const std::vector<std::string>& args);

/// Help text for `command` ("" for the overview).
std::string help_text(const std::string& command);

}  // namespace aloha::tool
