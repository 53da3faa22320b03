// Interpolation for throttled characters (animation LOD with update interval N > 1), in the manner
// of Unreal's update-rate optimisation with interpolation: at each update the controller evaluates
// the pose now and the pose one interval ahead, and every frame in between shows their blend in
// model space (positions linearly, rotations by nlerp). A clip played in place moves a planted foot
// backwards at exactly the walking speed, linearly in time, so the blend keeps it planted while the
// transform carries the body on: no 15-fps look, no foot slipping by speed * dt per skipped frame.
#pragma once

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace aloha {

/// One joint's model-space transform, decomposed for interpolation.
struct ModelKey {
    glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};
    glm::vec3 position{0.0f};
    glm::vec3 scale{1.0f};
};

/// Splits an affine matrix with positive scale into rotation, translation and per-axis scale.
[[nodiscard]] ModelKey decompose_model(const glm::mat4& m);

/// Pairs of model-space key poses (the pose at the last update and one interval ahead) for the
/// characters that interpolate, in slots handed out and taken back serially.
class ThrottleKeys {
public:
    /// Key poses of `joint_count` joints.
    explicit ThrottleKeys(int joint_count) : joints_(static_cast<size_t>(joint_count)) {}
    /// A free slot (grows storage; not during parallel evaluation).
    uint32_t acquire();
    /// Returns `slot` to the free list.
    void release(uint32_t slot);
    /// Stores `model` as the slot's start (`ahead` false) or end pose. Requires joint_count matrices.
    void capture(uint32_t slot, bool ahead, std::span<const glm::mat4> model);
    /// Writes the blend of the slot's two poses at weight `w` in [0, 1] (0 = start) into `model`.
    void interpolate(uint32_t slot, float w, std::span<glm::mat4> model) const;
    /// Slots in use.
    [[nodiscard]] size_t in_use() const { return used_; }

private:
    size_t joints_;
    std::vector<ModelKey> keys_;  // slot s: [2s * joints, 2s * joints + joints) start, then end
    std::vector<uint32_t> free_;
    size_t used_ = 0;
};

}  // namespace aloha
