// The World: ALOHA's own host of the systems. It spawns a scene's characters as entities in one owning
// group (kept sorted by character type and geometric level), registers the systems with the scheduler by
// what they read and write, and runs one frame per step(). Games with their own entity store call the
// systems' jobs on their own spans instead (docs/INTEGRATION.md).
#pragma once

#include "components/character.hpp"
#include "components/lod.hpp"
#include "components/motion.hpp"
#include "components/transform.hpp"
#include "engine/ecs/ecs.hpp"
#include "host/scene/character_type.hpp"
#include "host/scene/motion_sample.hpp"
#include "host/scene/skin_sample.hpp"
#include "host/scene/scene_desc.hpp"
#include "host/scene/world_phases.hpp"
#include "engine/scheduler/scheduler.hpp"
#include "systems/frame/draw_lists.hpp"
#include "systems/frame/geometry_frame.hpp"
#include "systems/frame/gpu_overlap_policy.hpp"
#include "systems/frame/impostor_share.hpp"
#include "systems/frame/level_groups.hpp"
#include "systems/geometry/controller/geometry_controller.hpp"
#include "systems/lod/attributes.hpp"
#include "systems/lod/budget_driver.hpp"
#include "systems/lod/level_caps.hpp"
#include "systems/lod/occlusion.hpp"
#include "systems/lod/rule_set.hpp"
#include "systems/lod/stats.hpp"
#include "systems/lod/switch_causes.hpp"
#include "systems/lod/tier.hpp"
#include "systems/render/crowd_renderer.hpp"

