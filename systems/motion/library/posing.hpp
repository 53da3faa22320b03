// Posing steps shared by the motion generators: easing curves, the trunk and head between pelvis
// and thorax rotations, an arm swung and flexed, and a leg planted by two-bone IK with the foot
// pitched. All rotations are model-space deltas applied to the joints' rest model rotations, so
// the generators work on any skeleton that names these joints, whatever its rest frames.
#pragma once

#include "systems/motion/library/pose_builder.hpp"
#include "systems/motion/walk_rig.hpp"

namespace aloha {

/// Hermite ease, 0 -> 1 with zero slope at both ends (x clamped to [0, 1]).
[[nodiscard]] float smoothstep(float x);
/// Quintic ease, 0 -> 1 with zero slope and curvature at both ends (x clamped to [0, 1]).
[[nodiscard]] float smootherstep(float x);
/// Rotation of a foot pitched by `pitch` radians (toes up > 0) about the lateral (X) axis.
[[nodiscard]] glm::quat foot_pitch_rotation(float pitch);

/// Rotates the spine from the pelvis delta towards `thorax` (lowerback, Chest, Chest2) and keeps
/// the head level and facing forward (lowerneck, Neck, Head). Missing joints are skipped.
void pose_trunk(PoseBuilder& pose, const HumanoidJoints& joints, const glm::quat& pelvis, const glm::quat& thorax);

/// The model-space delta of arm `side` (0 left, 1 right) swung forward by `flexion` radians
/// (backward < 0) and out by `abduction`, turned with the thorax's yaw only.
[[nodiscard]] glm::quat arm_swing(const glm::quat& thorax, int side, float flexion, float abduction);

/// Rotates the upper arm of `side` by the model delta `arm` and flexes the elbow by `elbow` radians
/// about the arm's own flexion axis (the forearm and hand follow).
void pose_arm(PoseBuilder& pose, const HumanoidJoints& joints, int side, const glm::quat& arm, float elbow);

/// Plants leg `side`: two-bone IK puts the ankle at `ankle` (model space), knee towards `forward`;
/// the foot is pitched by `pitch`, the toe segment by `toe_pitch` (absolute, toes up > 0).
void plant_leg(PoseBuilder& pose, const WalkRig& rig, int side, const glm::vec3& ankle, float pitch, float toe_pitch,
               const glm::vec3& forward, float yaw = 0.0f);

}  // namespace aloha
