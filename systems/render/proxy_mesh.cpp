#include "systems/render/proxy_mesh.hpp"

#include <cmath>

namespace aloha {

BoxMesh make_unit_box() {
    BoxMesh m{};
    // For each face: outward normal n and two tangents u, v with cross(u, v) = n (counter-clockwise).
    const glm::vec3 normals[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    for (uint32_t f = 0; f < 6; ++f) {
        const glm::vec3 n = normals[f];
        const glm::vec3 u = std::abs(n.y) > 0.5f ? glm::vec3(0, 0, n.y) : glm::vec3(-n.z, 0, n.x);
        const glm::vec3 v = glm::cross(n, u);
        const glm::vec3 c = 0.5f * n;
        const glm::vec3 corners[4] = {c - 0.5f * u - 0.5f * v, c + 0.5f * u - 0.5f * v, c + 0.5f * u + 0.5f * v,
                                      c - 0.5f * u + 0.5f * v};
        for (uint32_t k = 0; k < 4; ++k) {
            m.positions[f * 4 + k] = corners[k];
            m.normals[f * 4 + k] = n;
        }
        const uint32_t base = f * 4;
        const uint32_t tri[6] = {base, base + 1, base + 2, base, base + 2, base + 3};
        for (uint32_t k = 0; k < 6; ++k) m.indices[f * 6 + k] = tri[k];
    }
    return m;
}

void fill_box_batch_indices(uint32_t boxes, std::span<uint32_t> out) {
    const BoxMesh box = make_unit_box();
    std::array<uint32_t, kBoxIndexCount> corners{};
    for (uint32_t k = 0; k < kBoxIndexCount; ++k) corners[k] = box_corner_of(box.positions[box.indices[k]]);
    for (uint32_t b = 0; b < boxes; ++b)
        for (uint32_t k = 0; k < kBoxIndexCount; ++k) out[b * kBoxIndexCount + k] = b * kBoxCornerCount + corners[k];
}

glm::mat4 bone_box_matrix(glm::vec3 a, glm::vec3 b, float width) {
    const glm::vec3 axis = b - a;
    const float len = glm::length(axis);
    const glm::vec3 y = axis / len;
    const glm::vec3 helper = std::abs(y.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 0, 1);
    const glm::vec3 x = glm::normalize(glm::cross(helper, y));
    const glm::vec3 z = glm::cross(x, y);
    glm::mat4 m(1.0f);
    m[0] = glm::vec4(x * width, 0.0f);
    m[1] = glm::vec4(y * len, 0.0f);
    m[2] = glm::vec4(z * width, 0.0f);
    m[3] = glm::vec4(0.5f * (a + b), 1.0f);
    return m;
}

}  // namespace aloha
