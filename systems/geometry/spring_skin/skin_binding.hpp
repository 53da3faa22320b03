// Binding a real skinned mesh (e.g. from glTF) to the muscle layer so the muscles bulge it.
//
// At bind pose every mesh vertex is tied by a spring to its nearest muscle surface point: we store
// the muscle index, the point's continuous grid coordinates (theta, phi) and the vertex's offset in
// the local frame there (tangent along theta, bitangent, outward normal; the normal component is
// the spring's rest length). Each frame the vertex is placed at the deformed muscle point at the
// same (theta, phi) plus the offset in the deformed frame. Grid coordinates, not triangle ids, are
// stored, so the binding evaluates on any (T, P) the LOD picks (exact at the bind tessellation).
#pragma once

#include "systems/geometry/spring_skin/grid_sample.hpp"

#include <glm/glm.hpp>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace aloha {

/// Where one mesh vertex hangs on the muscle layer.
struct SkinBinding {
    uint32_t muscle = 0;           ///< muscle (grid) index within the character
    GridParam param;               ///< (theta, phi) of the nearest muscle point at bind pose
    glm::vec3 offset{0.0f};        ///< vertex - point in (tangent, bitangent, normal) coordinates
};

/// Binds mesh vertices to the nearest point of a character's bind-pose muscles (brute force over
/// every muscle triangle: a load-time job, O(vertices x triangles)).
struct SkinBindJob {
    uint32_t theta_steps = 8;                      ///< T of the bind-pose muscle grids (>= 3)
    uint32_t phi_steps = 6;                        ///< P of the bind-pose muscle grids (>= 2)
    std::span<const glm::vec3> muscle_positions;   ///< bind-pose muscles, muscles x V(T, P), >= 1 muscle
    std::span<const glm::vec3> muscle_normals;     ///< unit normals, same size
    std::span<const glm::vec3> mesh_positions;     ///< bind-pose mesh vertices (finite)
    std::span<SkinBinding> bindings;               ///< output, one per mesh vertex

    /// Checks sizes and finiteness of the mesh; one message per failure (first bad vertex named).
    bool Validate(std::vector<std::string>* errors = nullptr) const;
    /// Finds every vertex's binding. Requires Validate().
    void Run() const;
};

/// Places bound mesh vertices on the current muscles of a run of characters of one type.
/// Muscles may be tessellated at any (T, P); character c uses muscles [c * muscle_count, ...).
struct BoundSkinJob {
    uint32_t theta_steps = 8;                      ///< T of the current muscle grids (>= 3)
    uint32_t phi_steps = 6;                        ///< P of the current muscle grids (>= 2)
    uint32_t muscle_count = 1;                     ///< muscles per character (> every binding's muscle)
    std::span<const glm::vec3> muscle_positions;   ///< characters x muscle_count x V(T, P)
    std::span<const glm::vec3> muscle_normals;     ///< unit normals, same size
    std::span<const SkinBinding> bindings;         ///< per mesh vertex (shared by the characters)
    std::span<glm::vec3> positions;                ///< output, characters x bindings.size()

    /// Checks sizes and binding muscle indices.
    bool Validate(std::vector<std::string>* errors = nullptr) const;
    /// Places every vertex. Requires Validate(). Mesh normals: accumulate_vertex_normals afterwards.
    void Run() const;
};

}  // namespace aloha
