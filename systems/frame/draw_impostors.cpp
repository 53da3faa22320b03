// Draw lists of the impostor level: one ImpostorInstance per character (systems/render/impostor_atlas.hpp).
#include "systems/frame/draw_lists.hpp"
#include "systems/frame/placement.hpp"

#include <cassert>
#include <cmath>

namespace aloha {

void DrawListBuilder::set_impostor(uint16_t type, uint32_t atlas, float cycle_s, float scale) {
    assert(scale > 0.0f);
    if (impostors_.size() <= type) impostors_.resize(size_t{type} + 1);
    impostors_[type] = {atlas, cycle_s > 0.0f ? cycle_s : 1.0f, scale};
}

ImpostorInstance DrawListBuilder::impostor_instance(const DrawType& draw, uint16_t type, uint32_t e, const Frame& f,
                                                    float drawn_share) const {
    const Impostor& im = impostors_[type];
    const Transform& t = f.transforms[e];
    glm::vec3 fw = t.rotation * glm::vec3(0.0f, 0.0f, 1.0f);
    glm::vec2 forward(fw.x, fw.z);
    const float len = glm::length(forward);
    forward = len > 1e-6f ? forward / len : glm::vec2(0.0f, 1.0f);
    float phase = -1.0f;  // standing
    if (f.motion.empty()) {
        phase = 0.0f;
    } else if (f.motion[e].active == RequestKind::Walk) {
        const MotionState& m = f.motion[e];
        phase = f.anims[e].walk == WalkMethod::ClipPlayback ? m.time / im.cycle_s - std::floor(m.time / im.cycle_s) : m.phase;
    } else if (f.motion[e].active == RequestKind::PlayClip && f.motion[e].travelling) {
        phase = f.motion[e].phase;  // a clip whose root motion carries it: walking at its stride (MotionState::travelling)
    }
    ImpostorInstance inst;
    inst.position_scale = glm::vec4(t.position, t.scale * im.scale);
    // Fade: shaders/impostor.frag keeps, for w < 0, the pixels a mesh dithered at -w does not keep.
    inst.forward_phase = glm::vec4(forward, phase, drawn_share < 1.0f ? impostor_fade(drawn_share) : 1.0f);
    inst.colour = character_colour(f.settings.colour, f.states[e], f.anims[e], false, !draw.materials.empty());  // the atlas holds the materials' colours
    inst.atlas = static_cast<uint32_t>(im.atlas);
    return inst;
}

Status DrawListBuilder::gather_impostors(const DrawType& draw, const LevelRange& r, const CharacterGroups& groups, const Frame& f,
                                         RenderLists& out) {
    if (!has_impostor(r.type)) return {};
    const GeometryController& gc = *draw.geometry;
    for (uint32_t p = r.begin; p < r.end; ++p) {
        const uint32_t e = groups.order[p], id = groups.ids[p];
        if (!f.in_view(e)) continue;
        const LevelFade* fade = f.settings.overlay ? nullptr : gc.fade(id);
        if (!fade || !fade->into_impostor()) {
            out.impostors.push_back(impostor_instance(draw, r.type, e, f, 1.0f));
            continue;
        }
        // Fading in from a drawn level: that level's surface (or boxes), kept posed, takes its share of the pixels.
        const float share = fade->drawn_share();
        const glm::mat4 world = world_matrix(f.transforms[e]);
        bool drawn = false;
        if (const std::span<const glm::mat4> boxes = gc.fade_proxy_boxes(id); !boxes.empty()) {
            const glm::vec4 colour = character_colour(f.settings.colour, f.states[e], f.anims[e], true);
            const auto first = static_cast<uint32_t>(fading_proxies_.size());
            for (uint16_t j : draw.proxy_joints) fading_proxies_.push_back({proxy_box_matrix(world, boxes[j]), colour});
            fading_runs_.push_back({first, static_cast<uint32_t>(fading_proxies_.size()) - first, share});
            drawn = true;
        } else if (const SurfaceView surface = gc.fade_surface(id); !surface.positions.empty() && f.renderer) {
            auto topology = this->topology(*f.renderer, r.type, draw, surface);
            if (!topology.ok()) return topology.error();
            out.meshes.push_back({topology.value(), surface.positions, surface.normals, world,
                                  character_colour(f.settings.colour, f.states[e], f.anims[e], false, textured(r.type)), share});
            drawn = true;
        }
        out.impostors.push_back(impostor_instance(draw, r.type, e, f, drawn ? share : 1.0f));
        out.drawn_twice += drawn ? 1u : 0u;
    }
    return {};
}

}  // namespace aloha
