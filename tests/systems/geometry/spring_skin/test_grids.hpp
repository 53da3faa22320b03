// Synthetic muscle grids for the spring_skin tests: ellipsoids in the surface_grid layout
// (x = a cos(phi) cos(theta), y = b cos(phi) sin(theta), z = c sin(phi)), placed by a matrix.
#pragma once

#include "systems/geometry/surface_grid.hpp"

#include <glm/glm.hpp>

#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

namespace aloha::test {

/// Positions and unit normals of concatenated grids.
struct Grids {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;
};

/// Appends one ellipsoid grid with radii `radii`, transformed by the rigid/affine `placement`.
inline void append_ellipsoid(Grids& g, uint32_t T, uint32_t P, glm::vec3 radii, const glm::mat4& placement = glm::mat4(1.0f)) {
    const float pi = std::numbers::pi_v<float>;
    const glm::mat3 normal_matrix = glm::transpose(glm::inverse(glm::mat3(placement)));
    auto add = [&](float theta, float phi) {
        const glm::vec3 local(radii.x * std::cos(phi) * std::cos(theta), radii.y * std::cos(phi) * std::sin(theta),
                              radii.z * std::sin(phi));
        const glm::vec3 n = local / (radii * radii);
        g.positions.push_back(glm::vec3(placement * glm::vec4(local, 1.0f)));
        g.normals.push_back(glm::normalize(normal_matrix * n));
    };
    add(0.0f, -0.5f * pi);
    for (uint32_t r = 1; r < P; ++r)
        for (uint32_t t = 0; t < T; ++t)
            add(-pi + static_cast<float>(t) * 2.0f * pi / static_cast<float>(T), -0.5f * pi + static_cast<float>(r) * pi / static_cast<float>(P));
    add(0.0f, 0.5f * pi);
}

/// One ellipsoid grid.
inline Grids ellipsoid(uint32_t T, uint32_t P, glm::vec3 radii, const glm::mat4& placement = glm::mat4(1.0f)) {
    Grids g;
    append_ellipsoid(g, T, P, radii, placement);
    return g;
}

}  // namespace aloha::test
