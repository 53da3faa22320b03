// Super-ellipsoid maths (Barr; ALOHA paper eq. 1-8): surface points with signed powers, exact
// normals from the implicit function's gradient, volume, and volume-preserving radii.
//
//   x = rx * cos(phi)^A * cos(theta)^B      (1)      c^e means sign(c) * |c|^e
//   y = ry * cos(phi)^A * sin(theta)^B      (2)      -pi <= theta < pi, -pi/2 <= phi <= pi/2
//   z = rz * sin(phi)^A                     (3)
//
// Implicit form: F(x,y,z) = (|x/rx|^(2/B) + |y/ry|^(2/B))^(B/A) + |z/rz|^(2/A) = 1.
#pragma once

#include <glm/glm.hpp>

namespace aloha {

/// Smallest and largest accepted exponent A or B. Above 2 the normal is singular at the poles
/// (cos^(2-A) blows up); below 0.1 float powers lose the shape (near-cube corners).
inline constexpr float kMinSuperExponent = 0.1f;
inline constexpr float kMaxSuperExponent = 1.9f;

/// Signed power sign(c) * |c|^e. Requires e > 0; returns 0 for c == 0.
[[nodiscard]] float signed_pow(float c, float e);
/// Double-precision signed power (used to build tessellation tables). Requires e > 0.
[[nodiscard]] double signed_pow(double c, double e);

/// True when A and B lie in [kMinSuperExponent, kMaxSuperExponent] (and are not NaN).
[[nodiscard]] bool valid_super_exponents(float a, float b);

/// Local-frame surface point of eq. 1-3 at (theta, phi) for radii r and exponents (A, B).
[[nodiscard]] glm::vec3 superellipsoid_point(glm::vec3 radii, float a, float b, float theta, float phi);

/// Unit outward normal at (theta, phi): the normalised gradient of F at the eq. 1-3 point,
/// proportional to (cos(phi)^(2-A) cos(theta)^(2-B) / rx, cos(phi)^(2-A) sin(theta)^(2-B) / ry,
/// sin(phi)^(2-A) / rz). Requires valid exponents and positive radii.
[[nodiscard]] glm::vec3 superellipsoid_normal(glm::vec3 radii, float a, float b, float theta, float phi);

/// Implicit function F (1 on the surface, < 1 inside). Requires positive radii.
[[nodiscard]] double superellipsoid_implicit(glm::dvec3 p, glm::dvec3 radii, double a, double b);

/// Volume factor k(A, B) with V = k * rx * ry * rz:
///   k = 2/3 * A * B * Beta(A/2, A) * Beta(B/2, B/2)    (= 4 pi / 3 for A = B = 1, eq. 4).
/// (Equivalent to Jaklic's 2 A B Beta(A/2 + 1, A) Beta(B/2, B/2).) Requires A, B > 0.
[[nodiscard]] double superellipsoid_volume_factor(double a, double b);

/// Volume of the super-ellipsoid with radii r and exponents (A, B).
[[nodiscard]] double superellipsoid_volume(glm::dvec3 radii, double a, double b);

/// Volume-preserving radii (eq. 5-8 generalised by the shape factor k): rx' = length / 2,
/// rz' = sqrt(volume / (k * rx' * p)), ry' = p * rz'. Requires length > 0, volume > 0, p > 0, k > 0.
[[nodiscard]] glm::vec3 volume_preserving_radii(float length, float volume, float ratio_p, float volume_factor);

}  // namespace aloha
