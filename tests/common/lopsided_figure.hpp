// A lopsided figure for impostor tests (its views differ): a body ellipsoid 1.6 m tall standing on y = 0 and a head
// ellipsoid pushed forward (+Z) and to its left (+X), 1.77 m tall in all, with analytic normals.
#pragma once

#include <glm/glm.hpp>

#include <cmath>
#include <cstdint>
#include <vector>

namespace aloha::test {

struct LopsidedFigure {
    std::vector<glm::vec3> positions, normals;
    std::vector<uint32_t> indices;  ///< counter-clockwise from outside
    /// Adds an ellipsoid of `rings` x `segments` quads (two triangles each).
    void ellipsoid(glm::vec3 centre, glm::vec3 radii, uint32_t rings, uint32_t segments) {
        const auto base = static_cast<uint32_t>(positions.size());
        for (uint32_t r = 0; r <= rings; ++r)
            for (uint32_t s = 0; s <= segments; ++s) {
                const float phi = 3.14159265f * float(r) / float(rings), theta = 6.28318531f * float(s) / float(segments);
                const glm::vec3 u(std::sin(phi) * std::cos(theta), std::cos(phi), std::sin(phi) * std::sin(theta));
                positions.push_back(centre + u * radii);
                normals.push_back(u / radii);
            }
        for (uint32_t r = 0; r < rings; ++r)
            for (uint32_t s = 0; s < segments; ++s) {
                const uint32_t a = base + r * (segments + 1) + s, b = a + segments + 1;
                for (uint32_t i : {a, a + 1, b, a + 1, b + 1, b}) indices.push_back(i);
            }
    }
    LopsidedFigure() {
        ellipsoid({0.0f, 0.8f, 0.0f}, {0.28f, 0.8f, 0.16f}, 24, 32);
        ellipsoid({0.08f, 1.6f, 0.12f}, {0.13f, 0.17f, 0.15f}, 12, 16);
    }
};

}  // namespace aloha::test