#include <nlohmann/json_fwd.hpp>

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace aloha {

class CharacterRuntime;

/// The owning group every character belongs to: element i of each span is the same character.
using CharacterGroup = Group<Transform, Velocity, Bounds, Importance, CharacterRef, LodAttributes, LodRequest,
                             LodState, GeomLod, AnimLod, MotionState>;

/// The character group of `registry` (created on first use).
inline CharacterGroup character_group(Registry& registry) {
    return registry.group<Transform, Velocity, Bounds, Importance, CharacterRef, LodAttributes, LodRequest,
                          LodState, GeomLod, AnimLod, MotionState>();
}

/// How a World is built and run.
struct WorldOptions {
    unsigned threads = 0;                  ///< scheduler threads (0 = all cores)
    bool lod = true;                       ///< false: every character at level 0 (full detail) always
    std::optional<bool> budget;            ///< force the frame budget on/off (default: as the rule file says)
    std::optional<double> budget_ms;       ///< total CPU budget; overrides the rule file's (its parts are
                                           ///< scaled to sum to it; a file without parts gets one total)
    std::optional<double> budget_single_ms;     ///< one total for the CPU systems (the single-total controller),
                                                ///< whatever the rule file's budget says
    std::optional<double> budget_animation_ms;  ///< animation part's target; overrides the rule file's
    std::optional<double> budget_geometry_ms;   ///< geometry part's target; overrides the rule file's
    bool occlusion = true;                 ///< estimate LodAttributes::occluded from the crowd (lod_occlusion)
    std::optional<std::string> tier;       ///< tier name; overrides the rule file's default_tier and "auto"
    std::optional<HardwareInfo> hardware;  ///< facts for "default_tier": "auto" (without: the richest tier)
    uint64_t seed_override = 0;            ///< != 0 replaces every crowd's seed
    std::optional<uint32_t> characters;    ///< rescale crowds to this many characters in all
    DebugColour colour = DebugColour::Shaded;
    uint8_t overlay = 0;                   ///< OverlayBits: bones, muscle outlines, fat springs
    bool keep_refined_surfaces = true;     ///< false (runs with no renderer): subdivided skins are
                                           ///< computed each frame but not kept (see GeometryController)
    GpuOverlap overlap_gpu = GpuOverlap::Off;  ///< On: the render system submits the frame and returns, so the GPU
                                           ///< draws it while the next step()'s CPU systems run (the renderer
                                           ///< waits for a frame slot when it comes round again); Auto: so
                                           ///< while the GPU's frame is long (GpuOverlapPolicy); read back the
                                           ///< target on the renderer's queue or after finish_rendering()
    bool bake_cache = true;                ///< reuse the character types' load-time bakes (generated skins) from
                                           ///< the on-disk bake cache and save new ones there (false: always build)
    std::optional<std::string> bake_cache_dir;  ///< the bake cache's directory; default: $ALOHA_CACHE_DIR, else
                                                ///< $XDG_CACHE_HOME/aloha, else $HOME/.cache/aloha
    std::optional<uint64_t> bake_cache_max_bytes;  ///< the bake cache's size limit (0: none); default:
                                                   ///< $ALOHA_CACHE_MAX_MB MiB, else 1 GiB (least recently used go first)
    uint32_t impostor_elevations = 3;      ///< bands of views in each type's impostor atlas, 1 to 8: level views
                                           ///< only (1), or n evenly from level to straight down (the default 3:
                                           ///< 0, 45 and 90 degrees; each band one level atlas's memory and bake)
    /// A type whose impostor bake input lies within this many atlas pixels of one already baked, scaled
    /// (impostor_share_between: a file character's height variants), draws that atlas scaled instead of baking
    /// its own; 0: every type bakes its own.
    float impostor_share_px = kImpostorShareTolerancePx;
    bool pose_every_character = false;     ///< true: every character's pose is current every frame, seen or
                                           ///< not (tools that read every pose: motion metrics, export);
                                           ///< false: poses nobody reads are left out (PoseUse)
};

/// Hosts a scene's characters and systems. Not copyable; one thread drives step().
class World {
public:
    /// Loads the character types and rules a scene names, spawns its characters and builds the
    /// system plan. Errors name the file and the problem.
    static Result<std::unique_ptr<World>> create(const SceneDesc& scene, const WorldOptions& options);
    ~World();
    World(const World&) = delete;
    World& operator=(const World&) = delete;

    /// Runs one frame of every system (CPU phases; the Render phase too when a renderer is attached).
    void step();
    /// Fidelity: from the next step() on, after each frame's systems (outside their timings), every
    /// character at a mesh level also carries the fat springs of geometric level 0, the deviation's
    /// reference (GeometryController::step_reference_springs), so the deviation can be read against the
    /// full-detail body with its own fat motion. Off drops them. Costs a level-0 skin per mesh character.
    void set_reference_springs(bool on);
    /// Attaches a renderer and target for the Render phase (mesh topologies are registered with it on
    /// first use); nullptr detaches.
    Status attach_renderer(CrowdRenderer* renderer, gpu::OffscreenTarget* target);
    /// Waits until the GPU has drawn every frame submitted so far (only an overlapped frame leaves any in flight)
    /// and makes last_gpu_ms() the newest frame's. Errors: Vulkan failures.
    Status finish_rendering();
    /// The view the LOD is computed for: from the next step() on, `key` seen with a vertical field of
    /// view of `fov_y_deg` on a `viewport` (pixels) replaces the scene's camera path (a viewer's free
    /// camera, a resized window). std::nullopt returns to the scene camera.
    void set_view_override(std::optional<CameraKey> key, float fov_y_deg, glm::vec2 viewport) {
        view_override_ = key;
        override_fov_deg_ = fov_y_deg;
        override_viewport_ = viewport;
    }
    /// Debug colouring of the draw lists from the next frame on.
    void set_colour(DebugColour colour) { options_.colour = colour; }
    /// Debug overlays (OverlayBits) from the next frame on.
    void set_overlay(uint8_t overlay) { options_.overlay = overlay; }

    /// Frames run so far / simulated seconds.
    [[nodiscard]] uint64_t frame() const { return frame_; }
    [[nodiscard]] float time() const { return time_; }
    [[nodiscard]] const SceneDesc& scene() const { return scene_; }
    [[nodiscard]] const WorldOptions& options() const { return options_; }
    /// Number of characters alive.
    [[nodiscard]] size_t character_count() const;
    /// The ECS registry and the scheduler (timings, plan, trace).
    [[nodiscard]] Registry& registry() { return registry_; }
    [[nodiscard]] Scheduler& scheduler() { return scheduler_; }
    [[nodiscard]] const Scheduler& scheduler() const { return scheduler_; }
    /// The knowledge base (reload it live with rules().reload_from_file() or poll()).
    [[nodiscard]] RuleSet& rules() { return rules_; }
    [[nodiscard]] const RuleSet& rules() const { return rules_; }
    /// Characters per level / method / rule after the last frame.
    [[nodiscard]] const LodStats& lod_stats() const { return stats_; }
    /// Camera used by the last frame (LOD view) and its render matrices.
    [[nodiscard]] const LodCamera& camera() const { return camera_; }
    [[nodiscard]] RenderCamera render_camera() const;
    /// Sets `frame`'s camera (render_camera()), character lighting (set_character_lighting) and whether
    /// materials are drawn (in the shaded colouring; debug colourings show their palette alone).
    void frame_settings(FrameInput& frame) const;
    /// The last frame's draw lists.
    [[nodiscard]] const RenderLists& render_lists() const { return lists_; }
    /// GPU ms of the newest frame the GPU has finished (-1 without a renderer): the last Render phase's,
    /// or when overlapped an earlier frame's until finish_rendering().
    [[nodiscard]] double last_gpu_ms() const { return last_gpu_ms_; }
    /// The last frame's CPU systems (every phase before Render), ms: what a single-total budget steers.
    [[nodiscard]] double last_cpu_ms() const { return last_cpu_ms_; }
    /// Frame pacing against the GPU (WorldOptions::overlap_gpu): the last frame's decision, the smoothed times.
    [[nodiscard]] const GpuOverlapPolicy& gpu_overlap() const { return overlap_policy_; }
    /// The last frame's animation part (the motion system), ms.
    [[nodiscard]] double last_animation_ms() const { return last_animation_ms_; }
    /// The last frame's geometry part (the muscle and spring_skin systems), ms.
    [[nodiscard]] double last_geometry_ms() const { return last_geometry_ms_; }
    /// Characters that switched geometric [0] / animation [1] level in the last frame.
    [[nodiscard]] std::array<uint32_t, 2> last_level_switches() const { return {switches_[0], switches_[1]}; }
    /// The last frame's level switches by cause (the rules or the budget's edits; SwitchCauseJob).
    [[nodiscard]] const SwitchCauseCounts& last_switch_causes() const { return switch_causes_; }
    /// The frame budget's mode, settings and state.
    [[nodiscard]] BudgetStatus budget_status() const { return budget_.status(); }
    /// The hardware tier the rules are evaluated at, and why.
    [[nodiscard]] const TierChoice& tier() const { return tier_; }
    /// Outcome of the last Render phase (Vulkan errors surface here, not as exceptions).
    [[nodiscard]] const Status& render_status() const { return render_status_; }
    /// Why character `i` (group order) has its levels, as JSON (attributes, rule, levels).
    [[nodiscard]] nlohmann::json explain(uint32_t i) const;
    /// The renderer attached (nullptr without) and the builder of the draw lists with its topology cache.
    [[nodiscard]] CrowdRenderer* renderer() const { return renderer_; }
    [[nodiscard]] DrawListBuilder& draw_lists() { return draws_; }
    /// Per type: what the draw lists need (refreshed each step).
    [[nodiscard]] std::span<const DrawType> draw_types() const { return draw_types_; }
    /// Fills `out` with character `index` (spawn order: types in scene order, then id) as the last
    /// frame left it. Requires index < character_count().
    void motion_sample(uint32_t index, MotionSample& out) const;
    /// Fills `out` with character `index`'s (spawn order) displayed body as the last frame left it, in
    /// world space (world_skin.cpp): its level's skin (positions, normals, triangles), or the boxes of a
    /// rigid proxy; empty triangles when the level draws no mesh (hidden, impostor) or before its first
    /// frame. Requires index < character_count().
    void skin_sample(uint32_t index, SkinSample& out) const;
    /// Holds character `index` (spawn order) at geometric level `level` from the next step() on,
    /// whatever the rules, the caps and the budget say (the budget never demotes it). Errors (as
    /// ErrorKind::Option, path "character" or "level") name the valid range.
    Status pin_geom_level(uint32_t index, uint8_t level);
    /// One baked impostor atlas (attach_renderer bakes one per type when the rules have an impostor level).
    struct ImpostorReport {
        std::string type;             ///< the character type
        uint32_t width = 0, height = 0; ///< atlas pixels (colour and normal halves)
        double build_ms = 0.0;        ///< bake wall time (posing, reference surfaces, GPU frames, read-back, upload)
        uint64_t texture_bytes = 0;   ///< mipmapped texture memory
        bool cached = false;          ///< read back from the bake cache (build_ms: posing, the read and the upload)
        /// The type whose atlas this one draws, scaled (impostor_share_between found the two within the
        /// tolerance); empty when it has its own. texture_bytes is 0 then: no memory of its own.
        std::string shared_from;
        float scale = 1.0f;           ///< with shared_from: its atlas drawn this many times as large
        float distance_px = 0.0f;     ///< with shared_from: the largest distance found, in that atlas's pixels
    };
    /// The atlases baked for the attached renderer.
    [[nodiscard]] std::span<const ImpostorReport> impostor_atlases() const { return impostor_reports_; }
    /// The bake cache this world reads its types' bakes and atlases from and saves them to (nullptr: off).
    [[nodiscard]] const BlobStore* bake_cache() const { return bake_cache_.get(); }
    /// Number of character types and each one's data.
    [[nodiscard]] size_t type_count() const { return types_.size(); }
    [[nodiscard]] const CharacterType& type(size_t i) const;
    /// Type `i`'s controllers (motion, geometry) and its id -> group element map.
    [[nodiscard]] const CharacterRuntime& runtime(size_t i) const { return *types_[i]; }

private:
    World() = default;
    Status load(const SceneDesc& scene, const WorldOptions& options);
    Status spawn_characters();
    Status apply_rule_settings();
    void register_systems();
    void regroup();
    void refresh_type_views();
    /// Forgets the registered draw topologies, labels each level's GPU pass with its rule-file name and, with a
    /// renderer, registers every type's materials and mesh levels again (DrawListBuilder::prepare).
    Status reset_draws();
    /// reset_draws(), build_impostors(), then the renderer's warm-up (attach_renderer and a rules reload).
    Status prepare_drawing();
    /// Bakes and registers the impostor atlas of every type not baked yet (rules with an impostor level
    /// and a renderer attached; world_impostors.cpp).
    Status build_impostors();
    /// Fills pose_use_ for this frame (motion system): which poses the later stages read.
    void mark_pose_use(SystemContext& ctx, std::span<const CharacterRef> refs, std::span<const LodState> states);
    /// Type index and id of spawn index `index` (< character_count()).
    [[nodiscard]] std::pair<size_t, uint32_t> spawn_character(uint32_t index) const;
    /// Writes the pinned character's request (pin_geom_level) into `requests` and marks its state
    /// always_full (the resolve phase).
    void apply_level_pin(std::span<LodRequest> requests, std::span<LodState> states) const;

    SceneDesc scene_;
    WorldOptions options_;
    Registry registry_;
    Scheduler scheduler_{world_phases()};
    RuleSet rules_;
    LodBudget budget_;
    LevelCapScratch caps_scratch_;
    OcclusionGrid occlusion_grid_;
    TierChoice tier_;
    std::vector<uint64_t> geom_level_ns_;            ///< this frame: muscle + skin time per geometric level
    std::vector<double> geom_level_ms_;              ///< the last frame's, ms (what the geometry budget learns from)
    std::vector<uint64_t> anim_level_ns_;            ///< this frame: motion time per animation level and cost class (anim_cost_slot)
    std::vector<double> anim_level_ms_;              ///< the last frame's, ms (what the animation budget learns from)
    std::vector<uint8_t> walking_;                   ///< each character's animation cost class (1: walking), for the budget
    uint32_t switches_[2] = {0, 0};
    SwitchCauseCounts switch_causes_;                ///< this frame's switches by cause
    std::vector<SwitchRecord> switch_records_;       ///< per character (spawn index): its last switches' demotions
    std::vector<uint32_t> switch_keys_;              ///< this frame's changed characters' spawn indices (scratch)
    std::vector<uint32_t> type_first_;               ///< spawn index of each type's first character
    uint32_t applied_rules_generation_ = 0;          ///< RuleSet::generation() whose settings are in force
    int motion_system_ = -1, muscle_system_ = -1, skin_system_ = -1;
    double last_animation_ms_ = 0.0, last_geometry_ms_ = 0.0;
    LodStats stats_;
    LodCamera camera_;
    std::vector<std::unique_ptr<CharacterRuntime>> types_;
    CharacterGroups groups_;                         ///< (type, level) grouping; the group is kept sorted by
                                                     ///< it, so element == position (order[p] == p)
    std::vector<GeometryType> geometry_types_;       ///< per type: controller and poses (frame glue)
    std::vector<DrawType> draw_types_;               ///< per type: what the draw lists need
    std::vector<uint32_t> due_ids_;                  ///< per-frame scratch: characters needing geometry work
    std::vector<uint32_t> changed_;
    std::vector<uint8_t> pose_use_;                  ///< per-frame scratch: PoseUse per element (motion)
    std::vector<std::array<uint32_t, 3>> resolve_blocks_;  ///< per-frame scratch: the resolver's per-block counts
    size_t elements_mapped_ = SIZE_MAX;              ///< characters element_of_character was last filled for
    DrawListBuilder draws_;                          ///< draw lists and the renderer's topology cache
    RenderLists lists_;
    std::vector<ImpostorReport> impostor_reports_;   ///< atlases baked for renderer_, by type order
    std::vector<uint8_t> impostor_built_;            ///< per type: baked for renderer_
    std::shared_ptr<const BlobStore> bake_cache_;    ///< the types' bakes and the impostor atlases (none: off)
    CrowdRenderer* renderer_ = nullptr;
    gpu::OffscreenTarget* target_ = nullptr;
    double last_gpu_ms_ = -1.0;
    std::optional<CameraKey> view_override_;
    float override_fov_deg_ = 50.0f;
    glm::vec2 override_viewport_{1280.0f, 720.0f};
    Status render_status_;
    double last_cpu_ms_ = 0.0;
    GpuOverlapPolicy overlap_policy_;
    std::optional<std::pair<uint32_t, uint8_t>> pin_;  ///< spawn index, geometric level (pin_geom_level)
    uint64_t frame_ = 0;
    float time_ = 0.0f;
    bool first_frame_ = true;
    bool reference_springs_ = false;                  ///< set_reference_springs
    void step_reference_springs();                    ///< world_fidelity.cpp
};

}  // namespace aloha
