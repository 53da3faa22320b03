// The World's systems: each declares what it reads and writes as an Access type (engine/scheduler/access.hpp)
// and gets exactly those spans, const for reads; the scheduler derives the passes from the same types.
#include "engine/scene/character_runtime.hpp"
#include "engine/scene/world.hpp"
#include "engine/scheduler/access.hpp"
#include "systems/lod/resolver.hpp"
#include "systems/lod/rule_eval.hpp"
#include "systems/lod/rule_table.hpp"

#include <functional>
#include <type_traits>

namespace aloha {

namespace {
// Host state that is not a component, named by tag types for the scheduler's access sets (declared in
// Reads/Writes like components; the body reaches the state itself through the World).
struct CameraResource {};
struct RuleResource {};
struct PoseResource {};
struct GroupingResource {};         ///< groups_: the (type, level) grouping lod_resolve rebuilds
struct MuscleSurfaceResource {};
struct SurfaceResource {};
struct DrawListResource {};
struct RendererTablesResource {};   ///< the renderer's topology, material and texture tables
struct GpuResource {};

// Where the World's systems take their spans from: the character group's components; host-state tags
// (empty types) give empty spans, their state being the World's.
struct FrameSource {
    CharacterGroup group;
    template <class T>
    std::span<T> span() const {
        if constexpr (std::is_empty_v<T>)
            return {};
        else
            return group.span<T>();
    }
};

// Characters per parallel chunk for the cheap per-character LOD loops.
constexpr size_t kLodGrain = 2048;

}  // namespace

void World::register_systems() {
    auto source = [this] { return FrameSource{character_group(registry_)}; };

    using AttributesAccess = Access<Reads<Transform, Velocity, Bounds, Importance, CameraResource>, Writes<LodAttributes>>;
    scheduler_.add(make_system<AttributesAccess>("lod_attributes", Phase::Attributes, source,
                                                 [this](SystemContext& ctx, const AttributesAccess& a) {
        const auto out = a.write<LodAttributes>();
        ctx.parallel_for(out.size(), kLodGrain, [&](size_t b, size_t e) {
            LodAttributesJob job;
            job.transforms = a.read<Transform>().subspan(b, e - b);
            job.velocities = a.read<Velocity>().subspan(b, e - b);
            job.bounds = a.read<Bounds>().subspan(b, e - b);
            job.importance = a.read<Importance>().subspan(b, e - b);
            job.camera = camera_;
            job.output = out.subspan(b, e - b);
            job.Run();
        });
    }));

    // Occlusion by the crowd itself: a coarse depth grid of nearer characters' cores (systems/lod/occlusion.hpp).
    if (options_.occlusion) {
        using OcclusionAccess = Access<Reads<Transform, Bounds, GeomLod, CameraResource>, Writes<LodAttributes>>;
        scheduler_.add(make_system<OcclusionAccess>("lod_occlusion", Phase::Rules, source,
                                                    [this](SystemContext&, const OcclusionAccess& a) {
            OcclusionJob job;
            job.transforms = a.read<Transform>();
            job.bounds = a.read<Bounds>();
            job.geom = a.read<GeomLod>();
            job.camera = camera_;
            job.grid = &occlusion_grid_;
            job.attributes = a.write<LodAttributes>();
            job.Run();
        }));
    }

    using RulesAccess = Access<Reads<LodAttributes, LodState, RuleResource>, Writes<LodRequest>>;
    scheduler_.add(make_system<RulesAccess>("lod_rules", Phase::Rules, source, [this](SystemContext& ctx, const RulesAccess& a) {
        const RuleTable& table = rules_.table();
        const auto out = a.write<LodRequest>();
        if (!options_.lod) {  // LOD off: everyone asks for the richest levels
            for (LodRequest& r : out) r = LodRequest{0, 0, 0};
            return;
        }
        ctx.parallel_for(out.size(), kLodGrain, [&](size_t b, size_t e) {
            RuleEvalJob job;
            job.table = &table;
            job.attributes = a.read<LodAttributes>().subspan(b, e - b);
            job.states = a.read<LodState>().subspan(b, e - b);
            job.tier = tier_.tier;
            job.output = out.subspan(b, e - b);
            job.Run();
        });
    }));

    // The resolver regroups the characters (a structural change of every component's order).
    using ResolveAccess = Access<Reads<RuleResource>, Writes<Transform, Velocity, Bounds, Importance, CharacterRef, LodAttributes,
                                                            LodRequest, LodState, GeomLod, AnimLod, MotionState, SurfaceResource,
                                                            GroupingResource>>;
    scheduler_.add(make_system<ResolveAccess>("lod_resolve", Phase::Resolve, source, [this](SystemContext& ctx, const ResolveAccess& a) {
        const float dt = first_frame_ ? 0.0f : ctx.dt();  // the resolver's clocks run in simulated seconds
        const RuleTable& table = rules_.table();
        const auto states = a.write<LodState>();
        changed_.resize(states.size());
        // The frame budget (off, one total, or separate animation and geometry parts: LodBudget) steers
        // on the last frame's measured times and this frame's requests (to predict pending switches).
        if (budget_.active()) {
            BudgetMeasurement m;
            m.total_ms = static_cast<float>(last_cpu_ms_);
            m.animation_ms = static_cast<float>(last_animation_ms_);
            m.geometry_ms = static_cast<float>(last_geometry_ms_);
            if (geom_level_ms_.size() == table.geom_levels.size()) m.geometry_level_ms = geom_level_ms_;
            if (anim_level_ms_.size() == table.anim_levels.size()) m.animation_level_ms = anim_level_ms_;
            budget_.update(m, a.read<LodAttributes>(), a.write<LodRequest>(), states, table);
        }
        // Level caps (at most N characters at a level or richer, by significance) before the resolver.
        LevelCapJob caps;
        caps.table = &table;
        caps.requests = a.write<LodRequest>();
        caps.attributes = a.read<LodAttributes>();
        caps.states = states;
        caps.snap = first_frame_;
        caps.dt = dt;
        caps.keep_bonus = table.hysteresis.band;
        caps.scratch = &caps_scratch_;
        if (options_.lod) caps.Run();
        LodResolveJob job;
        job.table = &table;
        job.requests = a.read<LodRequest>();
        job.states = states;
        job.geom = a.write<GeomLod>();
        job.anim = a.write<AnimLod>();
        job.changed_indices = changed_;
        job.snap = first_frame_;
        job.dt = dt;
        job.switch_counts = switches_;
        const size_t changed = job.Run();
        // Marshal level switches to the geometric controllers (geomorph from the old surface).
        apply_level_switches(geometry_types_, a.read<CharacterRef>(), states, a.read<GeomLod>(),
                             std::span<const uint32_t>(changed_.data(), changed), first_frame_, ctx.dt());
        if (changed > 0 || first_frame_) regroup();  // keep characters grouped by (type, level)
        LodStatsJob stats;
        stats.table = &table;
        stats.states = states;
        stats.attributes = a.read<LodAttributes>();
        stats.output = &stats_;
        stats.Run();
    }));

    using MotionAccess = Access<Reads<AnimLod, CharacterRef>, Writes<MotionState, Transform, Velocity, PoseResource>>;
    scheduler_.add(make_system<MotionAccess>("motion", Phase::Motion, source, [this](SystemContext& ctx, const MotionAccess& a) {
        for (auto& rt : types_) {
            rt->motion->set_level_timing(anim_level_ns_);  // per-level time for the animation budget
            MotionUpdateJob job;
            job.controller = rt->motion.get();
            job.dt = ctx.dt();
            job.lods = a.read<AnimLod>();
            job.states = a.write<MotionState>();
            job.transforms = a.write<Transform>();
            job.velocities = a.write<Velocity>();
            job.element_of_character = rt->element_of_character;
            job.grain = 64;  // pose evaluation in parallel chunks (bit-identical to serial)
            job.run_chunks = [&ctx](size_t count, size_t grain, const std::function<void(size_t, size_t)>& fn) {
                ctx.parallel_for(count, grain, fn);
            };
            job.Run();
        }
    }));

    // The geometric controller, per (type, level) range of the grouping one tight loop, chunks in
    // parallel (systems/frame/geometry_frame.hpp).
    auto geometry_job = [this](SystemContext& ctx, std::span<const LodState> states, std::span<const MotionState> motion) {
        GeometryUpdateJob job;
        job.types = geometry_types_;
        job.groups = &groups_;
        job.states = states;
        job.motion = motion;
        job.dt = ctx.dt();
        job.first_frame = first_frame_;
        job.level_ns = geom_level_ns_;  // per-level time for the geometry budget
        job.run_chunks = [&ctx](size_t count, size_t grain, const std::function<void(size_t, size_t)>& fn) {
            ctx.parallel_for(count, grain, fn);
        };
        job.scratch = &due_ids_;
        return job;
    };
    // Muscle stage: the muscles shaped for the pose (volume kept) and tessellated at the level's (T, P).
    using MuscleAccess = Access<Reads<LodState, MotionState, PoseResource, GroupingResource>, Writes<MuscleSurfaceResource>>;
    scheduler_.add(make_system<MuscleAccess>("muscle", Phase::Tessellate, source, [geometry_job](SystemContext& ctx, const MuscleAccess& a) {
        geometry_job(ctx, a.read<LodState>(), a.read<MotionState>()).RunMuscles();
    }));
    // Skin stage: rigid proxies, linear-blend skin, fat springs on the muscle surface + skin, geomorph,
    // OpenSubdiv.
    using SkinAccess = Access<Reads<LodState, MotionState, PoseResource, GroupingResource, MuscleSurfaceResource>, Writes<SurfaceResource>>;
    scheduler_.add(make_system<SkinAccess>("spring_skin", Phase::Skin, source, [geometry_job](SystemContext& ctx, const SkinAccess& a) {
        geometry_job(ctx, a.read<LodState>(), a.read<MotionState>()).RunSkin();
    }));

    // The draw lists; registering a new topology or material writes the renderer's tables.
    using DrawAccess = Access<Reads<SurfaceResource, PoseResource, GroupingResource, Transform, LodState, AnimLod>,
                              Writes<DrawListResource, RendererTablesResource>>;
    scheduler_.add(make_system<DrawAccess>("render_prepare", Phase::Render, source, [this](SystemContext&, const DrawAccess& a) {
        if (!renderer_) return;
        render_status_ = draws_.gather(renderer_, draw_types_, groups_, a.read<Transform>(), a.read<LodState>(), a.read<AnimLod>(),
                                       DrawSettings{options_.colour, options_.overlay}, lists_);
    }));

    using RenderAccess = Access<Reads<DrawListResource, RendererTablesResource, CameraResource>, Writes<GpuResource>>;
    scheduler_.add(make_system<RenderAccess>("render", Phase::Render, source, [this](SystemContext&, const RenderAccess&) {
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
    }));
}

}  // namespace aloha
