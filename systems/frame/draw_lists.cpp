#include "systems/frame/draw_lists.hpp"

#include "systems/frame/placement.hpp"
#include "systems/geometry/surface_grid.hpp"
#include "systems/render/debug_colours.hpp"

namespace aloha {

glm::vec4 character_colour(DebugColour mode, const LodState& state, const AnimLod& anim, bool proxy, bool textured) {
    switch (mode) {
        case DebugColour::ByLodLevel: return colour_for_level(state.geom_level);
        case DebugColour::ByRule: return colour_for_rule(state.rule_id);
        case DebugColour::ByMotionMethod: return colour_for_motion_method(static_cast<int>(anim.walk));
        case DebugColour::Shaded: break;
    }
    if (textured) return glm::vec4(1.0f);
    return proxy ? glm::vec4(0.62f, 0.66f, 0.74f, 1.0f) : glm::vec4(0.86f, 0.68f, 0.56f, 1.0f);
}

void DrawListBuilder::reset() {
    topologies_.clear();
    materials_.clear();
}

Status DrawListBuilder::gather(CrowdRenderer* renderer, std::span<const DrawType> types, const CharacterGroups& groups,
                               std::span<const Transform> transforms, std::span<const LodState> states,
                               std::span<const AnimLod> anims, const DrawSettings& settings, RenderLists& out,
                               std::span<const MotionState> motion, std::span<const LodAttributes> attributes) {
    out.meshes.clear();
    out.proxies.clear();
    out.lines.clear();
    out.impostors.clear();
    out.proxy_fades.clear();
    out.drawn_twice = 0;
    fading_proxies_.clear();
    fading_runs_.clear();
    const Frame f{renderer, transforms, states, anims, motion, attributes, settings};
    // A character fading out of the impostor level into this range's drawn level: its share of pixels here,
    // the rest drawn as its impostor (1: not fading, or no impostor to fade with).
    auto fade_in = [&](const DrawType& draw, const GeometryController& gc, uint16_t type, uint32_t e, uint32_t id) {
        const LevelFade* fade = settings.overlay ? nullptr : gc.fade(id);
        if (!fade || fade->keeps_left() || !has_impostor(type)) return 1.0f;
        const float share = fade->drawn_share();
        out.impostors.push_back(impostor_instance(draw, type, e, f, share));
        ++out.drawn_twice;
        return share;
    };
    for (const LevelRange& r : groups.ranges) {
        const DrawType& draw = types[r.type];
        const GeometryController& gc = *draw.geometry;
        const GeomMethod method = gc.level(r.level).method;  // as this type draws it
        if (method == GeomMethod::Hidden) continue;
        if (method == GeomMethod::Impostor) {
            if (Status st = gather_impostors(draw, r, groups, f, out); !st.ok()) return st;
            continue;
        }
        if (method == GeomMethod::RigidProxy) {
            for (uint32_t p = r.begin; p < r.end; ++p) {
                const uint32_t e = groups.order[p], id = groups.ids[p];
                if (!f.in_view(e)) continue;
                const std::span<const glm::mat4> boxes = gc.proxy_boxes(id);
                if (boxes.empty()) continue;
                const glm::mat4 world = world_matrix(transforms[e]);
                const glm::vec4 colour = character_colour(settings.colour, states[e], anims[e], true);
                const float share = fade_in(draw, gc, r.type, e, id);
                std::vector<ProxyInstance>& to = share < 1.0f ? fading_proxies_ : out.proxies;
                const auto first = static_cast<uint32_t>(to.size());
                for (uint16_t j : draw.proxy_joints) to.push_back({proxy_box_matrix(world, boxes[j]), colour});
                if (share < 1.0f) fading_runs_.push_back({first, static_cast<uint32_t>(to.size()) - first, share});
                if (settings.overlay) overlays(draw, id, world, settings.overlay, out);
            }
            continue;
        }
        if (!renderer) continue;  // meshes need a renderer's topology ids
        for (uint32_t p = r.begin; p < r.end; ++p) {
            const uint32_t e = groups.order[p], id = groups.ids[p];
            if (!f.in_view(e)) continue;
            const SurfaceView surface = gc.surface(id);
            if (surface.positions.empty()) continue;
            const glm::mat4 world = world_matrix(transforms[e]);
            if (settings.overlay) {  // the skin is left out so the inner layers (bones, muscles, springs) show
                overlays(draw, id, world, settings.overlay, out);
                continue;
            }
            auto topology = this->topology(*renderer, r.type, draw, surface);
            if (!topology.ok()) return topology.error();
            const glm::vec4 colour = character_colour(settings.colour, states[e], anims[e], false, textured(r.type));
            // Between two mesh levels: the level left, kept posed, shows the pixels the entered one does not.
            const LevelFade* fade = gc.fade(id);
            float share = 1.0f;
            if (fade && fade->between_meshes) {
                if (const SurfaceView left = gc.fade_surface(id); !left.positions.empty()) {
                    auto left_topology = this->topology(*renderer, r.type, draw, left);
                    if (!left_topology.ok()) return left_topology.error();
                    share = fade->drawn_share();
                    out.meshes.push_back({left_topology.value(), left.positions, left.normals, world, colour, -share});
                    ++out.drawn_twice;
                }
            } else {
                share = fade_in(draw, gc, r.type, e, id);
            }
            out.meshes.push_back({topology.value(), surface.positions, surface.normals, world, colour, share});
        }
    }
    // The fading proxies last, so the others stay one draw (CrowdRenderer: one per gap between fade runs).
    const auto base = static_cast<uint32_t>(out.proxies.size());
    out.proxies.insert(out.proxies.end(), fading_proxies_.begin(), fading_proxies_.end());
    for (ProxyFade run : fading_runs_) {
        run.first += base;
        out.proxy_fades.push_back(run);
    }
    return {};
}

void DrawListBuilder::overlays(const DrawType& draw, uint32_t id, const glm::mat4& world, uint8_t bits, RenderLists& out) {
    auto to_world = [&](const glm::vec3& p) { return glm::vec3(world * glm::vec4(p, 1.0f)); };
    if ((bits & kOverlayBones) && draw.poses.model) {
        const std::span<const glm::mat4> pose = draw.poses.joints(id, draw.parents.size());
        for (size_t j = 0; j < draw.parents.size(); ++j)
            if (draw.parents[j] >= 0)
                out.lines.push_back({to_world(glm::vec3(pose[static_cast<size_t>(draw.parents[j])][3])), to_world(glm::vec3(pose[j][3])),
                                     glm::vec4(1.0f, 0.85f, 0.1f, 1.0f)});
    }
    draw.geometry->muscle_surface(id, muscle_scratch_);
    const std::span<const glm::vec3> muscle = muscle_scratch_;
    if (muscle.empty()) return;
    const GeomLod& lod = draw.geometry->level(draw.geometry->level_of(id));
    const uint32_t T = lod.theta_steps, P = lod.phi_steps, per = grid_vertex_count(T, P);
    if (T < 3 || P < 2 || muscle.size() % per != 0) return;
    if (bits & kOverlayMuscles) {  // each muscle's rings, as an outline
        for (size_t m = 0; m < muscle.size() / per; ++m)
            for (uint32_t r = 1; r < P; ++r)
                for (uint32_t t = 0; t < T; ++t)
                    out.lines.push_back({to_world(muscle[m * per + grid_ring_vertex(T, r, t)]),
                                         to_world(muscle[m * per + grid_ring_vertex(T, r, t + 1)]), glm::vec4(0.85f, 0.15f, 0.15f, 1.0f)});
    }
    // The springs of the control surface; a subdivided level displays the refined surface instead.
    if (!(bits & kOverlaySprings) || lod.method == GeomMethod::Subdivided) return;
    const SurfaceView skin = draw.geometry->surface(id);
    draw.geometry->spring_roots(id, muscle_scratch_);  // springs: root on the muscles -> skin vertex
    if (muscle_scratch_.size() > skin.positions.size()) return;
    for (size_t k = 0; k < muscle_scratch_.size(); ++k)
        out.lines.push_back({to_world(muscle_scratch_[k]), to_world(skin.positions[k]), glm::vec4(0.2f, 0.9f, 0.9f, 1.0f)});
}

Status DrawListBuilder::prepare(CrowdRenderer& renderer, std::span<const DrawType> types) {
    for (size_t t = 0; t < types.size(); ++t) {
        if (!types[t].geometry) continue;
        const GeometryController& gc = *types[t].geometry;
        for (uint8_t l = 0; l < gc.level_count(); ++l) {
            if (!drawn_as_mesh(gc.level(l).method) || gc.level_indices(l).empty() || gc.vertices_per_character(l) == 0) continue;
            auto id = topology(renderer, static_cast<uint16_t>(t), types[t], l, gc.topology_key(l), gc.vertices_per_character(l));
            if (!id.ok()) return id.error();
        }
    }
    return {};
}

Result<uint32_t> DrawListBuilder::topology(CrowdRenderer& renderer, uint16_t type, const DrawType& draw, uint8_t level,
                                           uint32_t topology_key, uint32_t vertex_count) {
    for (const auto& [key, id] : topologies_)
        if (key == topology_key) return id;
    if (materials_.size() <= type) materials_.resize(size_t{type} + 1);
    std::vector<uint32_t>& materials = materials_[type];
    if (materials.empty() && !draw.materials.empty()) {  // the type's textures and materials, once
        std::vector<uint32_t> textures;
        for (const TextureImage& t : draw.textures) {
            auto tex = renderer.register_texture(t);
            if (!tex.ok()) return tex.error();
            textures.push_back(tex.value());
        }
        for (const SurfaceMaterial& m : draw.materials) {
            auto mat = renderer.register_material(m, textures);
            if (!mat.ok()) {
                materials.clear();
                return mat.error();
            }
            materials.push_back(mat.value());
        }
    }
    TopologySurface surface_materials;
    surface_materials.uvs = draw.geometry->level_uvs(level);
    surface_materials.vertex_material = draw.geometry->level_vertex_materials(level);
    surface_materials.materials = materials;
    if (!materials.empty()) surface_materials.colours = draw.geometry->level_colours(level);
    // Double-sided materials (glTF doubleSided) need their back faces: no culling for the topology.
    bool double_sided = false;
    for (const SurfaceMaterial& m : draw.materials) double_sided = double_sided || m.double_sided;
    const bool vertex_lighting = drawn_lit_per_vertex(draw.geometry->level(level));
    renderer.declare_passes(pass_names_);  // levels drawn richest (nearest) first, whichever comes first
    auto id = renderer.register_topology(draw.geometry->level_indices(level), vertex_count,
                                         /*cull_back_faces=*/!double_sided, surface_materials,
                                         level < pass_names_.size() ? std::string_view(pass_names_[level]) : "meshes",
                                         vertex_lighting);
    if (!id.ok()) return id.error();
    topologies_.emplace_back(topology_key, id.value());
    return id.value();
}

}  // namespace aloha
