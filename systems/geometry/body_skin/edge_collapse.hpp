// Quadric-error edge-collapse simplification that keeps a closed 2-manifold closed and manifold.
//
// meshoptimizer 0.18 (the Debian package) collapses edges without the link condition, so a collapse
// can glue two sheets of the surface along an edge (an edge then lies in four triangles); the skin must
// be one closed manifold at every level, so the collapses are done here with the checks it needs:
//  - link condition (Dey, Edelsbrunner et al. 1999): collapsing edge uv of a closed 2-manifold keeps it a
//    2-manifold of the same topology iff the vertices adjacent to both u and v are exactly the two
//    vertices opposite uv;
//  - no triangle around u or v turns over (its normal keeps a positive dot product with the old one)
//    or degenerates to a sliver (minimum angle kept above ~2 degrees);
//  - cost: Garland-Heckbert quadric error of the merged vertex placed at u, v or the midpoint, whichever
//    is lowest (the skin is relaxed and projected onto the body field afterwards, skin_remesh.hpp).
#pragma once

#include "systems/geometry/body_skin/skin_field.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace aloha {

/// Collapses edges of `mesh` (a closed 2-manifold, counter-clockwise triangles) cheapest first until at
/// most `target_triangles` triangles remain or no edge may be collapsed. The result keeps every input
/// vertex slot (collapsed ones unused, kept ones possibly moved), the input's orientation and topology.
[[nodiscard]] TriangleSurface collapse_edges(const TriangleSurface& mesh, uint32_t target_triangles);

/// collapse_edges() to several targets in one pass over the collapse order (cost of the smallest
/// target alone): element i equals collapse_edges(mesh, target_triangles[i]), bit for bit, whatever the
/// order of the targets.
[[nodiscard]] std::vector<TriangleSurface> collapse_edges_progressive(const TriangleSurface& mesh,
                                                                      std::span<const uint32_t> target_triangles);

}  // namespace aloha
