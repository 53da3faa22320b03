// Per-bone muscle fitting for skinned characters that bring no muscle layout (glTF): one
// super-ellipsoid per bone from the vertices bound mostly to that bone, sitting inside the skin
// by the fat thickness.
#pragma once

#include "engine/anim/skeleton.hpp"
#include "engine/core/result.hpp"
#include "systems/geometry/muscle/muscle_set.hpp"

#include <glm/glm.hpp>

#include <span>
#include <string>

namespace aloha {

/// Parameters of fit_muscles_per_bone.
struct MuscleFitOptions {
    float fat_thickness = 0.01f;      ///< metres between each fitted muscle and the skin
    int min_vertices = 8;             ///< bones with fewer dominant vertices get no muscle
    float min_radius_fraction = 0.25f;///< radii never drop below this fraction of the skin's half-width
    bool insertion_on_child = true;   ///< anchor the far tendon on the child joint (muscle bulges as it bends)
    std::string source_name = "fit"; ///< names the mesh in errors
};

/// Fits one muscle per bone. `bind_model` holds the bind-pose model matrix of every skeleton joint;
/// `positions` are bind-pose vertices in the same model space; `joints`/`weights` are per-vertex
/// skin influences as skeleton joint indices (4 per vertex, weights need not be normalised).
/// Each vertex belongs to its largest-weight joint. Long axis: the bone direction (joint to first
/// non-zero child) when there is one, else the principal axis of the vertices; width/depth axes:
/// principal axes of the vertices across the long axis. Radii are half the vertex extents minus
/// the fat thickness. Muscles are named after their bone ("<joint>_muscle").
/// Errors: span lengths differ, joint index out of range, non-finite input.
Result<MuscleSet> fit_muscles_per_bone(const Skeleton& skeleton, std::span<const glm::mat4> bind_model,
                                       std::span<const glm::vec3> positions, std::span<const glm::ivec4> joints,
                                       std::span<const glm::vec4> weights, const MuscleFitOptions& options = {});

}  // namespace aloha
