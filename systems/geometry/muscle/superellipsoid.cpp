#include "systems/geometry/muscle/superellipsoid.hpp"

#include <cmath>

namespace aloha {

float signed_pow(float c, float e) {
    if (c == 0.0f) return 0.0f;
    const float m = std::pow(std::fabs(c), e);
    return c < 0.0f ? -m : m;
}

double signed_pow(double c, double e) {
    if (c == 0.0) return 0.0;
    const double m = std::pow(std::fabs(c), e);
    return c < 0.0 ? -m : m;
}

bool valid_super_exponents(float a, float b) {
    return a >= kMinSuperExponent && a <= kMaxSuperExponent && b >= kMinSuperExponent && b <= kMaxSuperExponent;
}

glm::vec3 superellipsoid_point(glm::vec3 radii, float a, float b, float theta, float phi) {
    const float ca = signed_pow(std::cos(phi), a), sa = signed_pow(std::sin(phi), a);
    const float cb = signed_pow(std::cos(theta), b), sb = signed_pow(std::sin(theta), b);
    return {radii.x * ca * cb, radii.y * ca * sb, radii.z * sa};
}

glm::vec3 superellipsoid_normal(glm::vec3 radii, float a, float b, float theta, float phi) {
    const float ca = signed_pow(std::cos(phi), 2.0f - a), sa = signed_pow(std::sin(phi), 2.0f - a);
    const float cb = signed_pow(std::cos(theta), 2.0f - b), sb = signed_pow(std::sin(theta), 2.0f - b);
    return glm::normalize(glm::vec3(ca * cb / radii.x, ca * sb / radii.y, sa / radii.z));
}

double superellipsoid_implicit(glm::dvec3 p, glm::dvec3 radii, double a, double b) {
    const double xy = std::pow(std::fabs(p.x / radii.x), 2.0 / b) + std::pow(std::fabs(p.y / radii.y), 2.0 / b);
    return std::pow(xy, b / a) + std::pow(std::fabs(p.z / radii.z), 2.0 / a);
}

double superellipsoid_volume_factor(double a, double b) {
    auto beta = [](double x, double y) { return std::exp(std::lgamma(x) + std::lgamma(y) - std::lgamma(x + y)); };
    return 2.0 / 3.0 * a * b * beta(a / 2.0, a) * beta(b / 2.0, b / 2.0);
}

double superellipsoid_volume(glm::dvec3 radii, double a, double b) {
    return superellipsoid_volume_factor(a, b) * radii.x * radii.y * radii.z;
}

glm::vec3 volume_preserving_radii(float length, float volume, float ratio_p, float volume_factor) {
    const float rx = 0.5f * length;
    const float rz = std::sqrt(volume / (volume_factor * rx * ratio_p));
    return {rx, ratio_p * rz, rz};
}

}  // namespace aloha
