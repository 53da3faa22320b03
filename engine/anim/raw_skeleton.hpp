// Loader output for a skeleton: editable, unvalidated joint hierarchy as read from BVH or glTF.
// Build a runtime Skeleton from it with build_skeleton().
#pragma once

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <string>
#include <vector>

namespace aloha {

/// One joint as read from a file. `parent` is an index into RawSkeleton::joints or -1 for a root.
struct RawJoint {
    std::string name;
    int parent = -1;
    glm::vec3 translation{0.0f};                 ///< rest translation relative to the parent (metres)
    glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};  ///< rest rotation relative to the parent
    glm::vec3 scale{1.0f};                       ///< rest scale relative to the parent
};

/// A joint hierarchy in file order (parents need not precede children yet).
struct RawSkeleton {
    std::vector<RawJoint> joints;
};

/// Per-joint rotation limits as Euler angles (radians, XYZ intrinsic) of the local rotation
/// relative to the rest pose. `limited == false` means the joint is free.
struct JointLimit {
    glm::vec3 min_angles{-3.14159265f};
    glm::vec3 max_angles{3.14159265f};
    bool limited = false;
};

}  // namespace aloha
