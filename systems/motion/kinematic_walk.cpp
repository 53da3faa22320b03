#include "systems/motion/kinematic_walk.hpp"

#include "systems/motion/library/gait_model.hpp"
#include "systems/motion/local_to_model.hpp"

#include <algorithm>
#include <cmath>

namespace aloha {

namespace {
constexpr float kPi = 3.14159265358979f;

glm::vec3 to_world(const Transform& x, const glm::vec3& model) { return x.position + x.rotation * (model * x.scale); }
glm::vec3 to_model(const Transform& x, const glm::vec3& world) {
    return (glm::inverse(x.rotation) * (world - x.position)) / x.scale;
}
}  // namespace

float walk_stride(const WalkRig& rig, float speed, const GaitParams& gait) {
    return std::min(gait_cycle(std::max(speed, 0.0f), rig.ankle_height + rig.leg_length).stride,
                    gait.max_stride * rig.leg_length);
}

void sample_walk_cycle(const AnimationClip& clip, float time, SamplingCache* cache, const PoseView& out) {
    const float t = wrap_clip_time(time, clip.duration(), true);
    int k = 0;
    float alpha = 0.0f;
    find_key(clip, t, cache, &k, &alpha);
    sample_blocks(clip, k, alpha, out.translations.data(), out.rotations.data(), out.scales.data());
    // Remove the clip's average horizontal travel (the transform moves instead) and turn the clip
    // so it travels along +Z.
    const glm::vec3 d(clip.root_end().x - clip.root_start().x, 0.0f, clip.root_end().z - clip.root_start().z);
    const float frac = clip.duration() > 0.0f ? t / clip.duration() : 0.0f;
    glm::vec3& rt = out.translations[0];
    rt.x -= clip.root_start().x + d.x * frac;
    rt.z -= clip.root_start().z + d.z * frac;
    if (glm::length(d) > 1e-6f) {
        const glm::quat q = glm::angleAxis(-std::atan2(d.x, d.z), glm::vec3(0, 1, 0));
        rt = q * rt;
        out.rotations[0] = glm::normalize(q * out.rotations[0]);
    }
}

void advance_walk_phase(KinematicWalkState& state, const WalkRig& rig, float speed, float dt, const GaitParams& gait) {
    const float stride = walk_stride(rig, speed, gait);
    if (stride <= 0.0f) return;
    state.phase += dt * std::max(speed, 0.0f) / stride;
    state.phase -= std::floor(state.phase);
}

glm::vec3 joint_world_position(std::span<const glm::mat4> model, int joint, const Transform& placement) {
    return to_world(placement, glm::vec3(model[static_cast<size_t>(joint)][3]));
}

void kinematic_walk_pose(const WalkRig& rig, const Skeleton& skeleton, KinematicWalkState& state, float speed,
                         const Transform& placement, const PoseView& pose, const GaitParams& gait,
                         const AnimationClip* body) {
    const size_t n = static_cast<size_t>(skeleton.joint_count());
    if (body) {
        sample_walk_cycle(*body, state.phase * body->duration(), nullptr, pose);
    } else {
        const auto rt = skeleton.rest_translations();
        const auto rr = skeleton.rest_rotations();
        const auto rs = skeleton.rest_scales();
        for (size_t j = 0; j < n; ++j) {
            pose.translations[j] = rt[j];
            pose.rotations[j] = rr[j];
            pose.scales[j] = rs[j];
        }
    }
    const float stride = walk_stride(rig, speed, gait) / placement.scale;  // model units
    const float half_stance = 0.5f * gait.duty * stride;
    // Lower the hips until the farthest stance foot (half a stance ahead/behind) is within reach.
    const float reach = gait.reach * rig.leg_length;
    const float rest_leg_vertical = std::min(rig.thigh[0] + rig.shin[0], rig.thigh[1] + rig.shin[1]);
    const float vertical = std::min(rest_leg_vertical, std::sqrt(std::max(reach * reach - half_stance * half_stance, 0.0f)));
    const float hip_height = rig.ankle_height + vertical;
    glm::vec3& root = pose.translations[static_cast<size_t>(rig.root)];
    // The gait's pelvis sway and bob ride on top, never higher than the planted legs reach.
    root = body ? glm::vec3(root.x, std::min(root.y, hip_height + rig.hip_drop), 0.0f)
                : glm::vec3(0.0f, hip_height + rig.hip_drop, 0.0f);
    local_to_model(skeleton.parents().data(), pose.translations.data(), pose.rotations.data(), pose.scales.data(),
                   nullptr, pose.model.data(), n);

    const glm::vec3 fwd_world = placement.rotation * glm::vec3(0, 0, 1) * placement.scale;
    const glm::vec3 up_world(0, 1, 0);
    for (int side = 0; side < 2; ++side) {
        float phi = state.phase + (side == 0 ? 0.0f : 0.5f);
        phi -= std::floor(phi);
        // The foot's neutral spot: under the hip, ankle height above the ground.
        const glm::vec3 base = to_world(placement, glm::vec3(rig.hip_offset[side].x, rig.ankle_height, rig.hip_offset[side].z));
        glm::vec3 target_world;
        if (phi < gait.duty) {
            // Stance: the foot moves from half a stance ahead of the hip to half behind while the
            // root advances; plant it (once) where that puts it and then hold it still.
            if (!state.initialised || !state.stance[side])
                state.planted[side] = base + fwd_world * (half_stance - phi * stride);
            state.stance[side] = 1;
            target_world = state.planted[side];
        } else {
            const float s = (phi - gait.duty) / (1.0f - gait.duty);
            if (!state.initialised) state.planted[side] = base + fwd_world * (half_stance - gait.duty * stride);
            const glm::vec3 liftoff = state.planted[side];
            const glm::vec3 landing = base + fwd_world * ((1.0f - phi) * stride + half_stance);
            // The foot lifts before it travels (the first 10% of the swing) and reaches the landing
            // spot's vertical at 80%, then comes down onto it: a foot that moved forward in its first or
            // last centimetre off the ground would be seen (and measured) sliding, most of all between
            // the keys of a throttled update.
            const float sh = std::clamp((s - 0.1f) / 0.7f, 0.0f, 1.0f);
            const float e = sh * sh * (3.0f - 2.0f * sh);
            target_world = liftoff + (landing - liftoff) * e +
                           up_world * (gait.clearance * rig.leg_length * placement.scale * std::sin(kPi * s));
            state.stance[side] = 0;
        }
        solve_leg_ik(rig, skeleton, side, to_model(placement, target_world), glm::vec3(0, 0, 1), pose);
    }
    state.initialised = 1;
    local_to_model(skeleton.parents().data(), pose.translations.data(), pose.rotations.data(), pose.scales.data(),
                   nullptr, pose.model.data(), n);
}

}  // namespace aloha
