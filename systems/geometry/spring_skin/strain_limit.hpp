// Strain limiting of the skin (Provot 1995, "Deformation constraints in a mass-spring model to
// describe rigid cloth behavior"): skin stretches and compresses only so far. After the skin is placed
// (spring ends or linear-blend skinning), every edge whose length left [lo, hi] x its bind length is
// projected back to the nearest limit, both ends moved half the error along the edge, Gauss-Seidel,
// until a pass starts with every edge within the accepted bounds (a little wider than the limits) or
// the passes are spent. The first pass measures every edge (squared lengths, no square root), so a
// frame with nothing to fix costs one pass; later passes revisit only the edges at a vertex the pass
// before moved (no other edge's length can have changed), so the folds cost passes, not the surface.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace aloha {

/// The unique edges of a triangle list and their bind lengths, built once per skin surface.
/// Vertices that share a bind position (an authored mesh's seams: one point, several normals or
/// texture coordinates) are welded: edges join the first of them, and the others follow it after
/// every projection, so limiting never opens a seam.
struct SkinEdges {
    std::vector<uint32_t> ends;    ///< edge e joins ends[2e] and ends[2e + 1] (welded vertices)
    std::vector<float> rest;       ///< bind length of edge e (> 0; zero-length edges are left out)
    std::vector<uint32_t> copies;  ///< pairs (vertex, the welded vertex whose position it takes)
    std::vector<uint32_t> vertex_first;  ///< edges at vertex v: vertex_edges[vertex_first[v], vertex_first[v + 1])
    std::vector<uint32_t> vertex_edges;  ///< (size: vertices + 1 and 2 x edges)
};

/// The unique edges of `indices` (triangles) with their lengths on `bind`, vertices at one bind
/// position welded. Requires indices < bind.size().
[[nodiscard]] SkinEdges build_skin_edges(std::span<const uint32_t> indices, std::span<const glm::vec3> bind);

/// Limits on edge length relative to the bind length.
struct StrainLimits {
    float lo = 0.55f;         ///< edges shorter than lo x bind length are projected (0 < lo <= 1)
    float hi = 1.8f;          ///< edges longer than hi x bind length are projected (hi >= 1)
    uint32_t iterations = 8;  ///< most passes over the edges (0: the job does nothing)
    float accept_lo = 0.5f;   ///< passes stop once every edge is within [accept_lo, accept_hi] (<= lo)
    float accept_hi = 2.0f;   ///< (>= hi)
};

/// The skin's limits in the geometric controller: the issue-14 bounds of a torn or collapsed skin edge
/// are [0.5, 2] x bind length, accepted; projecting to [0.55, 1.8] leaves room for what the last pass
/// leaves unsettled and for Catmull-Clark refinement (whose edges are averages of the control edges).
inline constexpr StrainLimits kSkinStrain{0.55f, 1.8f, 8, 0.5f, 2.0f};

/// What a StrainLimitJob did.
struct StrainLimitResult {
    uint32_t projected = 0;  ///< edge projections made, over every pass
    uint32_t outside = 0;    ///< edges outside the accepted bounds when the passes were spent (0: converged)
};

/// Projects the edges of one surface's `positions` back into the limits.
struct StrainLimitJob {
    const SkinEdges* edges = nullptr;    ///< the surface's edges (indices < positions.size())
    StrainLimits limits;                 ///< limits and pass count
    std::span<glm::vec3> positions;      ///< in/out: the surface's vertices

    /// Checks the edges, the limits and the sizes; appends one message per failure to `errors` when given.
    bool Validate(std::vector<std::string>* errors = nullptr) const;
    /// Projects. Requires Validate().
    StrainLimitResult Run() const;
};

/// Passes over a refined (Catmull-Clark) surface: four times the edges of its control surface, whose
/// folds need more Gauss-Seidel passes to settle (measured on the humanoid's walk: 8 left 18 edges
/// of 10.4 million samples up to 2.07x; 16 left 10 of 10.6 million up to 2.018x once the layout had its
/// 54th muscle, 24 none, up to 1.971x). Passes stop once every edge is accepted, so the frames that
/// settle sooner do not pay for them.
inline constexpr uint32_t kRefinedStrainIterations = 24;

/// Runs a StrainLimitJob with kSkinStrain's limits and `iterations` passes over `positions` when
/// `edges` has any; true when anything moved (normals computed with the positions are then stale).
/// Requires edge ends < positions.size().
bool limit_skin_strain(const SkinEdges& edges, std::span<glm::vec3> positions, uint32_t iterations = kSkinStrain.iterations);

}  // namespace aloha
