// Binding a skin (the generated body skin or an authored mesh) to the muscle layer across several
// muscles, and the fat springs that hang the skin on it.
//
// Bind (rest pose, once per skin and tessellation): for every skin vertex p and every muscle m, the
// muscle point on the ray from the muscle centre through p (radial projection: its (theta, phi) follow
// in closed form from the super-ellipsoid equations 1-3) is sampled on the tessellated muscle, giving
// a frame F_m (tangent, bitangent, normal), a point P_m and the distance d_m = |p - P_m|. The
// kBlendInfluences nearest muscles of compatible limb groups (nearest first, each pairwise
// compatible with those kept) are kept with weights
//     w_m = exp(-d_m / s) - exp(-d_(K+1) / s)          (s = spread, d_(K+1) the next nearest),
// normalised; subtracting the first left-out muscle's kernel makes every weight reach zero before a
// muscle leaves the set, so the weights are continuous over the rest surface and blend smoothly across
// joints. Each influence stores p's offset o_m = F_m^T (p - P_m).
// Per frame: root r = sum w_m P_m (a smooth blend of muscle-surface points) and rest end
// y = sum w_m (P_m + F_m o_m) (= p at the bind pose exactly). The fat spring runs from r to y: its
// rest length is h = |y - r| and its normal (y - r) / h, with the dynamics of fat_spring.hpp.
#pragma once

#include "systems/geometry/spring_skin/fat_spring.hpp"
#include "systems/geometry/spring_skin/grid_sample.hpp"

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace aloha {

/// Muscles one skin vertex blends.
inline constexpr int kBlendInfluences = 4;

/// Where one skin vertex hangs on the muscle layer (unused influences have weight 0).
struct BlendBinding {
    uint32_t muscle[kBlendInfluences] = {};       ///< muscle index within the character
    GridParam param[kBlendInfluences] = {};       ///< (theta, phi) of the muscle point
    GridCell cell[kBlendInfluences] = {};         ///< param's cell on the bind (T, P) grid (per-frame sampling)
    glm::vec3 offset[kBlendInfluences] = {};      ///< vertex - point in the point's (t, b, n) frame
    float weight[kBlendInfluences] = {};          ///< sum 1
};

/// Computes blend bindings of rest-pose skin vertices against rest-pose muscles.
struct BlendBindJob {
    uint32_t theta_steps = 8;                      ///< T of the muscle grids (>= 3)
    uint32_t phi_steps = 6;                        ///< P of the muscle grids (>= 2)
    float spread = 0.015f;                         ///< kernel distance s (m, > 0)
    std::span<const glm::vec3> centres;            ///< rest muscle centres (>= 1 muscle)
    std::span<const glm::quat> rotations;          ///< muscle frame -> model
    std::span<const glm::vec3> radii;              ///< (rx, ry, rz)
    std::span<const glm::vec2> exponents;          ///< (A, B) per muscle
    std::span<const glm::vec3> muscle_positions;   ///< tessellated rest muscles, muscles x V(T, P)
    std::span<const glm::vec3> muscle_normals;     ///< unit normals, same size
    std::span<const glm::vec3> skin_positions;     ///< rest-pose skin vertices (finite)
    std::span<BlendBinding> bindings;              ///< output, one per skin vertex
    /// Optional limb group per muscle (0 = trunk, skin_field.hpp): a vertex only blends muscles whose
    /// groups are pairwise equal or trunk, so skin near two limbs (hand by the thigh) follows one.
    /// Empty: all muscles compatible.
    std::span<const uint8_t> muscle_groups;
    /// Optional triangles of the skin (indices into skin_positions): with smooth_radius > 0 the
    /// kernel weights are smoothed over the skin's surface graph (weight_smoothing.hpp) before the
    /// kBlendInfluences largest compatible ones are kept. Empty: no smoothing.
    std::span<const uint32_t> skin_indices;
    float smooth_radius = 0.0f;                    ///< spread (m) of the smoothing (0: none)

    /// Checks sizes, spread and finiteness; one message per failure.
    bool Validate(std::vector<std::string>* errors = nullptr) const;
    /// Binds every vertex. Requires Validate().
    void Run() const;
};

/// The (theta, phi) of the radial projection of local point `q` onto a super-ellipsoid with radii
/// `radii` and exponents (A, B) (equations 1-3 inverted). q = 0 gives (0, 0).
[[nodiscard]] GridParam superellipsoid_param(glm::vec3 q, glm::vec3 radii, float a, float b);

/// The root of one skin vertex's fat spring: sum of weight x muscle point over `b`'s influences, on the
/// tessellated muscles `muscle_positions` (muscles x V(T, P), the (T, P) `b` was bound at). Requires
/// every influence's muscle present.
[[nodiscard]] glm::vec3 blend_root(std::span<const glm::vec3> muscle_positions, uint32_t theta_steps, uint32_t phi_steps,
                                   const BlendBinding& b);

/// Places one character's bound skin: the fat springs (root and rest end as above) stepped by the
/// exact damped-oscillator update of fat_spring.hpp, or, with `springs` false, the rest ends
/// directly (the skin without the fat dynamics; state untouched).
struct BlendSpringJob {
    uint32_t theta_steps = 8;                      ///< T of the current muscle grids (>= 3)
    uint32_t phi_steps = 6;                        ///< P of the current muscle grids (>= 2)
    uint32_t muscle_count = 1;                     ///< muscles of the character (> every influence)
    FatSpringParams params;                        ///< spring tuning (dt = this frame)
    bool springs = true;                           ///< false: skin = rest ends, no dynamics
    std::span<const glm::vec3> muscle_positions;   ///< muscle_count x V(T, P)
    std::span<const glm::vec3> muscle_normals;     ///< unit normals, same size
    std::span<const BlendBinding> bindings;        ///< one per skin vertex, bound at (T, P)
    FatSpringStateView state;                      ///< end (= skin output) / velocity / prev_rest per
                                                   ///< vertex, one `initialised` flag
    /// Optional per-region tuning: vertex i's springs use region_params[vertex_region[i]] (dt = this
    /// frame) instead of `params`. Empty vertex_region: `params` for every vertex.
    std::span<const uint8_t> vertex_region = {};
    std::span<const FatSpringParams> region_params = {};  ///< at most kMaxSpringTunings
    /// Checks sizes, parameters and influence indices; one message per failure.
    bool Validate(std::vector<std::string>* errors = nullptr) const;
    /// Updates state.end (the skin), four vertices at a time where it can (blend_rest.hpp: the same bits as one
    /// by one). Requires Validate().
    void Run() const;
};

}  // namespace aloha
