// The implicit body surface the continuous skin is cut from: a smooth union of the rest-pose muscles
// inflated by their fat thickness (super-ellipsoids) and thin capsules along the bones (they bridge the
// gaps the muscle layout leaves, e.g. wrist and ankle), sampled on a regular grid and polygonised by
// marching tetrahedra.
//
// Distance estimate of one super-ellipsoid: with F its implicit function (superellipsoid.hpp) and A the
// phi exponent, r = F^(A/2) is homogeneous of degree 1 in the local point q, so q / r lies on the
// surface on the ray through q and d = |q| (1 - 1 / r) is the signed distance along that ray (exact
// on the surface, negative inside). Primitives combine with the polynomial smooth minimum
//   smin(a, b) = min(a, b) - k/4 * max(k - |a - b|, 0)^2 / k^2        (blend radius k),
// which rounds the creases where muscles meet (armpit, groin, neck) into one surface.
//
// Marching tetrahedra on the Freudenthal (Kuhn) split of every grid cube into six tetrahedra around its
// main diagonal: neighbouring cubes split their shared faces the same way, and the zero set of a
// piecewise linear field on a simplicial complex with no zero at a grid point is a closed 2-manifold,
// so the output has every edge in exactly two triangles as long as the field is positive on the grid's
// border (the bounds are padded). Grid values of exactly 0 are nudged to +1e-7 m.
#pragma once

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace aloha {

/// One inflated super-ellipsoid of the body field (model space).
struct FieldEllipsoid {
    glm::vec3 centre{0.0f};
    glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};  ///< local frame -> model space
    glm::vec3 radii{0.1f};                        ///< radii including the fat thickness (> 0)
    glm::vec2 exponents{1.0f};                    ///< (A, B), valid super-ellipsoid exponents
};

/// One capsule (segment a-b, radius r > 0) of the body field.
struct FieldCapsule {
    glm::vec3 a{0.0f}, b{0.0f};
    float radius = 0.01f;
};

/// A smooth union of primitives with blend radius `blend` (m, > 0). Primitives carry a group: group 0
/// (the trunk) blends with everything; primitives of two different non-zero groups (two limbs) are
/// joined by the plain minimum, so no blended web grows between limbs that lie close together:
/// field = min over groups g > 0 of smin(trunk, group g) (just the trunk without other groups). The trunk's own
/// field has its concavities filled first (trunk_fill), never a limb's: that would web limbs to the body.
struct BodyField {
    std::vector<FieldEllipsoid> ellipsoids;
    std::vector<FieldCapsule> capsules;
    std::vector<uint8_t> ellipsoid_group;  ///< one per ellipsoid, or empty (all 0)
    std::vector<uint8_t> capsule_group;    ///< one per capsule, or empty (all 0)
    float blend = 0.015f;
    float trunk_fill = 0.0f;  ///< fill_concavities' sigma (m) for the trunk's primitives (group 0); 0: none
};

/// A sampled field: values at the points origin + (i, j, k) * cell of an nx x ny x nz grid.
struct SampledField {
    glm::vec3 origin{0.0f};
    float cell = 0.01f;
    uint32_t nx = 0, ny = 0, nz = 0;
    std::vector<float> values;  ///< x fastest, then y, then z

    /// Trilinear interpolation at `p` (clamped to the grid).
    [[nodiscard]] float sample(glm::vec3 p) const;
    /// Central-difference gradient of sample() at `p` (step = cell / 2).
    [[nodiscard]] glm::vec3 gradient(glm::vec3 p) const;
};

/// An indexed triangle mesh (counter-clockwise seen from outside).
struct TriangleSurface {
    std::vector<glm::vec3> positions;
    std::vector<uint32_t> indices;
};

/// Distance estimate of one field primitive at `p` (negative inside).
[[nodiscard]] float ellipsoid_distance(const FieldEllipsoid& e, glm::vec3 p);
/// Distance from `p` to the capsule surface (negative inside).
[[nodiscard]] float capsule_distance(const FieldCapsule& c, glm::vec3 p);

/// Samples `field` on a grid of spacing `cell` (> 0) covering every primitive plus two cells and the
/// blend radius of margin, with enclosed voids filled. Each primitive only writes the grid points within its bounds + blend
/// (elsewhere it cannot change the smooth minimum). Requires at least one primitive.
[[nodiscard]] SampledField sample_body_field(const BodyField& field, float cell);

/// Fills the concave parts of a signed distance field sampled on `grid`'s points (`values`, laid out as
/// grid.values): each value becomes the lower of itself and its Gaussian blur (standard deviation `sigma` m, cut at
/// 3 sigma). A blur keeps a plane's distance, raises a convex surface's and lowers a concave one's, so only hollows,
/// grooves and creases a few sigma wide are filled, as skin and fat bridge the hollows between muscles; convex parts
/// (a neck, a shoulder's cap) keep their shape.
void fill_concavities(std::vector<float>& values, const SampledField& grid, float sigma);

/// Fills enclosed voids: grid points with a positive value that cannot be reached from the grid's
/// border through positive points (6-neighbours) are negated, so the zero set has no inner shells
/// (pockets left between muscles inside the body). sample_body_field calls it.
void fill_cavities(SampledField& field);

/// The zero set of `field` by marching tetrahedra, with vertices shared between tetrahedra (one per
/// crossed grid edge), triangles oriented outwards (towards increasing field).
[[nodiscard]] TriangleSurface polygonise(const SampledField& field);

}  // namespace aloha
