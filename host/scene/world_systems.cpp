// The World's systems: each declares what it reads and writes as an Access type (engine/scheduler/access.hpp)
// and gets exactly those spans, const for reads; the scheduler derives the passes from the same types.
#include "host/scene/character_runtime.hpp"
#include "host/scene/world.hpp"
#include "engine/scheduler/access.hpp"
#include "systems/lod/resolver.hpp"
#include "systems/lod/rule_eval.hpp"
#include "systems/lod/rule_table.hpp"

#include <algorithm>
#include <array>
#include <cmath>
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
// Characters per part of the occlusion grid's rasterisation, at least (each part clears and merges a grid of its own).
constexpr size_t kOcclusionPartGrain = 256;

}  // namespace

void World::mark_pose_use(SystemContext& ctx, std::span<const CharacterRef> refs, std::span<const LodState> states) {
    // Which poses the stages after motion read this frame (the skin stage's rules below, per (type, level)
    // range as the type draws it): hidden characters none, proxies and linear-blend skins only when posed
    // or morphing, layered levels every frame. The group is kept sorted, so positions are elements.
    pose_use_.resize(refs.size());
    if (options_.pose_every_character || first_frame_ || !groups_.in_place()) {
        std::fill(pose_use_.begin(), pose_use_.end(), static_cast<uint8_t>(PoseUse::EveryFrame));
        return;
    }
    const bool bones = (options_.overlay & kOverlayBones) != 0;
    for (const LevelRange& r : groups_.ranges) {
        CharacterRuntime& rt = *types_[r.type];
        const GeomMethod method = rt.geometry->level(r.level).method;
        const bool every = method == GeomMethod::Layered || method == GeomMethod::Subdivided || (bones && method != GeomMethod::Hidden);
        // Impostors show baked poses (only the clip clock, which runs anyway, picks the row).
        const bool unseen = method == GeomMethod::Hidden || (method == GeomMethod::Impostor && !bones);
        const PoseUse whole = unseen ? PoseUse::Unseen : every ? PoseUse::EveryFrame : PoseUse::AtUpdates;
        if (whole != PoseUse::AtUpdates) {
            std::fill(pose_use_.begin() + static_cast<std::ptrdiff_t>(r.begin), pose_use_.begin() + static_cast<std::ptrdiff_t>(r.end),
                      static_cast<uint8_t>(whole));
            continue;
        }
        ctx.parallel_for(r.end - r.begin, kLodGrain, [&](size_t b, size_t e) {
            for (size_t i = r.begin + b; i < r.begin + e; ++i) {
                const bool morphing = states[i].seconds_at_geom == 0.0f || states[i].geomorph_left_s > 0.0f ||
                                      rt.geometry->geomorph_frames_left(refs[i].id) > 0;
                pose_use_[i] = static_cast<uint8_t>(morphing ? PoseUse::EveryFrame : PoseUse::AtUpdates);
            }
        });
    }
    // A character fading into the impostor level or between mesh levels is still drawn at the level it left,
    // posed every frame (GeometryController::update_fades): the few in a cross-fade, not a pass over the impostors.
    for (const auto& rt : types_)
        for (const LevelFade& f : rt->geometry->fades())
            if (f.keeps_left()) pose_use_[rt->element_of_character[f.character]] = static_cast<uint8_t>(PoseUse::EveryFrame);
}

