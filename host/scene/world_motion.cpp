// World::motion_sample: one character's joints, soles, animation level and method as the last frame
// left them, for the motion meters and the joint export.
#include "host/scene/world.hpp"

#include "host/scene/character_runtime.hpp"

#include "systems/lod/stats.hpp"

#include <cassert>

namespace aloha {

void World::motion_sample(uint32_t index, MotionSample& out) const {
    uint32_t first = 0;
    size_t t = 0;
    while (t < types_.size() && index >= first + types_[t]->count) first += types_[t++]->count;
    assert(t < types_.size() && "motion_sample: index out of range");
    const CharacterRuntime& rt = *types_[t];
    const uint32_t id = index - first;
    const uint32_t e = rt.element_of_character[id];

    auto& reg = const_cast<Registry&>(registry_);
    auto group = character_group(reg);
    const Transform& x = group.span<Transform>()[e];
    const AnimLod& lod = group.span<AnimLod>()[e];
    const MotionState& st = group.span<MotionState>()[e];

    out.type = static_cast<uint16_t>(t);
    out.id = id;
    out.anim_level = lod.level;
    out.update_interval = lod.update_interval;
    out.walking = st.active == RequestKind::Walk;
    out.method = out.walking ? std::string(to_string(rt.motion->resolved_walk_method(lod)))
                 : st.active == RequestKind::PlayClip ? "play_clip"
                                                      : "rest";
    out.in_transition = rt.motion->in_transition(id);
    out.root = x.position;

    const glm::mat4 world = world_matrix(x);
    const ConstPoseView pose = rt.motion->poses().view(id);
    out.joints.resize(pose.model.size());
    for (size_t j = 0; j < pose.model.size(); ++j) out.joints[j] = glm::vec3(world * pose.model[j][3]);
    out.soles.resize(rt.feet.size());
    for (size_t k = 0; k < rt.feet.size(); ++k)
        out.soles[k] = glm::vec3(world * (pose.model[static_cast<size_t>(rt.feet[k])] * glm::vec4(rt.soles[k], 1.0f)));
}

}  // namespace aloha
