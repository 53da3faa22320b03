// MuscleTessellateJob: muscle shapes (centre, orientation, radii) of a range of characters ->
// positions and unit outward normals in the surface_grid layout, all muscles of a character
// concatenated in muscle order, characters one after another.
#pragma once

#include "systems/geometry/muscle/superellipsoid_tables.hpp"

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <span>
#include <string>
#include <vector>

namespace aloha {

/// Tessellates `centres.size() / muscles` muscle shapes (a whole number of characters) at the
/// tables' (T, P). Vertex v of muscle m of character c lands at
/// (c * muscles + m) * (T*(P-1)+2) + v. Normals are the exact implicit-function gradients.
/// Allocates nothing; one tight loop over the whole range.
struct MuscleTessellateJob {
    const SuperEllipsoidTables* tables = nullptr;  ///< built for the muscle set being tessellated
    std::span<const glm::vec3> centres;            ///< characters * muscles (from MuscleShapeJob)
    std::span<const glm::quat> rotations;          ///< same count
    std::span<const glm::vec3> radii;              ///< same count
    std::span<glm::vec3> positions;                ///< out: shapes * vertices_per_muscle
    std::span<glm::vec3> normals;                  ///< out: same count

    /// Number of muscle grids the job writes (centres.size()).
    [[nodiscard]] size_t shape_count() const { return centres.size(); }
    /// Checks tables set, input spans of equal length and a whole number of characters, outputs
    /// large enough. Appends every failure to `errors` when given.
    bool Validate(std::vector<std::string>* errors = nullptr) const;
    /// Runs the job. Requires Validate().
    void Run() const;
};

}  // namespace aloha
