// A posing helper for generating clips offline: holds one local pose of a skeleton and its model
// matrices, sets joints by the model-space rotation wanted, solves two-bone chains analytically,
// and records key frames into a RawAnimation. Not for per-frame use (it allocates).
#pragma once

#include "engine/anim/raw_animation.hpp"
#include "engine/anim/skeleton.hpp"

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <vector>

namespace aloha {

/// Joints of the canonical humanoid (CMU names) that the motion generators drive; -1 when the
/// skeleton lacks one (that part of the motion is then left at rest).
struct HumanoidJoints {
    int root = -1;
    int spine[3] = {-1, -1, -1};   ///< lowerback, Chest, Chest2
    int neck[2] = {-1, -1};        ///< lowerneck, Neck
    int head = -1;
    int collar[2] = {-1, -1};      ///< left, right
    int shoulder[2] = {-1, -1};
    int elbow[2] = {-1, -1};
    int wrist[2] = {-1, -1};
};

/// Finds the joints above through the skeleton's humanoid map (engine/anim/humanoid_map.hpp).
[[nodiscard]] HumanoidJoints find_humanoid_joints(const Skeleton& skeleton);

/// One editable pose of `skeleton`, reset to rest, with model matrices kept up to date on demand.
class PoseBuilder {
public:
    /// Holds the skeleton by reference; it must outlive the builder.
    explicit PoseBuilder(const Skeleton& skeleton);

    /// Back to the rest pose.
    void reset();
    /// Recomputes every model matrix from the local pose.
    void update();
    /// Sets joint j's local rotation so its model rotation is `model_rotation` (the parent's model
    /// matrix must be current), and refreshes j's and its descendants' model matrices.
    void set_model_rotation(int j, const glm::quat& model_rotation);
    /// Model rotation of joint j in its rest pose.
    [[nodiscard]] glm::quat rest_model_rotation(int j) const { return rest_model_[static_cast<size_t>(j)]; }
    /// Current model rotation and position of joint j.
    [[nodiscard]] glm::quat model_rotation(int j) const;
    [[nodiscard]] glm::vec3 model_position(int j) const { return glm::vec3(model_[static_cast<size_t>(j)][3]); }
    /// Rest model position of joint j.
    [[nodiscard]] glm::vec3 rest_position(int j) const { return rest_pos_[static_cast<size_t>(j)]; }
    /// Analytic two-bone IK: rotates `upper` and `middle` so `end` reaches `target` (clamped to the
    /// reachable range), bending towards `pole` (model direction). Refreshes the model matrices.
    void two_bone(int upper, int middle, int end, const glm::vec3& target, const glm::vec3& pole);

    /// Local pose, for writing keys or sampling.
    std::vector<glm::vec3> translations;
    std::vector<glm::quat> rotations;

private:
    const Skeleton* skeleton_;
    std::vector<glm::vec3> scales_;
    std::vector<glm::mat4> model_;
    std::vector<glm::quat> rest_model_;
    std::vector<glm::vec3> rest_pos_;
};

/// Collects key frames of a PoseBuilder into a RawAnimation: the root gets translation and
/// rotation tracks, every other joint a rotation track.
class ClipRecorder {
public:
    /// Starts an empty clip called `name` for `skeleton`.
    ClipRecorder(const Skeleton& skeleton, std::string name);
    /// Appends the pose held by `pose` as the key at `time` (seconds, increasing).
    void add_key(float time, const PoseBuilder& pose);
    /// The finished clip (duration = last key time).
    [[nodiscard]] RawAnimation finish() &&;

private:
    RawAnimation clip_;
    int root_ = 0;
};

}  // namespace aloha
