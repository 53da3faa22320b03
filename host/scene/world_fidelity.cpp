// Fidelity support for the profiler: the frame as it would look at full detail, and how far each
// character's LOD skin is from its full-detail skin on screen.
#include "host/scene/character_runtime.hpp"
#include "host/scene/world_diagnostics.hpp"
#include "systems/geometry/spring_skin/skin_mesh.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace aloha {

namespace {

// Pixel position of a world point (OpenGL-convention perspective camera: clip w = view depth); false when
// nearer than the near plane, where the renderer clips it (and the division would blow a millimetre up
// into millions of pixels).
bool to_pixels(const glm::mat4& view_proj, const glm::vec3& p, const glm::vec2& viewport, float near_plane, glm::vec2& out) {
    const glm::vec4 c = view_proj * glm::vec4(p, 1.0f);
    if (!(c.w >= near_plane)) return false;
    out = glm::vec2((c.x / c.w * 0.5f + 0.5f) * viewport.x, (0.5f - c.y / c.w * 0.5f) * viewport.y);
    return true;
}

// The screen rectangle of a character's bounds box (feet at `t.position`, +-radius, 0..height, scaled),
// clamped to the viewport; empty when a corner is nearer than the near plane.
SwitchRect bounds_rect(const glm::mat4& view_proj, const Transform& t, const Bounds& b, const glm::vec2& viewport, float near_plane) {
    SwitchRect out;
    const float h = b.height * t.scale, r = b.radius * t.scale;
    glm::vec2 lo(viewport), hi(0.0f);
    for (int k = 0; k < 8; ++k) {
        const glm::vec3 corner = t.position + glm::vec3(k & 1 ? r : -r, k & 2 ? h : 0.0f, k & 4 ? r : -r);
        glm::vec2 px;
        if (!to_pixels(view_proj, corner, viewport, near_plane, px)) return out;
        lo = glm::min(lo, px);
        hi = glm::max(hi, px);
    }
    out.x0 = std::max(0, static_cast<int>(std::floor(lo.x)));
    out.y0 = std::max(0, static_cast<int>(std::floor(lo.y)));
    out.x1 = std::min(static_cast<int>(viewport.x), static_cast<int>(std::ceil(hi.x)));
    out.y1 = std::min(static_cast<int>(viewport.y), static_cast<int>(std::ceil(hi.y)));
    if (out.x1 < out.x0) out.x1 = out.x0;
    if (out.y1 < out.y0) out.y1 = out.y0;
    return out;
}

}  // namespace

void World::set_reference_springs(bool on) {
    reference_springs_ = on;
    if (on) return;
    for (auto& rt : types_) rt->geometry->step_reference_springs(0, {}, rt->poses(), scene_.dt, {});
}

void World::step_reference_springs() {
    auto g = character_group(registry_);
    auto refs = g.span<CharacterRef>();
    auto transforms = g.span<Transform>();
    std::vector<std::vector<uint32_t>> ids(types_.size());  // one pass: each type's characters and placements
    std::vector<std::vector<Transform>> placements(types_.size());
    for (size_t i = 0; i < g.size(); ++i) ids[refs[i].type].push_back(refs[i].id), placements[refs[i].type].push_back(transforms[i]);
    for (size_t t = 0; t < types_.size(); ++t)
        types_[t]->geometry->step_reference_springs(0, ids[t], types_[t]->poses(), scene_.dt, placements[t]);
}

uint8_t reference_level(const RuleTable& table) {
    for (size_t l = 0; l < table.geom_levels.size(); ++l)
        if (table.geom_lod(static_cast<uint8_t>(l)).method == GeomMethod::Layered) return static_cast<uint8_t>(l);
    return 0;
}

