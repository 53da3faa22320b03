#include "host/scene/world.hpp"

#include "host/scene/character_runtime.hpp"
#include "host/scene/scene_checks.hpp"
#include "host/scene/world_diagnostics.hpp"
#include "systems/geometry/controller/skin_layer.hpp"
#include "systems/lod/resolver.hpp"
#include "systems/lod/rule_table.hpp"
#include "systems/motion/motion_metrics.hpp"

#include <nlohmann/json.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cstdio>
#include <cmath>

namespace aloha {

CharacterRuntime::CharacterRuntime(CharacterType t, uint32_t n) : type(std::move(t)), count(n) {
    ik = std::make_unique<IkHookContext>();
    dynamics = std::make_unique<DynamicHookContext>();
    motion = std::make_unique<MotionController>(type.skeleton, type.clips, n);
    if (type.rig) motion->set_walk_rig(*type.rig);
    // The walk's clips: the generated gaits (the built-in humanoid's, or retargeted onto a mapped humanoid from a
    // file), or loops cut from its own takes (none: the walk is then kinematic at every level).
    motion->set_walk_clips(type.gait_clips);
    // Characters hold the idle's first pose until their requests pose them (a reacher's other arm): the idle as
    // idlers play it (its looped version, when its seam was closed), so an idler starts where it stands.
    if (type.idle_clip >= 0) motion->set_stance(*type.clips.find_looped(static_cast<ClipId>(type.idle_clip)));
    ik->map = &type.map;
    register_ik_hooks(*motion, *ik);
    register_dynamic_walk_hook(*motion, *dynamics);
    element_of_character.assign(n, 0);
    // Proxy boxes only for bones long enough to be seen: zero-length joints and finger stubs are
    // skipped, which roughly halves the boxes of the CMU skeleton.
    const auto parents = type.skeleton.parents();
    const auto rest_t = type.skeleton.rest_translations();
    for (size_t j = 0; j < parents.size(); ++j)
        if (parents[j] < 0 || glm::length(rest_t[j]) >= 0.05f) proxy_joints.push_back(static_cast<uint16_t>(j));
    if (type.rig) {
        for (int side = 0; side < 2; ++side) feet.push_back(type.rig->ankle[static_cast<size_t>(side)]);
        for (int side = 0; side < 2; ++side)
            if (type.rig->toe[static_cast<size_t>(side)] >= 0) feet.push_back(type.rig->toe[static_cast<size_t>(side)]);
        soles = sole_offsets(type.skeleton, feet);
    }
}

std::vector<GeomLod> CharacterRuntime::usable_levels(std::span<const GeomLod> levels) const {
    std::vector<GeomLod> out(levels.begin(), levels.end());
    if (type.muscles.size() > 0) return out;
    for (GeomLod& l : out) {
        if (l.method == GeomMethod::Hidden || l.method == GeomMethod::RigidProxy) continue;
        if (l.method == GeomMethod::Impostor && type.mesh) continue;  // baked from the skinned mesh
        l.lit_per_pixel = type.mesh && (l.method == GeomMethod::Layered || l.method == GeomMethod::Subdivided);
        l.method = type.mesh ? GeomMethod::SkinnedMesh : GeomMethod::RigidProxy;
        l.layers = type.mesh ? kLayerSkeleton | kLayerSkin : kLayerSkeleton;
    }
    return out;
}

Status CharacterRuntime::init_geometry(uint16_t type_index, std::span<const GeomLod> all_levels, bool keep_refined_surfaces,
                                      std::shared_ptr<const BlobStore> bake_cache) {
    const std::vector<GeomLod> levels = usable_levels(all_levels);
    CharacterGeometryDesc desc;
    desc.type = type_index;
    desc.name = type.name;
    desc.skeleton = type.skeleton;
    desc.muscles = type.muscles;
    desc.mesh = type.mesh;
    desc.length_scale = body_length_scale(type.frame.height);
    desc.bake_cache = std::move(bake_cache);
    if (type.mesh)  // muscles were fitted in bind space: let them rest there
        for (const glm::mat4& ibm : type.mesh->inverse_bind) desc.rest_model.push_back(glm::inverse(ibm));
    auto built = CharacterGeometry::create(std::move(desc));
    if (!built.ok()) return built.error();
    geometry_data = std::move(built.value());
    geometry = std::make_unique<GeometryController>(*geometry_data, levels, count, keep_refined_surfaces);
    return {};
}

std::vector<GeomLod> geom_levels(const RuleTable& table) {
    std::vector<GeomLod> levels;
    for (size_t l = 0; l < table.geom_levels.size(); ++l) levels.push_back(table.geom_lod(static_cast<uint8_t>(l)));
    return levels;
}

Transform character_placement(const CharacterDesc& c) {
    Transform t;
    t.position = c.position;
    t.rotation = glm::angleAxis(glm::radians(c.heading_deg), glm::vec3(0, 1, 0));
    return t;
}

DrawType CharacterRuntime::draw_type() const {
    DrawType d;
    d.geometry = geometry.get();
    d.poses = poses();
    d.parents = type.skeleton.parents();
    d.proxy_joints = proxy_joints;
    d.materials = type.materials;
    d.textures = type.textures;
    return d;
}

void CharacterRuntime::add_paths(const SceneDesc& scene) {
    for (const auto& p : scene.paths) {
        motion->add_path(p.points, p.loop);
        path_names.push_back(p.name);
    }
}

Status CharacterRuntime::queue_requests(const SceneDesc& scene, size_t index, const CharacterDesc& c, uint32_t id) {
    for (size_t k = 0; k < c.requests.size(); ++k) {
        const RequestDesc& rd = c.requests[k];
        MotionRequest req = rd.request;
        // The place is only spelled out for an error: most loads queue every request.
        const auto where = [&] { return request_place(scene, index, rd, k, false); };
        const ResolvedRequest resolved = resolve_request(type, rd);  // names looked up once
        if (!resolved.problem.empty()) return make_error(scene.file, resolved.problem, 0, 0, where());
        if (req.kind == RequestKind::PlayClip) {
            req.clip = static_cast<uint16_t>(resolved.clip);
        } else if (req.kind == RequestKind::Walk && !rd.route.empty()) {
            // Its own looping route (a crowd's walk_route); ids stop below 0xFFFF, "no path".
            if (motion->path_count() >= 0xFFFF)
                return make_error(scene.file, "more than 65535 walk paths and routes for type '" + type.name + "' (fewer circle walkers, or split them over types)",
                                  0, 0, where());
            req.path = motion->add_path(rd.route, true);
        } else if (req.kind == RequestKind::Walk && !rd.path.empty()) {
            const auto it = std::find(path_names.begin(), path_names.end(), rd.path);
            req.path = static_cast<uint16_t>(it - path_names.begin());
        } else if (req.kind == RequestKind::Reach || req.kind == RequestKind::LookAt) {
            req.effector = static_cast<int16_t>(resolved.effector);
        }
        if (!motion->push_request(id, req))
            return make_error(scene.file, "more than " + std::to_string(MotionController::kQueueCapacity) + " requests queued", 0, 0, where());
    }
    if (c.overlay) {
        MotionRequest req = c.overlay->request;
        const ResolvedRequest resolved = resolve_request(type, *c.overlay);
        if (!resolved.problem.empty()) return make_error(scene.file, resolved.problem, 0, 0, request_place(scene, index, *c.overlay, 0, true));
        req.effector = static_cast<int16_t>(resolved.effector);
        motion->set_overlay(id, req, c.overlay_weight);
    }
    return {};
}

PoseSource CharacterRuntime::poses() const {
    if (count == 0) return {};
    return PoseSource{motion->poses().view(0).model.data(), static_cast<size_t>(type.skeleton.joint_count())};
}

World::~World() = default;

const CharacterType& World::type(size_t i) const { return types_[i]->type; }

size_t World::character_count() const {
    auto& reg = const_cast<Registry&>(registry_);
    return character_group(reg).size();
}

Result<std::unique_ptr<World>> World::create(const SceneDesc& scene, const WorldOptions& options) {
    std::unique_ptr<World> world(new World());
    if (Status s = world->load(scene, options); !s.ok()) return s.error();
    return world;
}

Status World::load(const SceneDesc& scene, const WorldOptions& options) {
    scene_ = scene;
    options_ = options;
    overlap_policy_ = GpuOverlapPolicy(options.overlap_gpu);
    if (options.characters) {
        // Rescale the crowds so the scene has the asked number of characters in all.
        const uint64_t placed = scene_.characters.size();
        uint64_t crowd_total = 0;
        for (const auto& c : scene_.crowds) crowd_total += c.count;
        if (crowd_total == 0 || *options.characters < placed)
            return option_error(scene.file, "characters", std::to_string(*options.characters) +
                                                              " characters: the scene has no crowd to rescale to that size");
        uint64_t left = *options.characters - placed;
        for (size_t i = 0; i < scene_.crowds.size(); ++i) {
            auto& c = scene_.crowds[i];
            const uint64_t n = i + 1 == scene_.crowds.size() ? left : c.count * (*options.characters - placed) / crowd_total;
            if (c.layout == CrowdDesc::Layout::Disc && c.count > 0)
                c.radius *= static_cast<float>(std::sqrt(static_cast<double>(n) / static_cast<double>(c.count)));
            c.count = static_cast<uint32_t>(n);
            left -= n;
        }
    }
    if (Status s = rules_.load(scene_.rules); !s.ok()) return s;
    applied_rules_generation_ = rules_.generation();
    const RuleTable& table = rules_.table();
    if (Status s = spawn_characters(); !s.ok()) return s;
    if (Status s = apply_rule_settings(); !s.ok()) return s;
    if (!options.lod) {
        // With LOD off every character sits at level 0: refuse up front (with the figures) rather than
        // run out of memory half-way through the first frame.
        uint64_t need = 0;
        for (const auto& rt : types_) need += uint64_t(rt->count) * rt->geometry->bytes_per_character(0);
        const uint64_t have = available_memory_bytes();
        if (have > 0 && need > have * 8 / 10)
            return option_error(scene.file, "lod", "LOD off puts all " + std::to_string(character_count()) +
                                                       " characters at level '" + table.geom_levels[0].name + "': " +
                                                       std::to_string(need >> 20) + " MiB of geometry, more than 80% of the " +
                                                       std::to_string(have >> 20) + " MiB available; fewer characters would fit");
        // All of them enter level 0 on the first frame: allocate once rather than by doubling.
        for (const auto& rt : types_) rt->geometry->reserve(0, rt->count);
    }
    register_systems();
    if (Status s = scheduler_.build(); !s.ok()) return s;
    scheduler_.set_threads(options.threads);
    motion_system_ = scheduler_.find("motion");
    muscle_system_ = scheduler_.find("muscle");
    skin_system_ = scheduler_.find("spring_skin");
    return {};
}

Status World::apply_rule_settings() {
    const RuleTable& table = rules_.table();
    BudgetOverrides o;
    o.enabled = options_.budget;
    o.total_ms = options_.budget_ms;
    o.single_total_ms = options_.budget_single_ms;
    o.animation_ms = options_.budget_animation_ms;
    o.geometry_ms = options_.budget_geometry_ms;
    if (!options_.lod) o.enabled = false;  // LOD off: everyone at level 0, nothing to demote
    budget_.configure(table, o, character_group(registry_).span<LodState>());
    // The tier: the host's (--tier), else the scene's "tier", else the rule file's default_tier or auto.
    const std::string name = options_.tier ? *options_.tier : scene_.tier;
    const int named = name.empty() ? -1 : table.find_tier(name);
    tier_ = resolve_tier(table, named, options_.hardware ? &*options_.hardware : nullptr);
    if (named >= 0) tier_.reason = options_.tier ? "named by the host" : "named by the scene";
    if (name.empty() || named >= 0) return {};
    std::string list;
    for (const auto& t : table.tiers) list += (list.empty() ? "" : ", ") + t;
    const std::string message = "tier '" + name + "' is not one of the tiers of " + table.source + " (" + list + ")";
    if (options_.tier) return option_error("", "tier", message);
    return make_error(scene_.file, message, 0, 0, "/tier");
}

Status World::spawn_characters() {
    std::vector<CharacterDesc> chars = expand_characters(scene_, options_.seed_override);
    drop_unused_variants(scene_, chars);  // a crowd's members pick their bodies at random: build only those picked
    TypeLoadOptions load;
    load.threads = options_.threads;
    bake_cache_ = open_bake_cache(options_.bake_cache, options_.bake_cache_dir, options_.bake_cache_max_bytes);
    load.bake_cache = bake_cache_;
    auto types = make_character_runtimes(scene_, chars, geom_levels(rules_.table()), options_.keep_refined_surfaces, load);
    if (!types.ok()) return types.error();
    types_ = std::move(types.value());
    (void)character_group(registry_);  // create the owning group before the components arrive
    registry_.reserve(chars.size());
    for (size_t i = 0; i < chars.size(); ++i) {
        const CharacterDesc& c = chars[i];
        CharacterRuntime& rt = *types_[static_cast<size_t>(c.type)];
        const uint32_t id = rt.spawned++;
        const Entity e = registry_.create();
        registry_.emplace<Transform>(e, character_placement(c));
        registry_.emplace<Velocity>(e);
        registry_.emplace<Bounds>(e, Bounds{rt.type.height, rt.bounds_radius(c)});
        registry_.emplace<Importance>(e, Importance{c.importance});
        registry_.emplace<CharacterRef>(e, CharacterRef{static_cast<uint16_t>(c.type), id});
        registry_.emplace<LodAttributes>(e);
        registry_.emplace<LodRequest>(e);
        LodState state;
        state.always_full = c.always_full ? 1 : 0;
        registry_.emplace<LodState>(e, state);
        registry_.emplace<GeomLod>(e);
        registry_.emplace<AnimLod>(e);
        MotionState ms;
        ms.pose_slot = id;
        registry_.emplace<MotionState>(e, ms);
        if (Status st = rt.queue_requests(scene_, i, c, id); !st.ok()) return st;
    }
    type_first_.assign(types_.size(), 0);
    for (size_t t = 1; t < types_.size(); ++t) type_first_[t] = type_first_[t - 1] + types_[t - 1]->count;
    switch_records_.assign(chars.size(), SwitchRecord{});
    regroup();
    return {};
}

void World::regroup() {
    auto group = character_group(registry_);
    // Keep the group itself sorted by (type, level), so the grouped loops walk memory in order and
    // every index the World hands out (explain, the group spans) is both element and position.
    group_keys(group.span<CharacterRef>(), group.span<GeomLod>(), groups_.keys);
    const bool moved = group.partition_by_key(groups_.keys);
    group_by_level(group.span<CharacterRef>(), group.span<GeomLod>(), groups_);
    const auto refs = group.span<CharacterRef>();
    if (!moved && elements_mapped_ == refs.size()) return;  // nobody changed place: elements still hold
    elements_mapped_ = refs.size();
    for (size_t e = 0; e < refs.size(); ++e) types_[refs[e].type]->element_of_character[refs[e].id] = static_cast<uint32_t>(e);
}

void World::refresh_type_views() {
    geometry_types_.resize(types_.size());
    draw_types_.resize(types_.size());
    for (size_t t = 0; t < types_.size(); ++t) {
        geometry_types_[t] = types_[t]->geometry_type();
        draw_types_[t] = types_[t]->draw_type();
    }
}

void World::step() {
    const float dt = scene_.dt;
    if (view_override_) {
        camera_ = make_lod_camera(view_override_->position, view_override_->target, glm::radians(override_fov_deg_),
                                  override_viewport_, scene_.camera.near_plane, scene_.camera.far_plane);
    } else {
        const CameraKey cam = sample_camera(scene_.camera, time_);
        camera_ = make_lod_camera(cam.position, cam.target, glm::radians(scene_.camera.fov_y_deg),
                                  glm::vec2(static_cast<float>(scene_.width), static_cast<float>(scene_.height)),
                                  scene_.camera.near_plane, scene_.camera.far_plane);
    }
    if (rules_.shared()) {
        (void)rules_.poll();  // live tuning: pick up an edited rule file (a failed reload keeps the old table)
        // A new table (from the file, or swapped in by a viewer): apply every section of it.
        if (rules_.generation() != applied_rules_generation_) {
            applied_rules_generation_ = rules_.generation();
            auto group = character_group(registry_);
            clamp_lod_states(rules_.table(), group.span<LodState>());
            const std::vector<GeomLod> levels = geom_levels(rules_.table());
            for (auto& rt : types_) rt->geometry->set_levels(rt->usable_levels(levels));
            // Level topologies may have changed, or an impostor level come: register, bake and warm up again.
            if (Status s = prepare_drawing(); !s.ok()) render_status_ = s;
            (void)apply_rule_settings();  // budget and tier too; a tier the new file lacks falls back to its own
        }
    }
    // The budget parts learn from each level's time of the frame before.
    auto to_ms = [](const std::vector<uint64_t>& ns, std::vector<double>& ms) {
        ms.assign(ns.size(), 0.0);
        for (size_t l = 0; l < ns.size(); ++l) ms[l] = static_cast<double>(ns[l]) * 1e-6;
    };
    to_ms(geom_level_ns_, geom_level_ms_);
    to_ms(anim_level_ns_, anim_level_ms_);
    geom_level_ns_.assign(rules_.table().geom_levels.size(), 0);
    anim_level_ns_.assign(rules_.table().anim_levels.size() * kAnimCostClasses, 0);
    switches_[0] = switches_[1] = 0;
    switch_causes_ = SwitchCauseCounts{};
    refresh_type_views();
    scheduler_.run_frame(dt);
    last_cpu_ms_ = static_cast<double>(scheduler_.latest_ns_before(WorldPhase::Render)) * 1e-6;
    auto latest_ms = [&](int system) {
        return system < 0 ? 0.0 : static_cast<double>(scheduler_.timings(static_cast<uint32_t>(system)).latest()) * 1e-6;
    };
    last_animation_ms_ = latest_ms(motion_system_);
    last_geometry_ms_ = latest_ms(muscle_system_) + latest_ms(skin_system_);
    if (reference_springs_) step_reference_springs();
    first_frame_ = false;
    ++frame_;
    time_ += dt;
}

RenderCamera World::render_camera() const { return RenderCamera{camera_.view, camera_.projection}; }

nlohmann::json World::explain(uint32_t i) const {
    auto& reg = const_cast<Registry&>(registry_);
    auto group = character_group(reg);
    if (i >= group.size()) return nlohmann::json::object();
    nlohmann::json j = to_json(aloha::explain(rules_.table(), i, group.span<LodAttributes>(), group.span<LodState>()));
    const CharacterRef ref = group.span<CharacterRef>()[i];
    j["type"] = types_[ref.type]->type.name;
    j["character_id"] = ref.id;
    return j;
}

}  // namespace aloha
