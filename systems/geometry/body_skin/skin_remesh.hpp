// Turning the dense polygonised body surface into a skin of a given resolution: manifold-preserving
// edge-collapse simplification (edge_collapse.hpp), tangential relaxation with projection back onto the field's zero
// set (even triangles without losing the shape), and the topology checks the skin must pass (one
// component, every edge in exactly two triangles).
#pragma once

#include "systems/geometry/body_skin/skin_field.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace aloha {

/// Topology of a triangle list: connected components (over shared edges) and edges that are not
/// shared by exactly two triangles.
struct SurfaceTopology {
    uint32_t components = 0;          ///< connected components of the used vertices
    uint32_t boundary_edges = 0;      ///< edges in one triangle
    uint32_t non_manifold_edges = 0;  ///< edges in three or more triangles
    uint32_t degenerate_triangles = 0;///< triangles repeating a vertex
    /// One connected closed 2-manifold: one component, every edge in exactly two triangles.
    [[nodiscard]] bool closed_connected() const {
        return components == 1 && boundary_edges == 0 && non_manifold_edges == 0 && degenerate_triangles == 0;
    }
};

/// Counts components and edge valences of `indices` (triangles over `vertex_count` vertices).
[[nodiscard]] SurfaceTopology analyse_surface(std::span<const uint32_t> indices, size_t vertex_count);

/// Simplifies `dense` (a closed 2-manifold) to about `target_triangles` triangles (collapse_edges: the
/// result stays a closed manifold of the same topology), drops unused vertices, then relaxes: `iterations` rounds of moving every vertex half way to the
/// mean of its neighbours within the tangent plane, each followed by Newton projection onto the
/// zero set of `field`; finally orders the triangles for the vertex cache (meshopt_optimizeVertexCache)
/// and the vertices by first use. The result keeps the input's orientation.
[[nodiscard]] TriangleSurface simplify_and_relax(const TriangleSurface& dense, const SampledField& field,
                                                 uint32_t target_triangles, int iterations = 4);

/// simplify_and_relax() to several targets with one collapse pass (collapse_edges_progressive):
/// element i equals simplify_and_relax(dense, field, target_triangles[i], iterations).
[[nodiscard]] std::vector<TriangleSurface> simplify_and_relax_all(const TriangleSurface& dense, const SampledField& field,
                                                                  std::span<const uint32_t> target_triangles, int iterations = 4);

/// The relaxation half of simplify_and_relax(): `collapsed` (collapse_edges' output, unused vertex
/// slots allowed) compacted, relaxed onto `field` and put in vertex-cache order.
[[nodiscard]] TriangleSurface relax_collapsed(const TriangleSurface& collapsed, const SampledField& field, int iterations = 4);

}  // namespace aloha
