// MuscleShapeJob: model-space joint matrices of a range of characters -> per muscle centre,
// orientation and volume-preserving radii (paper eq. 5-8).
#pragma once

#include "systems/geometry/muscle/muscle_set.hpp"

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <span>
#include <string>
#include <vector>

namespace aloha {

/// Computes muscle shapes for `character_count` characters of one type. Character c uses
/// model[c * joint_count, (c + 1) * joint_count) and writes outputs [c * muscles, (c + 1) * muscles).
/// Muscle frame: x from origin to insertion, z from the depth hint carried by the origin joint
/// (made orthogonal to x), y = z cross x. Radii: rx = L/2, rz = sqrt(V / (k rx p)), ry = p rz.
/// Allocates nothing.
struct MuscleShapeJob {
    const MuscleSet* muscles = nullptr;      ///< resolved layout (required)
    std::span<const glm::mat4> model;        ///< characters * joint_count model-space joint matrices
    std::span<glm::vec3> centres;            ///< out: characters * muscles, model space (m)
    std::span<glm::quat> rotations;          ///< out: muscle frame -> model space
    std::span<glm::vec3> radii;              ///< out: (rx, ry, rz) metres

    /// Number of characters implied by `model` (0 when the layout is missing).
    [[nodiscard]] size_t character_count() const;
    /// Checks the layout is set, model is a whole number of characters, outputs are large enough.
    /// Appends every failure to `errors` when given.
    bool Validate(std::vector<std::string>* errors = nullptr) const;
    /// Runs the job. Requires Validate().
    void Run() const;
};

}  // namespace aloha
