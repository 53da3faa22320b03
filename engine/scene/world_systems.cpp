// The World's systems: each declares what it reads and writes; the scheduler derives the passes.
#include "engine/scene/character_runtime.hpp"
#include "engine/scene/world.hpp"
#include "systems/lod/resolver.hpp"
#include "systems/lod/rule_eval.hpp"
#include "systems/lod/rule_table.hpp"

#include <algorithm>
#include <array>
#include <chrono>
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

uint64_t now_ns() {
    return static_cast<uint64_t>(
        std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch()).count());
}
}  // namespace

void World::mark_pose_use(SystemContext& ctx) {
    // Which poses the stages after motion read this frame (the skin stage's rules below, per (type, level)
    // range as the type draws it): hidden characters none, proxies and linear-blend skins only when posed
    // or morphing, layered levels every frame.
    auto g = character_group(registry_);
    pose_use_.resize(g.size());
    if (options_.pose_every_character || first_frame_) {
        std::fill(pose_use_.begin(), pose_use_.end(), static_cast<uint8_t>(PoseUse::EveryFrame));
        return;
    }
    auto refs = g.span<CharacterRef>();
    auto geom = g.span<GeomLod>();
    auto states = g.span<LodState>();
    const bool bones = (options_.overlay & kOverlayBones) != 0;
    for (const KeyRange& r : ranges_) {
        CharacterRuntime& rt = *types_[refs[r.begin].type];
        const GeomMethod method = rt.geometry->level(geom[r.begin].level).method;
        const bool every = method == GeomMethod::Layered || method == GeomMethod::Subdivided || (bones && method != GeomMethod::Hidden);
        const PoseUse whole = method == GeomMethod::Hidden ? PoseUse::Unseen : every ? PoseUse::EveryFrame : PoseUse::AtUpdates;
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
}

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
                        [this](SystemContext& ctx) {
                            auto g = character_group(registry_);
                            OcclusionJob job;
                            job.transforms = g.span<Transform>();
                            job.bounds = g.span<Bounds>();
                            job.geom = g.span<GeomLod>();
                            job.camera = camera_;
                            job.grid = &occlusion_grid_;
                            job.attributes = g.span<LodAttributes>();
                            job.Rasterise();  // pass 1 fills the grid; pass 2 only reads it, in parallel chunks
                            ctx.parallel_for(g.size(), kLodGrain, [&](size_t b, size_t e) { (void)job.Test(b, e); });
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
            caps.run_chunks = [&ctx](size_t count, size_t grain, const std::function<void(size_t, size_t)>& fn) {
                ctx.parallel_for(count, grain, fn);
            };
            if (options_.lod) caps.Run();
            // The resolver in fixed blocks on both cores: each block lists its changes in its own part of
            // changed_ and counts its switches; the lists are then packed in block order (same as serial).
            const size_t n = g.size(), blocks = (n + kLodGrain - 1) / kLodGrain;
            std::vector<std::array<uint32_t, 3>> block_out(blocks);  // changed, geometric, animation switches
            ctx.parallel_for(blocks, 1, [&](size_t kb, size_t ke) {
                for (size_t k = kb; k < ke; ++k) {
                    const size_t b = k * kLodGrain, e = std::min(n, b + kLodGrain);
                    LodResolveJob job;
                    job.table = &table;
                    job.requests = g.span<LodRequest>().subspan(b, e - b);
                    job.states = g.span<LodState>().subspan(b, e - b);
                    job.geom = g.span<GeomLod>().subspan(b, e - b);
                    job.anim = g.span<AnimLod>().subspan(b, e - b);
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
            // Marshal level switches to the geometric controller (geomorph from the old surface).
            auto refs = g.span<CharacterRef>();
            auto states = g.span<LodState>();
            auto geom = g.span<GeomLod>();
            if (first_frame_) {
                for (size_t i = 0; i < g.size(); ++i)
                    types_[refs[i].type]->geometry->begin_level(refs[i].id, states[i].geom_level, -1, 0);
            } else {
                for (size_t k = 0; k < changed; ++k) {
                    const uint32_t i = changed_[k];
                    GeometryController& gc = *types_[refs[i].type]->geometry;
                    if (gc.level_of(refs[i].id) == states[i].geom_level) continue;  // animation level only
                    gc.begin_level(refs[i].id, states[i].geom_level, static_cast<int8_t>(states[i].prev_geom_level),
                                   transition_frames(geom[i].geomorph_s, ctx.dt()));
                }
            }
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

    scheduler_.add({"motion", Phase::Motion, reads<AnimLod, CharacterRef, GeomLod, LodState>(),
                    writes<MotionState, Transform, Velocity, PoseResource>(), [this](SystemContext& ctx) {
                        auto g = character_group(registry_);
                        mark_pose_use(ctx);
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
                            job.pose_use = pose_use_;
                            job.grain = 64;  // pose evaluation in parallel chunks (bit-identical to serial)
                            job.run_chunks = [&ctx](size_t count, size_t grain, const std::function<void(size_t, size_t)>& fn) {
                                ctx.parallel_for(count, grain, fn);
                            };
                            job.Run();
                        }
                    }});

    // The geometric controller, muscle stage: per (type, level) range of a muscle level one tight loop
    // shaping the muscles for the pose (volume kept) and tessellating them at the level's (T, P).
    scheduler_.add({"muscle", Phase::Tessellate, reads<GeomLod, CharacterRef, PoseResource>(), writes<MuscleSurfaceResource>(),
                    [this](SystemContext& ctx) {
                        auto g = character_group(registry_);
                        auto refs = g.span<CharacterRef>();
                        auto geom = g.span<GeomLod>();
                        for (const KeyRange& r : ranges_) {
                            CharacterRuntime& rt = *types_[refs[r.begin].type];
                            const GeomMethod method = rt.geometry->level(geom[r.begin].level).method;  // as the type draws it
                            if (method != GeomMethod::Layered && method != GeomMethod::Subdivided) continue;
                            const PoseSource poses = rt.poses();
                            const uint8_t level = geom[r.begin].level;
                            const std::span<const uint32_t> ids(ids_.data() + r.begin, r.end - r.begin);
                            const uint64_t start = now_ns();  // per-level time for the geometry budget
                            ctx.parallel_for(ids.size(), 1, [&](size_t b, size_t e) {
                                rt.geometry->update_muscles(level, ids.subspan(b, e - b), poses);
                            });
                            if (level < geom_level_ns_.size()) geom_level_ns_[level] += now_ns() - start;
                        }
                    }});

    // The geometric controller, skin stage: per (type, level) range one tight loop of that level's
    // skin (rigid proxies, linear-blend skin, fat springs on the muscle surface + skin, geomorph,
    // OpenSubdiv), chunks in parallel.
    scheduler_.add({"spring_skin", Phase::Skin,
                    reads<GeomLod, LodState, MotionState, CharacterRef, PoseResource, MuscleSurfaceResource>(),
                    writes<SurfaceResource>(), [this](SystemContext& ctx) {
                        auto g = character_group(registry_);
                        auto refs = g.span<CharacterRef>();
                        auto geom = g.span<GeomLod>();
                        auto motion = g.span<MotionState>();
                        auto states = g.span<LodState>();
                        due_ids_.resize(g.size());
                        for (const KeyRange& r : ranges_) {
                            CharacterRuntime& rt = *types_[refs[r.begin].type];
                            const GeomMethod method = rt.geometry->level(geom[r.begin].level).method;  // as the type draws it
                            if (method == GeomMethod::Hidden) continue;
                            const PoseSource poses = rt.poses();
                            const uint8_t level = geom[r.begin].level;
                            // Proxies and linear-blend skins depend on the pose alone: only characters posed
                            // this frame (update_interval throttling), entering the level or morphing need
                            // work. Layered levels run every frame (the fat springs move).
                            std::span<const uint32_t> ids(ids_.data() + r.begin, r.end - r.begin);
                            if (method == GeomMethod::RigidProxy || method == GeomMethod::SkinnedMesh) {
                                size_t n = 0;
                                for (size_t i = r.begin; i < r.end; ++i)
                                    if (motion[i].frames_since_update == 0 || states[i].seconds_at_geom == 0.0f ||
                                        states[i].geomorph_left_s > 0.0f || first_frame_ ||
                                        rt.geometry->geomorph_frames_left(refs[i].id) > 0)
                                        due_ids_[r.begin + n++] = refs[i].id;
                                ids = std::span<const uint32_t>(due_ids_.data() + r.begin, n);
                            }
                            // Grain: cheap methods in big chunks, rich ones one or a few characters each.
                            const size_t grain = method == GeomMethod::RigidProxy ? 256 : method == GeomMethod::SkinnedMesh ? 16 : 1;
                            const uint64_t start = now_ns();  // per-level time for the geometry budget
                            ctx.parallel_for(ids.size(), grain, [&](size_t b, size_t e) {
                                rt.geometry->update_skin(level, ids.subspan(b, e - b), poses, ctx.dt());
                            });
                            if (level < geom_level_ns_.size()) geom_level_ns_[level] += now_ns() - start;
                        }
                    }});

    scheduler_.add({"render_prepare", Phase::Render,
                    reads<SurfaceResource, Transform, GeomLod, LodState, AnimLod, CharacterRef>(),
                    writes<DrawListResource>(), [this](SystemContext&) {
                        if (renderer_) gather_render_lists();
                    }});

    scheduler_.add({"render", Phase::Render, reads<DrawListResource, CameraResource>(), writes<GpuResource>(),
                    [this](SystemContext&) {
                        if (!renderer_ || !target_) return;
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
