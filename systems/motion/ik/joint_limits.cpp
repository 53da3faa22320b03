#include "systems/motion/ik/joint_limits.hpp"

#include <algorithm>
#include <cmath>

namespace aloha::ik {

glm::vec3 euler_xyz(const glm::quat& q) {
    // Row-major entries of R = Rx(a) Ry(b) Rz(c): r02 = sin b, r12 = -sa cb, r22 = ca cb,
    // r01 = -cb sc, r00 = cb cc.
    const glm::mat3 m = glm::mat3_cast(q);  // column-major: m[col][row]
    const float r02 = m[2][0];
    const float r12 = m[2][1];
    const float r22 = m[2][2];
    const float r01 = m[1][0];
    const float r00 = m[0][0];
    const float b = std::asin(std::clamp(r02, -1.0f, 1.0f));
    if (std::abs(r02) < 0.9999f) {
        return {std::atan2(-r12, r22), b, std::atan2(-r01, r00)};
    }
    // Gimbal lock: only a +/- c is defined; put it all in a (c = 0).
    const float r21 = m[1][2];
    const float r11 = m[1][1];
    return {std::atan2(r21, r11), b, 0.0f};
}

glm::quat quat_from_euler_xyz(const glm::vec3& e) {
    const glm::quat qx = glm::angleAxis(e.x, glm::vec3(1, 0, 0));
    const glm::quat qy = glm::angleAxis(e.y, glm::vec3(0, 1, 0));
    const glm::quat qz = glm::angleAxis(e.z, glm::vec3(0, 0, 1));
    return qx * qy * qz;
}

glm::vec3 relative_euler_xyz(const glm::quat& rest, const glm::quat& local) {
    return euler_xyz(glm::normalize(glm::inverse(rest) * local));
}

glm::quat clamp_to_limit(const JointLimit& limit, const glm::quat& rest, const glm::quat& local) {
    if (!limit.limited) return local;
    const glm::vec3 e = relative_euler_xyz(rest, local);
    const glm::vec3 c = glm::clamp(e, limit.min_angles, limit.max_angles);
    if (c == e) return local;
    return glm::normalize(rest * quat_from_euler_xyz(c));
}

void euler_axes(const glm::quat& rest, const glm::vec3& e, glm::vec3 axes[3]) {
    const glm::quat qx = rest * glm::angleAxis(e.x, glm::vec3(1, 0, 0));
    axes[0] = rest * glm::vec3(1, 0, 0);
    axes[1] = qx * glm::vec3(0, 1, 0);
    axes[2] = (qx * glm::angleAxis(e.y, glm::vec3(0, 1, 0))) * glm::vec3(0, 0, 1);
}

float best_angle_about(const glm::vec3& axis, const glm::vec3* a, const glm::vec3* b, int count) {
    // b . R(t) a_perp = cos t (a_perp . b) + sin t (axis . (a_perp x b)): maximum at atan2(S, C).
    float s = 0.0f;
    float c = 0.0f;
    for (int i = 0; i < count; ++i) {
        const glm::vec3 ap = a[i] - glm::dot(a[i], axis) * axis;
        s += glm::dot(axis, glm::cross(ap, b[i]));
        c += glm::dot(ap, b[i]);
    }
    if (std::abs(s) < 1e-12f && std::abs(c) < 1e-12f) return 0.0f;
    return std::atan2(s, c);
}

}  // namespace aloha::ik
