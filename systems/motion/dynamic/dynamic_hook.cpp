#include "systems/motion/dynamic/dynamic_hook.hpp"

#include <algorithm>
#include <cmath>

namespace aloha {

namespace {

// Rigid character frame (position + rotation; the simulation runs in metres, so no scale).
glm::mat4 rigid_frame(const Transform& t) {
    glm::mat4 m = glm::mat4_cast(glm::normalize(t.rotation));
    m[3] = glm::vec4(t.position, 1.0f);
    return m;
}

void dynamic_hook(void* user, MethodContext& m) {
    auto& cx = *static_cast<DynamicHookContext*>(user);
    if (m.character >= cx.characters.size() || !m.skeleton || !m.transform) return;
    DynamicCharacter& dc = cx.characters[m.character];
    if (dc.failed || !(m.dt > 0.0f) || !std::isfinite(m.dt)) return;  // keep the kinematic pose
    const Skeleton& sk = *m.skeleton;
    const auto n = static_cast<size_t>(sk.joint_count());
    const glm::mat4 frame = rigid_frame(*m.transform);
    if (!dc.initialised) {
        // Enter the method from the pose the character has now (the kinematic gait pose).
        const ConstPoseView start{m.pose.translations, m.pose.rotations, m.pose.scales, m.pose.model};
        if (!init_dynamic_walk(sk, start, frame, dc.state, cx.settings).ok()) {
            dc.failed = 1;
            return;
        }
        dc.target.resize(n);
        dc.initialised = 1;
        dc.steps = 0;
    }
    std::copy(m.pose.rotations.begin(), m.pose.rotations.end(), dc.target.begin());
    // Targets and output are expressed in the character's current frame; the bodies live in the
    // world, so moving the frame each step is only a change of coordinates.
    dc.state.root_world = frame;
    const glm::vec3 root_now = glm::vec3(frame * glm::vec4(m.pose.translations[0], 1.0f));
    const glm::vec3 root_before = dc.state.has_prev_target ? dc.state.prev_target_root : root_now;
    const glm::mat4 to_frame = glm::inverse(frame);
    const int steps = std::clamp(static_cast<int>(std::ceil(m.dt / cx.max_step - 1e-4f)), 1, 8);
    const float h = m.dt / static_cast<float>(steps);
    for (int i = 1; i <= steps; ++i) {
        // The root target moves linearly over the posed interval, so its velocity stays right.
        const float a = static_cast<float>(i) / static_cast<float>(steps);
        const glm::vec3 root_world = root_before + (root_now - root_before) * a;
        const glm::vec3 root_local = glm::vec3(to_frame * glm::vec4(root_world, 1.0f));
        // A push under way acts for whole steps while it lasts (its impulse is force x time).
        dc.state.pelvis_force = dc.push_left > 0.5f * h ? dc.push_force : glm::vec3(0.0f);
        dc.push_left = std::max(0.0f, dc.push_left - h);
        step_dynamic_walk(sk, dc.target, root_local, h, dc.state, m.pose, nullptr);
        ++dc.steps;
    }
}

void dynamic_release(void* user, uint32_t character) {
    auto& cx = *static_cast<DynamicHookContext*>(user);
    if (character >= cx.characters.size()) return;
    cx.characters[character] = DynamicCharacter{};  // frees the simulation buffers
}

}  // namespace

bool push_dynamic_walker(DynamicHookContext& context, uint32_t character, const glm::vec3& impulse) {
    if (character >= context.characters.size()) return false;
    DynamicCharacter& dc = context.characters[character];
    if (!dc.initialised || dc.failed || dc.state.bodies.empty()) return false;
    if (!std::isfinite(impulse.x + impulse.y + impulse.z)) return false;
    dc.push_force = impulse / kDynamicPushSeconds;
    dc.push_left = kDynamicPushSeconds;
    return true;
}

size_t DynamicHookContext::simulated() const {
    return static_cast<size_t>(std::count_if(characters.begin(), characters.end(),
                                             [](const DynamicCharacter& c) { return c.initialised != 0; }));
}

void register_dynamic_walk_hook(MotionController& controller, DynamicHookContext& context) {
    context.characters.clear();
    context.characters.resize(controller.capacity());
    controller.set_method_hook(MethodSlot::DynamicWalk, &dynamic_hook, &context, &dynamic_release);
}

}  // namespace aloha
