// OpenSubdiv top level: Catmull-Clark refinement of the grid-layout skin. The refinement topology
// and its stencil table depend only on (T, P, muscle count, level), so they are built ONCE per key
// in a SubdivisionCache (Far::TopologyRefiner + Far::StencilTableFactory) and flattened into
// plain arrays; SubdivideJob then evaluates the stencils on the skin positions every frame and
// recomputes area-weighted normals from the refined faces (kept as a triangle index buffer).
#pragma once

#include "systems/geometry/surface_grid.hpp"

#include <glm/glm.hpp>

#include <compare>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <span>
#include <string>
#include <vector>

namespace aloha {

/// What a refinement depends on: the grid tessellation, the number of muscle grids and the level.
struct SubdivisionKey {
    uint32_t theta_steps = 8;   ///< T >= 3
    uint32_t phi_steps = 6;     ///< P >= 2
    uint32_t muscle_count = 1;  ///< grids concatenated per character (>= 1)
    uint32_t level = 1;         ///< uniform Catmull-Clark levels, 0 (identity) to 4
    /// Keys order lexicographically (for the cache map).
    auto operator<=>(const SubdivisionKey&) const = default;
};

/// A refinement flattened for evaluation: refined vertex i = sum over k in
/// [offsets[i], offsets[i+1]) of weights[k] * control[indices[k]].
struct SubdivisionTopology {
    uint32_t control_vertex_count = 0;  ///< vertices of the control mesh (per character)
    uint32_t refined_vertex_count = 0;  ///< vertices of the finest level (per character)
    uint32_t refined_face_count = 0;    ///< faces (quads for level >= 1) of the finest level
    std::vector<uint32_t> offsets;      ///< refined_vertex_count + 1 stencil starts
    std::vector<uint32_t> indices;      ///< control vertex per stencil entry
    std::vector<float> weights;         ///< weight per stencil entry
    std::vector<uint32_t> triangles;    ///< refined faces split into counter-clockwise triangles
};

/// Builds a refinement of an arbitrary closed or open polygon mesh with OpenSubdiv (Catmull-Clark,
/// edge-and-corner boundary). Requires faces to index [0, vertex_count), level <= 4.
std::unique_ptr<SubdivisionTopology> build_subdivision(const GridFaces& faces, uint32_t vertex_count, uint32_t level);

/// Thread-safe cache of refinements per SubdivisionKey; entries never move once built.
class SubdivisionCache {
public:
    /// The refinement for `key`, built on first use (append_grid_faces for every muscle, then
    /// OpenSubdiv). Requires T >= 3, P >= 2, muscle_count >= 1, level <= 4.
    const SubdivisionTopology& get(const SubdivisionKey& key);
    /// Number of refinements built so far (a lookup of a cached key builds nothing).
    [[nodiscard]] size_t build_count() const;

private:
    mutable std::mutex mutex_;
    std::map<SubdivisionKey, std::unique_ptr<SubdivisionTopology>> entries_;
    size_t builds_ = 0;
};

/// Evaluates a refinement on a contiguous run of characters that share it: control positions are
/// characters x control_vertex_count, outputs characters x refined_vertex_count.
struct SubdivideJob {
    const SubdivisionTopology* topology = nullptr;  ///< from SubdivisionCache::get
    std::span<const glm::vec3> control_positions;   ///< skin vertices (grid layout)
    std::span<glm::vec3> refined_positions;         ///< output refined vertices
    std::span<glm::vec3> refined_normals;           ///< output unit normals (empty = skip normals)

    /// Checks the topology pointer and span sizes; one message per failure.
    bool Validate(std::vector<std::string>* errors = nullptr) const;
    /// Evaluates stencils (and normals). Requires Validate().
    void Run() const;
};

}  // namespace aloha
