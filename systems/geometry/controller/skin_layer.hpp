// The skin layer of a character type at one tessellation: a closed triangle surface at rest (the
// project-generated continuous body skin for a type without a mesh, the authored mesh otherwise),
// every vertex bound to several muscles (blend_binding.hpp), plus linear-blend weights for the peeled
// skinned-mesh level.
//
// The generated body skin is built once per body variant as a dense surface (the smooth union of the
// rest muscles inflated by their fat and thin bone capsules, polygonised at kBodySkinCell), then
// simplified for each level to M * V(T, P) / 2 vertices (M * V(T, P) triangles): the same (T, P) that
// sets the muscle tessellation and the spring count (one spring per skin vertex) sets the skin's
// resolution.
#pragma once

#include "engine/anim/skeleton.hpp"
#include "systems/geometry/body_skin/blend_binding.hpp"
#include "systems/geometry/body_skin/skin_field.hpp"
#include "systems/geometry/muscle/muscle_set.hpp"
#include "systems/geometry/muscle/superellipsoid_tables.hpp"

#include <glm/glm.hpp>
#include <glm/gtc/type_precision.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace aloha {

struct GeneratedBindMesh;

/// The lengths below are set for people (a body 0.5 to 2.5 m tall). A body of another size takes them times
/// body_length_scale(its height), so a giant's skin is polygonised at as many cells a body, blended and bound over
/// the same share of it, as a person's (at 8 mm a 12 m body took minutes and came out as thin as a 2.5 m one).

/// Grid spacing (m) of the dense body surface.
inline constexpr float kBodySkinCell = 0.008f;
/// Blend radius (m) of the smooth union of muscles and capsules.
inline constexpr float kBodySkinBlend = 0.02f;
/// Hollows of the trunk's surface filled (fill_concavities' sigma, m): the pits between the trapezius, the
/// deltoids and the pectorals at the shoulders, the grooves between chest and belly.
inline constexpr float kBodySkinTrunkFill = 0.03f;
/// Kernel distance (m) of the multi-muscle binding weights.
inline constexpr float kBindSpread = 0.015f;
/// Spread (m) of the binding weights' smoothing over the skin graph (weight_smoothing.hpp): the
/// transition between two body parts' muscles takes a band this wide instead of one edge. 0.05 m
/// gave the lowest worst-edge stretch of 0.02 / 0.03 / 0.04 / 0.05 / 0.07 m on the humanoid's walk.
inline constexpr float kBindSmoothing = 0.05f;

/// The factor the body-skin lengths above take on a body `height` metres tall: 1 from 0.5 to 2.5 m, height / 2.5
/// above, height / 0.5 below (so continuous); 1 for a height that is not positive and finite (unknown).
[[nodiscard]] float body_length_scale(float height);

/// The dense implicit body surface of one body variant (shared by its levels).
struct BodySurface {
    SampledField field;      ///< signed distance estimate sampled on the grid
    TriangleSurface dense;   ///< marching-tetrahedra zero set
};

/// A skin layer at one (T, P).
struct SkinLayer {
    uint32_t theta_steps = 0, phi_steps = 0;   ///< tessellation the bindings were made at
    std::vector<glm::vec3> rest_positions;     ///< model space, rest pose
    std::vector<glm::vec3> rest_normals;       ///< unit, rest pose
    std::vector<uint32_t> indices;             ///< triangle list (counter-clockwise from outside)
    std::vector<BlendBinding> bindings;        ///< one per vertex
    std::vector<uint16_t> dominant_muscle;     ///< the influence with the largest weight, per vertex
    std::vector<glm::u16vec4> joints;          ///< generated skin: LBS joints (palette = model * inverse rest)
    std::vector<glm::vec4> weights;            ///< generated skin: LBS weights (sum 1)
};

/// Dense body surface of `muscles` at rest: muscles inflated by their fat thickness, capsules of half
/// the proxy radius along every bone, blended with kBodySkinBlend, polygonised at kBodySkinCell (both times
/// `length_scale`, body_length_scale of the body's height).
[[nodiscard]] BodySurface build_body_surface(const MuscleSet& muscles, const Skeleton& skeleton,
                                             std::span<const glm::mat4> rest_model, std::span<const float> proxy_radii,
                                             float length_scale = 1.0f);

/// The generated skin at the tables' (T, P): `body` simplified to M * V(T, P) triangles and relaxed,
/// bound to the rest muscles (influences restricted to compatible limbs of the skeleton `parents`; kBindSpread and
/// kBindSmoothing times `length_scale`), with LBS weights blended from `generated` (the per-muscle grid mesh at the
/// same (T, P)) by the binding weights.
[[nodiscard]] SkinLayer build_generated_skin(const BodySurface& body, const MuscleSet& muscles, std::span<const int16_t> parents,
                                             std::span<const glm::mat4> rest_model, const SuperEllipsoidTables& tables,
                                             const GeneratedBindMesh& generated, float length_scale = 1.0f);

/// Triangles of the generated skin at the tables' (T, P): M * V(T, P).
[[nodiscard]] uint32_t generated_skin_triangles(const MuscleSet& muscles, const SuperEllipsoidTables& tables);

/// build_generated_skin() from an already simplified and relaxed body surface `skin`
/// (simplify_and_relax[_all] of the body to generated_skin_triangles()): bound and LBS-weighted.
[[nodiscard]] SkinLayer bind_generated_skin(TriangleSurface skin, const MuscleSet& muscles, std::span<const int16_t> parents,
                                            std::span<const glm::mat4> rest_model, const SuperEllipsoidTables& tables,
                                            const GeneratedBindMesh& generated, float length_scale = 1.0f);

/// An authored mesh's skin layer at the tables' (T, P): its rest positions and triangles, bound to the
/// rest muscles (no LBS data: the mesh has its own).
[[nodiscard]] SkinLayer build_mesh_skin(std::span<const glm::vec3> rest_positions, std::span<const uint32_t> indices,
                                        const MuscleSet& muscles, std::span<const int16_t> parents,
                                        std::span<const glm::mat4> rest_model,
                                        const SuperEllipsoidTables& tables, float length_scale = 1.0f);

}  // namespace aloha
