// Draw lists of the impostor level: one ImpostorInstance per character (systems/render/impostor_atlas.hpp).
#include "systems/frame/draw_lists.hpp"

#include <cmath>

namespace aloha {

void DrawListBuilder::set_impostor(uint16_t type, uint32_t atlas, float cycle_s) {
    if (impostors_.size() <= type) impostors_.resize(size_t{type} + 1);
    impostors_[type] = {atlas, cycle_s > 0.0f ? cycle_s : 1.0f};
}

void DrawListBuilder::gather_impostors(const DrawType& draw, const LevelRange& r, const CharacterGroups& groups,
                                       std::span<const Transform> transforms, std::span<const LodState> states,
                                       std::span<const AnimLod> anims, std::span<const MotionState> motion,
                                       const DrawSettings& settings, RenderLists& out) const {
    if (r.type >= impostors_.size() || impostors_[r.type].atlas < 0) return;
    const Impostor& im = impostors_[r.type];
    const bool textured = !draw.materials.empty();  // the atlas holds the materials' colours
    for (uint32_t p = r.begin; p < r.end; ++p) {
        const uint32_t e = groups.order[p];
        const Transform& t = transforms[e];
        glm::vec3 f = t.rotation * glm::vec3(0.0f, 0.0f, 1.0f);
        glm::vec2 forward(f.x, f.z);
        const float len = glm::length(forward);
        forward = len > 1e-6f ? forward / len : glm::vec2(0.0f, 1.0f);
        float phase = -1.0f;  // standing
        if (motion.empty()) {
            phase = 0.0f;
        } else if (motion[e].active == RequestKind::Walk) {
            const MotionState& m = motion[e];
            phase = anims[e].walk == WalkMethod::ClipPlayback ? m.time / im.cycle_s - std::floor(m.time / im.cycle_s) : m.phase;
        }
        ImpostorInstance inst;
        inst.position_scale = glm::vec4(t.position, t.scale);
        inst.forward_phase = glm::vec4(forward, phase, 1.0f);
        inst.colour = character_colour(settings.colour, states[e], anims[e], false, textured);
        inst.atlas = static_cast<uint32_t>(im.atlas);
        out.impostors.push_back(inst);
    }
}

}  // namespace aloha