void World::register_systems() {
    auto source = [this] { return FrameSource{character_group(registry_)}; };

    using AttributesAccess = Access<Reads<Transform, Velocity, Bounds, Importance, CameraResource>, Writes<LodAttributes>>;
    scheduler_.add(make_system<AttributesAccess>("lod_attributes", WorldPhase::Attributes, source,
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
        scheduler_.add(make_system<OcclusionAccess>("lod_occlusion", WorldPhase::Rules, source,
                                                    [this](SystemContext& ctx, const OcclusionAccess& a) {
            OcclusionJob job;
            job.transforms = a.read<Transform>();
            job.bounds = a.read<Bounds>();
            job.geom = a.read<GeomLod>();
            job.camera = camera_;
            job.grid = &occlusion_grid_;
            job.attributes = a.write<LodAttributes>();
            if (job.NoneCanBeHidden()) {  // a close-up's one character: no grid to fill
                job.ClearAll();
                return;
            }
            // Pass 1 in one part per thread (a grid each, merged: the same grid bit for bit), but no more parts
            // than kOcclusionPartGrain characters each fill: a small crowd (a close-up's one character) is rasterised on
            // this thread, not handed to a worker that a busy machine may leave unscheduled for milliseconds
            // (closeup: one frame's lod_occlusion took 5.2 ms). Pass 2 only reads the grid, in parallel chunks.
            const size_t parts = std::clamp<size_t>(job.transforms.size() / kOcclusionPartGrain, 1, std::max<size_t>(1, ctx.threads()));
            job.PrepareParts(parts);
            ctx.parallel_for(parts, 1, [&](size_t b, size_t e) {
                for (size_t p = b; p < e; ++p) job.RasterisePart(p, parts);
            });
            job.MergeParts(parts);
            ctx.parallel_for(job.attributes.size(), kLodGrain, [&](size_t b, size_t e) { (void)job.Test(b, e); });
        }));
    }

    using RulesAccess = Access<Reads<LodAttributes, LodState, RuleResource>, Writes<LodRequest>>;
    scheduler_.add(make_system<RulesAccess>("lod_rules", WorldPhase::Rules, source, [this](SystemContext& ctx, const RulesAccess& a) {
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
    scheduler_.add(make_system<ResolveAccess>("lod_resolve", WorldPhase::Resolve, source, [this](SystemContext& ctx, const ResolveAccess& a) {
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
            if (anim_level_ms_.size() == table.anim_levels.size() * kAnimCostClasses) m.animation_level_ms = anim_level_ms_;
            // Each character's animation cost class (walking or not) as the motion system left it.
            const auto motion = a.read<MotionState>();
            walking_.resize(motion.size());
            for (size_t i = 0; i < motion.size(); ++i) walking_[i] = motion[i].active == RequestKind::Walk ? 1 : 0;
            m.animation_classes = walking_;
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
        caps.run_chunks = [&ctx](size_t count, size_t grain, const std::function<void(size_t, size_t)>& fn) {
            ctx.parallel_for(count, grain, fn);
        };
        if (options_.lod) caps.Run();
        apply_level_pin(a.write<LodRequest>(), states);  // a character held at one level (pin_geom_level)
        // The resolver in fixed blocks on both cores: each block lists its changes in its own part of
        // changed_ and counts its switches; the lists are then packed in block order (same as serial).
        const size_t n = states.size(), blocks = (n + kLodGrain - 1) / kLodGrain;
        std::vector<std::array<uint32_t, 3>>& block_out = resolve_blocks_;  // changed, geometric, animation switches
        block_out.resize(blocks);
        ctx.parallel_for(blocks, 1, [&](size_t kb, size_t ke) {
            for (size_t k = kb; k < ke; ++k) {
                const size_t b = k * kLodGrain, e = std::min(n, b + kLodGrain);
                LodResolveJob job;
                job.table = &table;
                job.requests = a.read<LodRequest>().subspan(b, e - b);
                job.states = states.subspan(b, e - b);
                job.geom = a.write<GeomLod>().subspan(b, e - b);
                job.anim = a.write<AnimLod>().subspan(b, e - b);
                job.changed_indices = std::span<uint32_t>(changed_).subspan(b, e - b);
                job.index_base = static_cast<uint32_t>(b);
                job.snap = first_frame_;
                job.dt = dt;
                block_out[k] = {0, 0, 0};
                job.switch_counts = &block_out[k][1];
                block_out[k][0] = static_cast<uint32_t>(job.Run());
            }
        });
        size_t changed = 0;
        for (size_t k = 0; k < blocks; ++k) {
            const auto from = changed_.begin() + static_cast<std::ptrdiff_t>(k * kLodGrain);
            std::copy(from, from + block_out[k][0], changed_.begin() + static_cast<std::ptrdiff_t>(changed));
            changed += block_out[k][0];
            switches_[0] += block_out[k][1];
            switches_[1] += block_out[k][2];
        }
        // Why they switched (the rules or the budget's edits): a profiling count, O(switches).
        if (!first_frame_ && options_.lod && changed > 0) {
            const auto refs = a.read<CharacterRef>();
            switch_keys_.resize(changed);
            for (size_t c = 0; c < changed; ++c) switch_keys_[c] = type_first_[refs[changed_[c]].type] + refs[changed_[c]].id;
            SwitchCauseJob causes;
            causes.table = &table;
            causes.requests = a.read<LodRequest>();
            causes.states = states;
            causes.changed = std::span<const uint32_t>(changed_.data(), changed);
            causes.keys = switch_keys_;
            causes.records = switch_records_;
            causes.frame = frame_;
            causes.undo_frames = dt > 0.0f ? static_cast<uint64_t>(std::lround(1.0f / dt)) : 60;  // one second
            causes.out = &switch_causes_;
            if (causes.Validate()) causes.Run();
        }
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

    using MotionAccess = Access<Reads<AnimLod, CharacterRef, LodState, GroupingResource>, Writes<MotionState, Transform, Velocity, PoseResource>>;
    scheduler_.add(make_system<MotionAccess>("motion", WorldPhase::Motion, source, [this](SystemContext& ctx, const MotionAccess& a) {
        mark_pose_use(ctx, a.read<CharacterRef>(), a.read<LodState>());
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
            job.pose_use = pose_use_;
            job.grain = 64;  // pose evaluation in parallel chunks (bit-identical to serial)
            job.run_chunks = [&ctx](size_t count, size_t grain, const std::function<void(size_t, size_t)>& fn) {
                ctx.parallel_for(count, grain, fn);
            };
            job.Run();
        }
    }));

    // The geometric controller, per (type, level) range of the grouping one tight loop, chunks in
    // parallel (systems/frame/geometry_frame.hpp).
    auto geometry_job = [this](SystemContext& ctx, std::span<const LodState> states, std::span<const MotionState> motion,
                               std::span<const Transform> placements) {
        GeometryUpdateJob job;
        job.types = geometry_types_;
        job.groups = &groups_;
        job.states = states;
        job.motion = motion;
        job.placements = placements;
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
    using MuscleAccess = Access<Reads<Transform, LodState, MotionState, PoseResource, GroupingResource>, Writes<MuscleSurfaceResource>>;
    scheduler_.add(make_system<MuscleAccess>("muscle", WorldPhase::Tessellate, source, [geometry_job](SystemContext& ctx, const MuscleAccess& a) {
        geometry_job(ctx, a.read<LodState>(), a.read<MotionState>(), a.read<Transform>()).RunMuscles();
    }));
    // Skin stage: rigid proxies, linear-blend skin, fat springs on the muscle surface + skin, geomorph,
    // OpenSubdiv.
    using SkinAccess = Access<Reads<Transform, LodState, MotionState, PoseResource, GroupingResource, MuscleSurfaceResource>,
                              Writes<SurfaceResource>>;
    scheduler_.add(make_system<SkinAccess>("spring_skin", WorldPhase::Skin, source, [geometry_job](SystemContext& ctx, const SkinAccess& a) {
        geometry_job(ctx, a.read<LodState>(), a.read<MotionState>(), a.read<Transform>()).RunSkin();
    }));

    // The draw lists; registering a new topology or material writes the renderer's tables.
    using DrawAccess = Access<Reads<SurfaceResource, PoseResource, GroupingResource, Transform, LodState, LodAttributes, AnimLod, MotionState>,
                              Writes<DrawListResource, RendererTablesResource>>;
    scheduler_.add(make_system<DrawAccess>("render_prepare", WorldPhase::Render, source, [this](SystemContext&, const DrawAccess& a) {
        if (!renderer_) return;
        render_status_ = draws_.gather(renderer_, draw_types_, groups_, a.read<Transform>(), a.read<LodState>(), a.read<AnimLod>(),
                                       DrawSettings{options_.colour, options_.overlay}, lists_, a.read<MotionState>(),
                                       a.read<LodAttributes>());
    }));

    using RenderAccess = Access<Reads<DrawListResource, RendererTablesResource, CameraResource>, Writes<GpuResource>>;
    scheduler_.add(make_system<RenderAccess>("render", WorldPhase::Render, source, [this](SystemContext&, const RenderAccess&) {
        if (!renderer_ || !target_ || !render_status_.ok()) return;
        FrameInput input;
        frame_settings(input);
        input.meshes = lists_.meshes;
        input.proxies = lists_.proxies;
        input.proxy_fades = lists_.proxy_fades;
        input.lines = lists_.lines;
        input.impostors = lists_.impostors;
        Status s = renderer_->render(input, *target_);
        // Overlapped: drawn while the next step runs; else waited for here (every frame still in flight).
        const bool overlap = overlap_policy_.decide(last_cpu_ms_, last_gpu_ms_);
        if (s.ok() && !overlap) s = renderer_->finish();
        render_status_ = s;
        last_gpu_ms_ = renderer_->last_gpu_ms();
    }));
}

}  // namespace aloha
