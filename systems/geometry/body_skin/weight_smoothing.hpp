// Smoothing per-vertex muscle weights over a skin's surface graph, so that neighbouring skin vertices
// hang on nearly the same muscles with nearly the same weights: a band of several edges, not one
// edge, takes up the relative motion of two body parts (the arm against the torso, the thigh against
// the buttock), which keeps every edge's stretch bounded.
//
// Diffusion: each round replaces a vertex's weights by the mean of its own and its neighbours' mean,
//     w_i <- (w_i + mean_{j in N(i)} w_j) / 2,
// an explicit heat-equation step; on a regular mesh of edge length e it adds e^2 / 4 to the variance
// of a point spread, so n rounds spread a weight by sigma = e sqrt(n) / 2 (smoothing_rounds()).
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace aloha {

/// Muscle weights kept per vertex while smoothing.
inline constexpr int kSparseWeights = 8;

/// Up to kSparseWeights (muscle, weight) pairs of one vertex, largest first, weights summing to 1.
struct SparseWeights {
    uint32_t muscle[kSparseWeights] = {};  ///< muscle indices
    float weight[kSparseWeights] = {};     ///< weights (0 past count)
    int count = 0;                         ///< pairs in use
};

/// Vertex adjacency of a triangle list in compressed rows; vertices at exactly the same position
/// (an authored mesh split at UV or material seams) share their neighbours, so smoothing crosses seams.
struct VertexGraph {
    std::vector<uint32_t> offsets;     ///< neighbours of i: neighbours[offsets[i] .. offsets[i + 1])
    std::vector<uint32_t> neighbours;  ///< vertex indices
    float mean_edge = 0.0f;            ///< mean length of the distinct edges (m)
};

/// The graph of `indices` (triangles) over `positions`, coincident vertices welded.
[[nodiscard]] VertexGraph build_vertex_graph(std::span<const glm::vec3> positions, std::span<const uint32_t> indices);

/// Rounds of smooth_weights() that spread a weight by `radius` (m) on a mesh of mean edge length
/// `mean_edge`: ceil(4 radius^2 / mean_edge^2), at most `max_rounds`; 0 when radius <= 0.
[[nodiscard]] int smoothing_rounds(float radius, float mean_edge, int max_rounds = 400);

/// `rounds` diffusion rounds of `weights` over `graph` (one entry per graph vertex); each vertex keeps
/// its kSparseWeights largest weights, renormalised. Deterministic (no threads).
void smooth_weights(const VertexGraph& graph, int rounds, std::span<SparseWeights> weights);

}  // namespace aloha
