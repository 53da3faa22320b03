// Diffusion of sparse muscle weights over the skin graph (see weight_smoothing.hpp).
#include "systems/geometry/body_skin/weight_smoothing.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <unordered_map>

namespace aloha {
namespace {

// Accumulates (muscle, weight) pairs; keeps the kSparseWeights largest on extraction.
struct Accumulator {
    static constexpr int kCap = 4 * kSparseWeights;
    uint32_t muscle[kCap];
    float weight[kCap];
    int count = 0;
    void add(uint32_t m, float w) {
        for (int k = 0; k < count; ++k)
            if (muscle[k] == m) {
                weight[k] += w;
                return;
            }
        if (count < kCap) {
            muscle[count] = m;
            weight[count++] = w;
            return;
        }
        // Full: replace the smallest when w is larger (only with many far-apart muscles around).
        int lo = 0;
        for (int k = 1; k < count; ++k)
            if (weight[k] < weight[lo]) lo = k;
        if (w > weight[lo]) muscle[lo] = m, weight[lo] = w;
    }
    void extract(SparseWeights& out) {
        int order[kCap];
        for (int k = 0; k < count; ++k) order[k] = k;
        std::sort(order, order + count, [&](int a, int b) { return weight[a] > weight[b] || (weight[a] == weight[b] && muscle[a] < muscle[b]); });
        out = SparseWeights{};
        float sum = 0.0f;
        for (int k = 0; k < std::min(count, kSparseWeights); ++k) {
            out.muscle[k] = muscle[order[k]];
            out.weight[k] = weight[order[k]];
            sum += out.weight[k];
            ++out.count;
        }
        if (sum > 0.0f)
            for (int k = 0; k < out.count; ++k) out.weight[k] /= sum;
    }
};

}  // namespace

VertexGraph build_vertex_graph(std::span<const glm::vec3> positions, std::span<const uint32_t> indices) {
    const size_t n = positions.size();
    // Weld: every vertex -> the first vertex at its exact position.
    std::vector<uint32_t> weld(n);
    struct Hash {
        size_t operator()(const glm::vec3& p) const {
            return std::bit_cast<uint32_t>(p.x) * 73856093u ^ std::bit_cast<uint32_t>(p.y) * 19349663u ^ std::bit_cast<uint32_t>(p.z) * 83492791u;
        }
    };
    std::unordered_map<glm::vec3, uint32_t, Hash> first;
    first.reserve(n);
    for (uint32_t i = 0; i < n; ++i) weld[i] = first.try_emplace(positions[i], i).first->second;
    // Edges between welded representatives, both directions, deduplicated.
    std::vector<std::pair<uint32_t, uint32_t>> edges;
    edges.reserve(indices.size() * 2);
    for (size_t f = 0; f + 2 < indices.size(); f += 3)
        for (int k = 0; k < 3; ++k) {
            const uint32_t a = weld[indices[f + k]], b = weld[indices[f + (k + 1) % 3]];
            if (a == b) continue;
            edges.emplace_back(a, b);
            edges.emplace_back(b, a);
        }
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    VertexGraph g;
    double length = 0.0;
    for (const auto& [a, b] : edges) length += glm::length(positions[a] - positions[b]);
    g.mean_edge = edges.empty() ? 0.0f : static_cast<float>(length / static_cast<double>(edges.size()));
    // Rows of the representatives, then every welded vertex shares its representative's row.
    std::vector<uint32_t> start(n + 1, 0);
    for (const auto& e : edges) ++start[e.first + 1];
    for (size_t i = 0; i < n; ++i) start[i + 1] += start[i];
    g.offsets.assign(n + 1, 0);
    for (size_t i = 0; i < n; ++i) g.offsets[i + 1] = g.offsets[i] + (start[weld[i] + 1] - start[weld[i]]);
    g.neighbours.resize(g.offsets[n]);
    for (size_t i = 0; i < n; ++i)
        for (uint32_t k = start[weld[i]]; k < start[weld[i] + 1]; ++k) g.neighbours[g.offsets[i] + (k - start[weld[i]])] = edges[k].second;
    return g;
}

int smoothing_rounds(float radius, float mean_edge, int max_rounds) {
    if (!(radius > 0.0f) || !(mean_edge > 0.0f)) return 0;
    const float r = radius / mean_edge;
    return std::min(max_rounds, static_cast<int>(std::ceil(4.0f * r * r)));
}

void smooth_weights(const VertexGraph& graph, int rounds, std::span<SparseWeights> weights) {
    std::vector<SparseWeights> next(weights.size());
    for (int round = 0; round < rounds; ++round) {
        for (size_t i = 0; i < weights.size(); ++i) {
            const uint32_t begin = graph.offsets[i], end = graph.offsets[i + 1];
            Accumulator acc;
            const SparseWeights& own = weights[i];
            const float self = end > begin ? 0.5f : 1.0f;
            for (int k = 0; k < own.count; ++k) acc.add(own.muscle[k], self * own.weight[k]);
            const float share = end > begin ? 0.5f / static_cast<float>(end - begin) : 0.0f;
            for (uint32_t e = begin; e < end; ++e) {
                const SparseWeights& w = weights[graph.neighbours[e]];
                for (int k = 0; k < w.count; ++k) acc.add(w.muscle[k], share * w.weight[k]);
            }
            acc.extract(next[i]);
        }
        std::copy(next.begin(), next.end(), weights.begin());
    }
}

}  // namespace aloha