Status reference_frame(World& host, ReferenceFrame& out) {
    CrowdRenderer* renderer = host.renderer();
    if (!renderer) return make_error("", "the fidelity check's reference frame needs an attached renderer");
    out.meshes.clear();
    out.deviation_sum.assign(host.rules().table().geom_levels.size(), 0.0);
    out.deviation_max.assign(out.deviation_sum.size(), 0.0);
    out.deviation_count.assign(out.deviation_sum.size(), 0);
    out.rest_deviation_sum.assign(out.deviation_sum.size(), 0.0);
    out.rest_deviation_count.assign(out.deviation_sum.size(), 0);
    out.moving_deviation_sum.assign(out.deviation_sum.size(), 0.0);
    out.moving_deviation_count.assign(out.deviation_sum.size(), 0);
    out.switches = 0;
    out.switch_rects.clear();
    auto g = character_group(host.registry());
    auto refs = g.span<CharacterRef>();
    auto transforms = g.span<Transform>();
    auto bounds = g.span<Bounds>();
    auto attributes = g.span<LodAttributes>();
    auto states = g.span<LodState>();
    const uint8_t picture_level = reference_level(host.rules().table());
    const LodCamera& camera = host.camera();
    const glm::mat4 view_proj = camera.projection * camera.view;
    const glm::vec2 viewport = camera.viewport_px;
    size_t used = 0;
    for (size_t i = 0; i < g.size(); ++i) {
        if (!attributes[i].visible) continue;
        if (states[i].seconds_at_geom == 0.0f && host.frame() > 0) {
            ++out.switches;
            SwitchRect rect = bounds_rect(view_proj, transforms[i], bounds[i], viewport, camera.near_plane);
            rect.from = states[i].prev_geom_level;
            rect.to = states[i].geom_level;
            out.switch_rects.push_back(rect);
        }
        const CharacterRuntime& rt = host.runtime(refs[i].type);
        const PoseSource poses = rt.poses();
        const glm::mat4 world = world_matrix(transforms[i]);
        // Screen-space deviation of the displayed control surface from the richest level's.
        rt.geometry->deviation_pairs(poses, refs[i].id, 0, out.current_scratch, out.reference_scratch, &out.rest_scratch,
                                     &out.moving_scratch);
        const uint8_t level = states[i].geom_level;
        for (size_t k = 0; k < out.current_scratch.size(); ++k) {
            glm::vec2 a, b, r;
            if (!to_pixels(view_proj, glm::vec3(world * glm::vec4(out.current_scratch[k], 1.0f)), viewport, camera.near_plane, a) ||
                !to_pixels(view_proj, glm::vec3(world * glm::vec4(out.reference_scratch[k], 1.0f)), viewport, camera.near_plane, b))
                continue;
            if (k < out.rest_scratch.size() &&
                to_pixels(view_proj, glm::vec3(world * glm::vec4(out.rest_scratch[k], 1.0f)), viewport, camera.near_plane, r)) {
                out.rest_deviation_sum[level] += glm::length(r - b);
                ++out.rest_deviation_count[level];
            }
            if (k < out.moving_scratch.size() &&
                to_pixels(view_proj, glm::vec3(world * glm::vec4(out.moving_scratch[k], 1.0f)), viewport, camera.near_plane, r)) {
                out.moving_deviation_sum[level] += glm::length(a - r);
                ++out.moving_deviation_count[level];
            }
            const double d = glm::length(a - b);
            out.deviation_sum[level] += d;
            out.deviation_max[level] = std::max(out.deviation_max[level], d);
            ++out.deviation_count[level];
        }
        // The full-detail picture: every visible character at the richest layered level.
        if (used == out.positions.size()) {
            out.positions.emplace_back();
            out.normals.emplace_back();
        }
        auto& pos = out.positions[used];
        auto& nrm = out.normals[used];
        rt.geometry->reference_surface(poses, refs[i].id, picture_level, pos);
        if (pos.empty()) continue;
        const std::span<const uint32_t> indices = rt.geometry->level_indices(picture_level);
        nrm.assign(pos.size(), glm::vec3(0.0f));
        accumulate_vertex_normals(pos, indices, nrm);
        SurfaceView view;
        view.level = picture_level;
        view.topology_key = rt.geometry->topology_key(picture_level);
        view.positions = pos;
        auto topology = host.draw_lists().topology(*renderer, refs[i].type, host.draw_types()[refs[i].type], view);
        if (!topology.ok()) return topology.error();
        // The shaded colouring's instance colour: white over the type's materials, skin tone without.
        out.meshes.push_back({topology.value(), pos, nrm, world,
                              host.draw_lists().textured(refs[i].type) ? glm::vec4(1.0f) : glm::vec4(0.86f, 0.68f, 0.56f, 1.0f)});
        ++used;
    }
    return {};
}

}  // namespace aloha
