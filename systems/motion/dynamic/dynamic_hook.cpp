#include "systems/motion/dynamic/dynamic_hook.hpp"

#include "systems/motion/inertialize.hpp"

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

// Model matrix (character frame) of joint `j` in `pose` from its local transforms; allocates nothing.
glm::mat4 chain_model(const Skeleton& sk, const PoseView& pose, int j) {
    glm::mat4 m(1.0f);
    for (int k = j; k >= 0; k = sk.parents()[static_cast<size_t>(k)]) {
        const auto u = static_cast<size_t>(k);
        m = trs_matrix(pose.translations[u], pose.rotations[u], pose.scales[u]) * m;
    }
    return m;
}

// After a hand-back: the kinematic pose in `pose` plus the decaying offset from the last simulated pose.
void apply_fallback(const DynamicHookContext& cx, DynamicCharacter& dc, float dt, const PoseView& pose) {
    dc.fallback_elapsed += dt;
    const float w = inertial_weight(dc.fallback_elapsed, cx.fallback_seconds);
    if (w <= 0.0f) return;
    const glm::quat id(1.0f, 0.0f, 0.0f, 0.0f);
    for (size_t j = 0; j < pose.rotations.size(); ++j) {
        pose.rotations[j] = glm::normalize(glm::slerp(id, dc.offset_rotations[j], w) * pose.rotations[j]);
        pose.translations[j] += w * dc.offset_translations[j];
    }
}

// The simulation came apart this step: show the kinematic pose (saved before the step) and keep
// the last simulated pose shown as an offset that decays (inertialization).
void hand_back(const DynamicHookContext& cx, DynamicCharacter& dc, const PoseView& pose) {
    for (size_t j = 0; j < pose.rotations.size(); ++j) {
        pose.rotations[j] = dc.target[j];
        pose.translations[j] = dc.kinematic_translations[j];
        glm::quat q = dc.shown_rotations[j] * glm::inverse(pose.rotations[j]);
        if (q.w < 0.0f) q = -q;  // the shorter arc
        dc.offset_rotations[j] = glm::normalize(q);
        dc.offset_translations[j] = dc.shown_translations[j] - pose.translations[j];
    }
    dc.diverged = 1;
    dc.fallback_elapsed = 0.0f;
    apply_fallback(cx, dc, 0.0f, pose);
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
        dc.kinematic_translations.resize(n);
        dc.offset_rotations.resize(n);
        dc.offset_translations.resize(n);
        dc.shown_rotations.assign(m.pose.rotations.begin(), m.pose.rotations.end());
        dc.shown_translations.assign(m.pose.translations.begin(), m.pose.translations.end());
        dc.initialised = 1;
        dc.diverged = 0;
        dc.steps = 0;
    }
    if (dc.diverged) {  // handed back: the kinematic pose, the last simulated one decaying into it
        apply_fallback(cx, dc, m.dt, m.pose);
        return;
    }
    std::copy(m.pose.rotations.begin(), m.pose.rotations.end(), dc.target.begin());
    std::copy(m.pose.translations.begin(), m.pose.translations.end(), dc.kinematic_translations.begin());
    // The root body's joint (the pelvis, also under an Unreal "root" joint) as the kinematic pose has it.
    const glm::mat4 root_model = chain_model(sk, m.pose, dc.state.root_joint);
    const glm::mat3 root_axes(glm::normalize(glm::vec3(root_model[0])), glm::normalize(glm::vec3(root_model[1])),
                              glm::normalize(glm::vec3(root_model[2])));
    const glm::quat pelvis_target = glm::normalize(glm::quat_cast(glm::mat3(frame)) * glm::quat_cast(root_axes));
    // Targets and output are expressed in the character's current frame; the bodies live in the
    // world, so moving the frame each step is only a change of coordinates.
    dc.state.root_world = frame;
    const glm::vec3 root_now = glm::vec3(frame * root_model[3]);
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
        step_dynamic_walk(sk, dc.target, root_local, h, dc.state, m.pose, nullptr, dc.kinematic_translations);
        ++dc.steps;
        if (dynamic_walk_diverged(dc.state, pelvis_target, cx.guard)) {
            hand_back(cx, dc, m.pose);
            return;
        }
    }
    std::copy(m.pose.rotations.begin(), m.pose.rotations.end(), dc.shown_rotations.begin());
    std::copy(m.pose.translations.begin(), m.pose.translations.end(), dc.shown_translations.begin());
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
    if (!dc.initialised || dc.failed || dc.diverged || dc.state.bodies.empty()) return false;
    if (!std::isfinite(impulse.x + impulse.y + impulse.z)) return false;
    dc.push_force = impulse / kDynamicPushSeconds;
    dc.push_left = kDynamicPushSeconds;
    return true;
}

bool dynamic_walk_diverged(const DynamicWalkState& state, const glm::quat& pelvis_target, const DynamicGuard& guard) {
    if (state.bodies.empty()) return false;
    if (state.failed_factorisations > 0) return true;
    for (const DynamicBody& b : state.bodies) {
        const float speed = glm::length(b.v);
        if (!std::isfinite(speed + b.x.x + b.x.y + b.x.z + b.q.w) || speed > guard.max_body_speed) return true;
    }
    if (max_constraint_error(state) > guard.max_joint_gap) return true;
    glm::quat d = state.bodies[0].q * glm::inverse(pelvis_target);
    if (d.w < 0.0f) d = -d;
    return 2.0f * std::acos(std::clamp(d.w, -1.0f, 1.0f)) > guard.max_pelvis_tilt;
}

size_t DynamicHookContext::diverged() const {
    return static_cast<size_t>(std::count_if(characters.begin(), characters.end(),
                                             [](const DynamicCharacter& c) { return c.initialised != 0 && c.diverged != 0; }));
}

size_t DynamicHookContext::simulated() const {
    return static_cast<size_t>(std::count_if(characters.begin(), characters.end(),
                                             [](const DynamicCharacter& c) { return c.initialised != 0; }));
}

void register_dynamic_walk_hook(MotionController& controller, DynamicHookContext& context) {
    context.characters.clear();
    context.characters.resize(controller.capacity());
    if (context.settings.contact_points.empty() && controller.walk_rig())
        context.settings.contact_points = dynamic_sole_contacts(controller.skeleton(), *controller.walk_rig());
    // The pelvis is the root body, also when the skeleton's root is a joint above it (Unreal's "root").
    if (context.settings.root_joint < 0 && controller.walk_rig()) context.settings.root_joint = controller.walk_rig()->root;
    controller.set_method_hook(MethodSlot::DynamicWalk, &dynamic_hook, &context, &dynamic_release);
}

}  // namespace aloha
