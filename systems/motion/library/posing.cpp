#include "systems/motion/library/posing.hpp"

#include <algorithm>
#include <cmath>

namespace aloha {

float smoothstep(float x) {
    x = std::clamp(x, 0.0f, 1.0f);
    return x * x * (3.0f - 2.0f * x);
}

float smootherstep(float x) {
    x = std::clamp(x, 0.0f, 1.0f);
    return x * x * x * (x * (6.0f * x - 15.0f) + 10.0f);
}

glm::quat foot_pitch_rotation(float pitch) { return glm::angleAxis(-pitch, glm::vec3(1, 0, 0)); }

void pose_trunk(PoseBuilder& pose, const HumanoidJoints& j, const glm::quat& pelvis, const glm::quat& thorax) {
    const float spine_share[3] = {0.4f, 0.75f, 1.0f};
    for (int i = 0; i < 3; ++i)
        if (j.spine[i] >= 0)
            pose.set_model_rotation(j.spine[i], glm::slerp(pelvis, thorax, spine_share[i]) * pose.rest_model_rotation(j.spine[i]));
    // The head stays level and faces the direction of travel (vestibular stabilisation).
    const glm::quat head(1.0f, 0.0f, 0.0f, 0.0f);
    const int chain[3] = {j.neck[0], j.neck[1], j.head};
    const float neck_share[3] = {0.4f, 0.7f, 1.0f};
    for (int i = 0; i < 3; ++i)
        if (chain[i] >= 0)
            pose.set_model_rotation(chain[i], glm::slerp(thorax, head, neck_share[i]) * pose.rest_model_rotation(chain[i]));
}

glm::quat arm_swing(const glm::quat& thorax, int side, float flexion, float abduction) {
    const glm::vec3 f = thorax * glm::vec3(0, 0, 1);
    const glm::quat yaw = glm::angleAxis(std::atan2(f.x, f.z), glm::vec3(0, 1, 0));
    const float out = side == 0 ? abduction : -abduction;  // +X is the left side
    return yaw * glm::angleAxis(-flexion, glm::vec3(1, 0, 0)) * glm::angleAxis(out, glm::vec3(0, 0, 1));
}

void pose_arm(PoseBuilder& pose, const HumanoidJoints& j, int side, const glm::quat& arm, float elbow) {
    if (j.shoulder[side] < 0) return;
    pose.set_model_rotation(j.shoulder[side], arm * pose.rest_model_rotation(j.shoulder[side]));
    const glm::quat forearm = arm * glm::angleAxis(-elbow, glm::vec3(1, 0, 0));
    if (j.elbow[side] >= 0) pose.set_model_rotation(j.elbow[side], forearm * pose.rest_model_rotation(j.elbow[side]));
    if (j.wrist[side] >= 0) pose.set_model_rotation(j.wrist[side], forearm * pose.rest_model_rotation(j.wrist[side]));
}

void plant_leg(PoseBuilder& pose, const WalkRig& rig, int side, const glm::vec3& ankle, float pitch, float toe_pitch,
               const glm::vec3& forward, float yaw) {
    pose.two_bone(rig.hip[side], rig.knee[side], rig.ankle[side], ankle, forward);
    const glm::quat heading = glm::angleAxis(yaw, glm::vec3(0, 1, 0));
    pose.set_model_rotation(rig.ankle[side], heading * foot_pitch_rotation(pitch) * pose.rest_model_rotation(rig.ankle[side]));
    if (rig.toe[side] >= 0)
        pose.set_model_rotation(rig.toe[side],
                                heading * foot_pitch_rotation(toe_pitch) * pose.rest_model_rotation(rig.toe[side]));
}

}  // namespace aloha
