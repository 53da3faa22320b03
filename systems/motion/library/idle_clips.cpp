#include "systems/motion/library/idle_clips.hpp"

#include "systems/motion/library/gait_clip.hpp"
#include "systems/motion/library/posing.hpp"

#include <algorithm>
#include <cmath>

namespace aloha {

namespace {

constexpr float kTwoPi = 6.28318530718f;
constexpr float kDeg = 0.0174532925f;

// The standing body at time t of the idle cycle (period kIdleSeconds): root offset from the rest
// root (x sway, y dip), pelvis and thorax deltas, a glance of the head.
struct Stance {
    glm::vec3 root_offset;
    glm::quat pelvis, thorax;
    float glance;
    float breath;
};

Stance stance_at(float t, float body_scale, float shift) {
    const float w = kTwoPi * t / kIdleSeconds;
    Stance s;
    s.breath = std::sin(2.0f * w);  // two breaths per cycle
    s.root_offset = glm::vec3(shift * body_scale * std::sin(w), -body_scale * (0.012f + 0.004f * std::cos(2.0f * w)), 0.0f);
    s.pelvis = glm::angleAxis(2.0f * kDeg * std::sin(w), glm::vec3(0, 0, 1));
    s.thorax = glm::angleAxis(2.0f * kDeg * std::sin(w + 1.0f), glm::vec3(0, 1, 0)) *
               glm::angleAxis(1.2f * kDeg * s.breath, glm::vec3(1, 0, 0));
    s.glance = 10.0f * kDeg * std::sin(w + 0.5f);
    return s;
}

// Poses the idle stance at time t with both feet flat at `feet` (model space, yaw per foot).
void pose_stance(PoseBuilder& pose, const WalkRig& rig, const HumanoidJoints& joints, const Stance& s, float root_yaw,
                 const glm::vec3 feet[2], const float foot_yaw[2], const float lift[2]) {
    pose.reset();
    const glm::vec3 rest_root = pose.rest_position(rig.root);
    pose.translations[static_cast<size_t>(rig.root)] = glm::vec3(0.0f, rest_root.y, 0.0f) + s.root_offset;
    const glm::quat yaw = glm::angleAxis(root_yaw, glm::vec3(0, 1, 0));
    const glm::quat pelvis = yaw * s.pelvis, thorax = yaw * s.thorax;
    pose.set_model_rotation(rig.root, pelvis * pose.rest_model_rotation(rig.root));
    pose_trunk(pose, joints, pelvis, thorax);
    if (joints.head >= 0)
        pose.set_model_rotation(joints.head, yaw * glm::angleAxis(s.glance, glm::vec3(0, 1, 0)) *
                                                 pose.rest_model_rotation(joints.head));
    for (int k = 0; k < 2; ++k) {
        pose_arm(pose, joints, k, arm_swing(thorax, k, 1.5f * kDeg * s.breath, 6.0f * kDeg), 10.0f * kDeg);
        const glm::vec3 fwd = glm::angleAxis(foot_yaw[k], glm::vec3(0, 1, 0)) * glm::vec3(0, 0, 1);
        plant_leg(pose, rig, k, feet[k] + glm::vec3(0.0f, lift[k], 0.0f), 0.0f, 0.0f, fwd, foot_yaw[k]);
    }
}

// Rest ankle position of each side on the ground, relative to the root's vertical axis.
glm::vec3 rest_foot(const PoseBuilder& pose, const WalkRig& rig, int side) {
    const glm::vec3 a = pose.rest_position(rig.ankle[side]) - pose.rest_position(rig.root);
    return glm::vec3(a.x, rig.ankle_height, a.z);
}

int key_count(float seconds) { return static_cast<int>(std::lround(seconds * kGeneratedKeyRate)); }

// Both feet flat where they stand at rest, not turned, not lifted.
struct StandingFeet {
    glm::vec3 feet[2];
    float yaw[2] = {0.0f, 0.0f};
    float lift[2] = {0.0f, 0.0f};
};

// Records a clip standing on the rest feet: keys + 1 keys over `seconds`, each posed by
// pose_at(t, body_scale, pose, feet).
template <class PoseAt>
RawAnimation record_standing(const Skeleton& skeleton, const WalkRig& rig, const std::string& name, float seconds, int keys,
                             PoseAt pose_at) {
    PoseBuilder pose(skeleton);
    const float scale = rig.leg_length / 0.86f;
    StandingFeet f;
    f.feet[0] = rest_foot(pose, rig, 0);
    f.feet[1] = rest_foot(pose, rig, 1);
    ClipRecorder rec(skeleton, name);
    for (int i = 0; i <= keys; ++i) {
        const float t = seconds * static_cast<float>(i) / static_cast<float>(keys);
        pose_at(t, scale, pose, f);
        rec.add_key(t, pose);
    }
    return std::move(rec).finish();
}

}  // namespace

RawAnimation make_idle_clip(const Skeleton& skeleton, const WalkRig& rig, const HumanoidJoints& joints,
                            const std::string& name) {
    const int keys = key_count(kIdleSeconds) / 2;  // slow motion: 30 keys per second is plenty
    return record_standing(skeleton, rig, name, kIdleSeconds, keys, [&](float t, float scale, PoseBuilder& pose, const StandingFeet& f) {
        pose_stance(pose, rig, joints, stance_at(t, scale, 0.03f), 0.0f, f.feet, f.yaw, f.lift);
    });
}

RawAnimation make_turn_clip(const Skeleton& skeleton, const WalkRig& rig, const HumanoidJoints& joints,
                            const std::string& name) {
    PoseBuilder pose(skeleton);
    const float scale = rig.leg_length / 0.86f;
    const glm::vec3 home[2] = {rest_foot(pose, rig, 0), rest_foot(pose, rig, 1)};
    const float rate = kTwoPi / kTurnSeconds;  // rad/s, turning left (+Y)
    const float step = kTurnSeconds / 4.0f;    // one step of each foot per `step` seconds
    // Foot k swings during [start_k, start_k + 0.4 step) of every step and lands where the body
    // will face 0.3 steps later, so it stays planted, still, until its next swing.
    auto foot_yaw = [&](int k, float t, float* lift) {
        const float start = k == 0 ? 0.0f : 0.5f * step;
        const float tau = (t - start) / step;
        const float c = std::floor(tau), s = tau - c;
        const float planted_before = rate * step * (c - 1.0f + 0.7f) + rate * start;
        const float planted_after = rate * step * (c + 0.7f) + rate * start;
        if (s >= 0.4f) {
            *lift = 0.0f;
            return planted_after;
        }
        *lift = 0.04f * scale * std::sin(3.14159265f * s / 0.4f);
        return glm::mix(planted_before, planted_after, smootherstep((s / 0.4f - 0.15f) / 0.7f));
    };
    ClipRecorder rec(skeleton, name);
    const int keys = key_count(kTurnSeconds);
    for (int i = 0; i <= keys; ++i) {
        const float t = kTurnSeconds * static_cast<float>(i) / static_cast<float>(keys);
        float lift[2], yaw[2];
        glm::vec3 feet[2];
        for (int k = 0; k < 2; ++k) {
            yaw[k] = foot_yaw(k, t, &lift[k]);
            feet[k] = glm::angleAxis(yaw[k], glm::vec3(0, 1, 0)) * home[k];
        }
        Stance s = stance_at(0.0f, scale, 0.0f);
        s.glance = 15.0f * kDeg;  // look into the turn
        pose_stance(pose, rig, joints, s, rate * t, feet, yaw, lift);
        rec.add_key(t, pose);
    }
    return std::move(rec).finish();
}

RawAnimation make_wave_clip(const Skeleton& skeleton, const WalkRig& rig, const HumanoidJoints& joints,
                            const std::string& name) {
    return record_standing(skeleton, rig, name, kWaveSeconds, key_count(kWaveSeconds), [&](float t, float scale, PoseBuilder& pose,
                                                                                          const StandingFeet& f) {
        // Weight shift of the idle, scaled into the wave's length so the clip still loops.
        const Stance s = stance_at(t * kIdleSeconds / kWaveSeconds, scale, 0.01f);
        pose_stance(pose, rig, joints, s, 0.0f, f.feet, f.yaw, f.lift);
        // Right arm: raised sideways, turned out so the elbow bends upwards, forearm waving.
        const float up = smoothstep(t / 0.6f) * (1.0f - smoothstep((t - (kWaveSeconds - 0.6f)) / 0.6f));
        const float wave = 20.0f * kDeg * std::sin(kTwoPi * 2.0f * (t - 0.6f)) * smoothstep((t - 0.4f) / 0.4f) *
                           (1.0f - smoothstep((t - (kWaveSeconds - 0.8f)) / 0.4f));
        const glm::quat arm = glm::angleAxis(-80.0f * kDeg * up, glm::vec3(0, 0, 1)) *
                              glm::angleAxis(-90.0f * kDeg * up, glm::vec3(0, 1, 0));
        pose_arm(pose, joints, 1, arm, 100.0f * kDeg * up + wave * up);
    });
}

}  // namespace aloha
