// The unit box drawn instanced for the rigid-proxy level (one box per bone).
#pragma once

#include <glm/glm.hpp>

#include <array>
#include <cstdint>
#include <span>

namespace aloha {

/// Vertices of the unit box [-0.5, 0.5]^3: 4 per face so each face has its own flat normal.
inline constexpr uint32_t kBoxVertexCount = 24;
/// Indices of the unit box: 2 triangles per face, counter-clockwise seen from outside.
inline constexpr uint32_t kBoxIndexCount = 36;

/// Unit box geometry: positions, outward face normals and triangle indices.
struct BoxMesh {
    std::array<glm::vec3, kBoxVertexCount> positions;  ///< corners of [-0.5, 0.5]^3
    std::array<glm::vec3, kBoxVertexCount> normals;    ///< outward unit normal of each vertex's face
    std::array<uint32_t, kBoxIndexCount> indices;      ///< triangle list into positions
};

/// Builds the unit box (deterministic; same data every call).
[[nodiscard]] BoxMesh make_unit_box();

/// Corners per box in the batched proxy draw (shaders/lit_mesh.vert box mode).
inline constexpr uint32_t kBoxCornerCount = 8;

/// Corner number (bit 0: x, bit 1: y, bit 2: z set when that coordinate is +0.5) of a unit-box position.
[[nodiscard]] constexpr uint32_t box_corner_of(glm::vec3 p) {
    return (p.x > 0.0f ? 1u : 0u) | (p.y > 0.0f ? 2u : 0u) | (p.z > 0.0f ? 4u : 0u);
}

/// Writes the index list of `boxes` unit boxes drawn as one mesh: box b uses corners b * 8 .. b * 8 + 7,
/// triangles as in make_unit_box(). Requires out.size() >= boxes * kBoxIndexCount.
void fill_box_batch_indices(uint32_t boxes, std::span<uint32_t> out);

/// Model matrix placing the unit box along a bone from `a` to `b` with square cross-section `width`
/// (the box's local y axis follows the bone). Requires a != b.
[[nodiscard]] glm::mat4 bone_box_matrix(glm::vec3 a, glm::vec3 b, float width);

}  // namespace aloha
