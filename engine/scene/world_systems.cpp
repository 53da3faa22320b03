// The World's systems: each declares what it reads and writes; the scheduler derives the passes.
#include "engine/scene/character_runtime.hpp"
#include "engine/scene/world.hpp"
#include "systems/lod/resolver.hpp"
#include "systems/lod/rule_eval.hpp"
#include "systems/lod/rule_table.hpp"

#include <functional>

namespace aloha {

namespace {
// Resources that are not components, named for the scheduler's access sets.
struct CameraResource {};
struct RuleResource {};
struct PoseResource {};
struct MuscleSurfaceResource {};
struct SurfaceResource {};
struct DrawListResource {};
struct GpuResource {};

// Characters per parallel chunk for the cheap per-character LOD loops.
constexpr size_t kLodGrain = 2048;

}  // namespace

void World::register_systems() {
    const std::vector<ComponentTypeId> everything_in_group =
        writes<Transform, Velocity, Bounds, Importance, CharacterRef, LodAttributes, LodRequest, LodState, GeomLod,
               AnimLod, MotionState>();

    scheduler_.add({"lod_attributes", Phase::Attributes,
                    reads<Transform, Velocity, Bounds, Importance, CameraResource>(), writes<LodAttributes>(),
                    [this](SystemContext& ctx) {
                        auto g = character_group(registry_);
                        ctx.parallel_for(g.size(), kLodGrain, [&](size_t b, size_t e) {
                            LodAttributesJob job;
                            job.transforms = g.span<Transform>().subspan(b, e - b);
                            job.velocities = g.span<Velocity>().subspan(b, e - b);
                            job.bounds = g.span<Bounds>().subspan(b, e - b);
                            job.importance = g.span<Importance>().subspan(b, e - b);
                            job.camera = camera_;
                            job.output = g.span<LodAttributes>().subspan(b, e - b);
                            job.Run();
                        });
                    }});

    // Occlusion by the crowd itself: a coarse depth grid of nearer characters' cores (systems/lod/occlusion.hpp).
    if (options_.occlusion) {
        scheduler_.add({"lod_occlusion", Phase::Rules, reads<Transform, Bounds, GeomLod, CameraResource>(), writes<LodAttributes>(),
                        [this](SystemContext&) {
                            auto g = character_group(registry_);
                            OcclusionJob job;
                            job.transforms = g.span<Transform>();
                            job.bounds = g.span<Bounds>();
                            job.geom = g.span<GeomLod>();
                            job.camera = camera_;
                            job.grid = &occlusion_grid_;
                            job.attributes = g.span<LodAttributes>();
                            job.Run();
                        }});
    }

    scheduler_.add({"lod_rules", Phase::Rules, reads<LodAttributes, LodState, RuleResource>(), writes<LodRequest>(),
                    [this](SystemContext& ctx) {
                        auto g = character_group(registry_);
                        const RuleTable& table = rules_.table();
                        if (!options_.lod) {  // LOD off: everyone asks for the richest levels
                            for (LodRequest& r : g.span<LodRequest>()) r = LodRequest{0, 0, 0};
                            return;
                        }
                        ctx.parallel_for(g.size(), kLodGrain, [&](size_t b, size_t e) {
                            RuleEvalJob job;
                            job.table = &table;
                            job.attributes = g.span<LodAttributes>().subspan(b, e - b);
                            job.states = g.span<LodState>().subspan(b, e - b);
                            job.tier = tier_.tier;
                            job.output = g.span<LodRequest>().subspan(b, e - b);
                            job.Run();
                        });
                    }});

    {
        SystemDesc resolve{"lod_resolve", Phase::Resolve, reads<RuleResource>(), everything_in_group, nullptr};
        resolve.writes.push_back(resource_type_id<SurfaceResource>());
        resolve.run = [this](SystemContext& ctx) {
            auto g = character_group(registry_);
            const float dt = first_frame_ ? 0.0f : ctx.dt();  // the resolver's clocks run in simulated seconds
            const RuleTable& table = rules_.table();
            changed_.resize(g.size());
            // The frame budget (off, one total, or separate animation and geometry parts: LodBudget) steers
            // on the last frame's measured times and this frame's requests (to predict pending switches).
            if (budget_.active()) {
                BudgetMeasurement m;
                m.total_ms = static_cast<float>(last_cpu_ms_);
                m.animation_ms = static_cast<float>(last_animation_ms_);
                m.geometry_ms = static_cast<float>(last_geometry_ms_);
                if (geom_level_ms_.size() == table.geom_levels.size()) m.geometry_level_ms = geom_level_ms_;
                if (anim_level_ms_.size() == table.anim_levels.size()) m.animation_level_ms = anim_level_ms_;
                budget_.update(m, g.span<LodAttributes>(), g.span<LodRequest>(), g.span<LodState>(), table);
            }
            // Level caps (at most N characters at a level or richer, by significance) before the resolver.
            LevelCapJob caps;
            caps.table = &table;
            caps.requests = g.span<LodRequest>();
            caps.attributes = g.span<LodAttributes>();
            caps.states = g.span<LodState>();
            caps.snap = first_frame_;
            caps.dt = dt;
            caps.keep_bonus = table.hysteresis.band;
            caps.scratch = &caps_scratch_;
            if (options_.lod) caps.Run();
            LodResolveJob job;
            job.table = &table;
            job.requests = g.span<LodRequest>();
            job.states = g.span<LodState>();
            job.geom = g.span<GeomLod>();
            job.anim = g.span<AnimLod>();
            job.changed_indices = changed_;
            job.snap = first_frame_;
            job.dt = dt;
            job.switch_counts = switches_;
            const size_t changed = job.Run();
            // Marshal level switches to the geometric controllers (geomorph from the old surface).
            apply_level_switches(geometry_types_, g.span<CharacterRef>(), g.span<LodState>(), g.span<GeomLod>(),
                                 std::span<const uint32_t>(changed_.data(), changed), first_frame_, ctx.dt());
            if (changed > 0 || first_frame_) regroup();  // keep characters grouped by (type, level)
            LodStatsJob stats;
            stats.table = &table;
            stats.states = g.span<LodState>();
            stats.attributes = g.span<LodAttributes>();
            stats.output = &stats_;
            stats.Run();
        };
        scheduler_.add(std::move(resolve));
    }

    scheduler_.add({"motion", Phase::Motion, reads<AnimLod, CharacterRef>(),
                    writes<MotionState, Transform, Velocity, PoseResource>(), [this](SystemContext& ctx) {
                        auto g = character_group(registry_);
                        for (auto& rt : types_) {
                            rt->motion->set_level_timing(anim_level_ns_);  // per-level time for the animation budget
                            MotionUpdateJob job;
                            job.controller = rt->motion.get();
                            job.dt = ctx.dt();
                            job.lods = g.span<AnimLod>();
                            job.states = g.span<MotionState>();
                            job.transforms = g.span<Transform>();
                            job.velocities = g.span<Velocity>();
                            job.element_of_character = rt->element_of_character;
                            job.grain = 64;  // pose evaluation in parallel chunks (bit-identical to serial)
                            job.run_chunks = [&ctx](size_t count, size_t grain, const std::function<void(size_t, size_t)>& fn) {
                                ctx.parallel_for(count, grain, fn);
                            };
                            job.Run();
                        }
                    }});

    // The geometric controller, per (type, level) range of the grouping one tight loop, chunks in
    // parallel (systems/frame/geometry_frame.hpp). Muscle stage: the muscles shaped for the pose
    // (volume kept) and tessellated at the level's (T, P).
    auto geometry_job = [this](SystemContext& ctx) {
        auto g = character_group(registry_);
        GeometryUpdateJob job;
        job.types = geometry_types_;
        job.groups = &groups_;
        job.states = g.span<LodState>();
        job.motion = g.span<MotionState>();
        job.dt = ctx.dt();
        job.first_frame = first_frame_;
        job.level_ns = geom_level_ns_;  // per-level time for the geometry budget
        job.run_chunks = [&ctx](size_t count, size_t grain, const std::function<void(size_t, size_t)>& fn) {
            ctx.parallel_for(count, grain, fn);
        };
        job.scratch = &due_ids_;
        return job;
    };
    scheduler_.add({"muscle", Phase::Tessellate, reads<GeomLod, CharacterRef, PoseResource>(), writes<MuscleSurfaceResource>(),
                    [geometry_job](SystemContext& ctx) { geometry_job(ctx).RunMuscles(); }});

    // Skin stage: rigid proxies, linear-blend skin, fat springs on the muscle surface + skin, geomorph,
    // OpenSubdiv.
    scheduler_.add({"spring_skin", Phase::Skin,
                    reads<GeomLod, LodState, MotionState, CharacterRef, PoseResource, MuscleSurfaceResource>(),
                    writes<SurfaceResource>(), [geometry_job](SystemContext& ctx) { geometry_job(ctx).RunSkin(); }});

    scheduler_.add({"render_prepare", Phase::Render,
                    reads<SurfaceResource, Transform, GeomLod, LodState, AnimLod, CharacterRef>(),
                    writes<DrawListResource>(), [this](SystemContext&) {
                        if (!renderer_) return;
                        auto g = character_group(registry_);
                        render_status_ = draws_.gather(renderer_, draw_types_, groups_, g.span<Transform>(), g.span<LodState>(),
                                                       g.span<AnimLod>(), DrawSettings{options_.colour, options_.overlay}, lists_);
                    }});

    scheduler_.add({"render", Phase::Render, reads<DrawListResource, CameraResource>(), writes<GpuResource>(),
                    [this](SystemContext&) {
                        if (!renderer_ || !target_ || !render_status_.ok()) return;
                        FrameInput input;
                        frame_settings(input);
                        input.meshes = lists_.meshes;
                        input.proxies = lists_.proxies;
                        input.lines = lists_.lines;
                        Status s = renderer_->render(input, *target_);
                        if (s.ok()) s = renderer_->finish();
                        render_status_ = s;
                        last_gpu_ms_ = renderer_->last_gpu_ms();
                    }});
}

}  // namespace aloha
