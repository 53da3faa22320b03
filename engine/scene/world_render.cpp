// The World's draw lists: world-space proxies and deformable meshes per character, coloured by the
// chosen debug view, and the renderer hook-up.
#include "engine/scene/character_runtime.hpp"
#include "engine/scene/world.hpp"
#include "systems/geometry/surface_grid.hpp"
#include "systems/render/debug_colours.hpp"

#include <glm/gtc/matrix_transform.hpp>

namespace aloha {

namespace {

// `textured`: the surface carries the type's materials, which give its colour (the instance is white).
glm::vec4 character_colour(DebugColour mode, const LodState& state, const AnimLod& anim, bool proxy, bool textured = false) {
    switch (mode) {
        case DebugColour::ByLodLevel: return colour_for_level(state.geom_level);
        case DebugColour::ByRule: return colour_for_rule(state.rule_id);
        case DebugColour::ByMotionMethod: return colour_for_motion_method(static_cast<int>(anim.walk));
        case DebugColour::Shaded: break;
    }
    if (textured) return glm::vec4(1.0f);
    return proxy ? glm::vec4(0.62f, 0.66f, 0.74f, 1.0f) : glm::vec4(0.86f, 0.68f, 0.56f, 1.0f);
}

// The renderer's unit box is [-0.5, 0.5]^3; proxy boxes map [-1, 1]^3.
const glm::mat4 kHalfToUnit = glm::scale(glm::mat4(1.0f), glm::vec3(2.0f));

}  // namespace

Status World::attach_renderer(CrowdRenderer* renderer, gpu::OffscreenTarget* target) {
    renderer_ = renderer;
    target_ = target;
    topologies_.clear();
    for (auto& rt : types_) rt->render_materials.clear();
    return {};
}

void World::frame_settings(FrameInput& frame) const {
    frame.camera = render_camera();
    set_character_lighting(frame);
    frame.materials = options_.colour == DebugColour::Shaded;
}

void World::gather_render_lists() {
    lists_.meshes.clear();
    lists_.proxies.clear();
    lists_.lines.clear();
    auto g = character_group(registry_);
    auto refs = g.span<CharacterRef>();
    auto geom = g.span<GeomLod>();
    auto states = g.span<LodState>();
    auto anims = g.span<AnimLod>();
    auto transforms = g.span<Transform>();
    for (const KeyRange& r : ranges_) {
        CharacterRuntime& rt = *types_[refs[r.begin].type];
        const GeometryController& gc = *rt.geometry;
        // The method as this type draws the level (a non-humanoid has no layered levels).
        const GeomMethod method = gc.level(geom[r.begin].level).method;
        if (method == GeomMethod::Hidden) continue;
        if (method == GeomMethod::RigidProxy) {
            for (size_t i = r.begin; i < r.end; ++i) {
                const std::span<const glm::mat4> boxes = gc.proxy_boxes(refs[i].id);
                if (boxes.empty()) continue;
                const glm::mat4 world = world_matrix(transforms[i]);
                const glm::vec4 colour = character_colour(options_.colour, states[i], anims[i], true);
                for (uint16_t j : rt.proxy_joints) lists_.proxies.push_back({world * boxes[j] * kHalfToUnit, colour});
                if (options_.overlay) gather_overlays(rt, refs[i].id, world);
            }
            continue;
        }
        if (!renderer_) continue;  // meshes need a renderer's topology ids
        for (size_t i = r.begin; i < r.end; ++i) {
            const SurfaceView surface = gc.surface(refs[i].id);
            if (surface.positions.empty()) continue;
            const uint32_t topology = topology_id(rt, surface);
            if (topology == kNoTopology) continue;
            const glm::mat4 world = world_matrix(transforms[i]);
            // With overlays on, the skin is left out so the inner layers (bones, muscles, springs) show.
            if (!options_.overlay)
                lists_.meshes.push_back({topology, surface.positions, surface.normals, world,
                                         character_colour(options_.colour, states[i], anims[i], false, !rt.render_materials.empty())});
            else
                gather_overlays(rt, refs[i].id, world);
        }
    }
}

void World::gather_overlays(const CharacterRuntime& rt, uint32_t id, const glm::mat4& world) {
    auto to_world = [&](const glm::vec3& p) { return glm::vec3(world * glm::vec4(p, 1.0f)); };
    if (options_.overlay & kOverlayBones) {
        const ConstPoseView pose = rt.motion->poses().view(id);
        const auto parents = rt.type.skeleton.parents();
        for (size_t j = 0; j < parents.size(); ++j)
            if (parents[j] >= 0)
                lists_.lines.push_back({to_world(glm::vec3(pose.model[static_cast<size_t>(parents[j])][3])),
                                        to_world(glm::vec3(pose.model[j][3])), glm::vec4(1.0f, 0.85f, 0.1f, 1.0f)});
    }
    rt.geometry->muscle_surface(id, overlay_muscles_);
    const std::span<const glm::vec3> muscle = overlay_muscles_;
    if (muscle.empty()) return;
    const GeomLod& lod = rt.geometry->level(rt.geometry->level_of(id));
    const uint32_t T = lod.theta_steps, P = lod.phi_steps, per = grid_vertex_count(T, P);
    if (T < 3 || P < 2 || muscle.size() % per != 0) return;
    if (options_.overlay & kOverlayMuscles) {  // each muscle's rings, as an outline
        for (size_t m = 0; m < muscle.size() / per; ++m)
            for (uint32_t r = 1; r < P; ++r)
                for (uint32_t t = 0; t < T; ++t)
                    lists_.lines.push_back({to_world(muscle[m * per + grid_ring_vertex(T, r, t)]),
                                            to_world(muscle[m * per + grid_ring_vertex(T, r, t + 1)]),
                                            glm::vec4(0.85f, 0.15f, 0.15f, 1.0f)});
    }
    const SurfaceView skin = rt.geometry->surface(id);
    if ((options_.overlay & kOverlaySprings) && skin.positions.size() == muscle.size())  // springs: muscle -> skin
        for (size_t k = 0; k < muscle.size(); ++k)
            lists_.lines.push_back({to_world(muscle[k]), to_world(skin.positions[k]), glm::vec4(0.2f, 0.9f, 0.9f, 1.0f)});
}

uint32_t World::topology_id(CharacterRuntime& rt, const SurfaceView& surface) {
    for (const auto& [key, id] : topologies_)
        if (key == surface.topology_key) return id;
    if (rt.render_materials.empty() && !rt.type.materials.empty()) {  // the type's textures and materials, once
        std::vector<uint32_t> textures;
        for (const TextureImage& t : rt.type.textures) {
            auto tex = renderer_->register_texture(t);
            if (!tex.ok()) {
                render_status_ = tex.error();
                return kNoTopology;
            }
            textures.push_back(tex.value());
        }
        for (const SurfaceMaterial& m : rt.type.materials) {
            const int texture = m.texture >= 0 && static_cast<size_t>(m.texture) < textures.size() ? static_cast<int>(textures[static_cast<size_t>(m.texture)]) : -1;
            auto mat = renderer_->register_material(m, texture);
            if (!mat.ok()) {
                render_status_ = mat.error();
                rt.render_materials.clear();
                return kNoTopology;
            }
            rt.render_materials.push_back(mat.value());
        }
    }
    TopologySurface materials;
    materials.uvs = rt.geometry->level_uvs(surface.level);
    materials.vertex_material = rt.geometry->level_vertex_materials(surface.level);
    materials.materials = rt.render_materials;
    // Double-sided materials (glTF doubleSided) need their back faces: no culling for the topology.
    bool double_sided = false;
    for (const SurfaceMaterial& m : rt.type.materials) double_sided = double_sided || m.double_sided;
    auto id = renderer_->register_topology(rt.geometry->level_indices(surface.level),
                                           static_cast<uint32_t>(surface.positions.size()), /*cull_back_faces=*/!double_sided, materials);
    if (!id.ok()) {
        render_status_ = id.error();
        return kNoTopology;
    }
    topologies_.emplace_back(surface.topology_key, id.value());
    return id.value();
}

std::vector<uint64_t> World::memory_per_level() const {
    std::vector<uint64_t> bytes(rules_.table().geom_levels.size(), 0);
    const uint64_t base = sizeof(Transform) + sizeof(Velocity) + sizeof(Bounds) + sizeof(Importance) +
                          sizeof(CharacterRef) + sizeof(LodAttributes) + sizeof(LodRequest) + sizeof(LodState) +
                          sizeof(GeomLod) + sizeof(AnimLod) + sizeof(MotionState);
    for (size_t l = 0; l < bytes.size(); ++l) {
        for (const auto& rt : types_) {
            const uint64_t pose = static_cast<uint64_t>(rt->joints()) *
                                  (sizeof(glm::vec3) * 2 + sizeof(glm::quat) + sizeof(glm::mat4) * 2);
            bytes[l] = std::max<uint64_t>(bytes[l], base + pose + rt->geometry->bytes_per_character(static_cast<uint8_t>(l)));
        }
    }
    return bytes;
}

}  // namespace aloha
