// Skin simplification (edge_collapse.hpp), relaxation, vertex-cache order and topology checks (see skin_remesh.hpp).
#include "systems/geometry/body_skin/skin_remesh.hpp"

#include "systems/geometry/body_skin/edge_collapse.hpp"

#include <meshoptimizer.h>

#include <algorithm>
#include <numeric>
#include <unordered_map>

namespace aloha {
namespace {

uint64_t edge_key(uint32_t a, uint32_t b) { return a < b ? (uint64_t{a} << 32 | b) : (uint64_t{b} << 32 | a); }

uint32_t find_root(std::vector<uint32_t>& parent, uint32_t v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
}

// Keeps only referenced vertices (in first-use order) and renumbers the indices.
TriangleSurface compact(std::span<const glm::vec3> positions, std::span<const uint32_t> indices) {
    TriangleSurface out;
    std::vector<uint32_t> remap(positions.size(), UINT32_MAX);
    out.indices.reserve(indices.size());
    for (const uint32_t i : indices) {
        if (remap[i] == UINT32_MAX) {
            remap[i] = static_cast<uint32_t>(out.positions.size());
            out.positions.push_back(positions[i]);
        }
        out.indices.push_back(remap[i]);
    }
    return out;
}

}  // namespace

SurfaceTopology analyse_surface(std::span<const uint32_t> indices, size_t vertex_count) {
    SurfaceTopology t;
    std::unordered_map<uint64_t, uint32_t> edges;
    std::vector<uint32_t> parent(vertex_count);
    std::iota(parent.begin(), parent.end(), 0u);
    std::vector<uint8_t> used(vertex_count, 0);
    for (size_t f = 0; f + 2 < indices.size(); f += 3) {
        const uint32_t v[3] = {indices[f], indices[f + 1], indices[f + 2]};
        if (v[0] == v[1] || v[1] == v[2] || v[0] == v[2]) ++t.degenerate_triangles;
        for (int k = 0; k < 3; ++k) {
            used[v[k]] = 1;
            ++edges[edge_key(v[k], v[(k + 1) % 3])];
            parent[find_root(parent, v[k])] = find_root(parent, v[(k + 1) % 3]);
        }
    }
    for (const auto& [key, count] : edges) {
        if (count == 1) ++t.boundary_edges;
        if (count > 2) ++t.non_manifold_edges;
    }
    for (uint32_t v = 0; v < vertex_count; ++v)
        if (used[v] && find_root(parent, v) == v) ++t.components;
    return t;
}

TriangleSurface simplify_and_relax(const TriangleSurface& dense, const SampledField& field, uint32_t target_triangles,
                                   int iterations) {
    return relax_collapsed(collapse_edges(dense, target_triangles), field, iterations);
}

std::vector<TriangleSurface> simplify_and_relax_all(const TriangleSurface& dense, const SampledField& field,
                                                    std::span<const uint32_t> target_triangles, int iterations) {
    std::vector<TriangleSurface> out = collapse_edges_progressive(dense, target_triangles);
    for (TriangleSurface& s : out) s = relax_collapsed(s, field, iterations);
    return out;
}

TriangleSurface relax_collapsed(const TriangleSurface& collapsed, const SampledField& field, int iterations) {
    TriangleSurface out = compact(collapsed.positions, collapsed.indices);
    // Neighbours of every vertex (each undirected edge once per direction).
    const size_t n = out.positions.size();
    std::vector<std::vector<uint32_t>> ring(n);
    for (size_t f = 0; f < out.indices.size(); f += 3)
        for (int k = 0; k < 3; ++k) {
            const uint32_t a = out.indices[f + k], b = out.indices[f + (k + 1) % 3];
            ring[a].push_back(b);
            ring[b].push_back(a);
        }
    for (auto& r : ring) {
        std::sort(r.begin(), r.end());
        r.erase(std::unique(r.begin(), r.end()), r.end());
    }
    std::vector<glm::vec3> next(n);
    for (int it = 0; it < iterations; ++it) {
        for (size_t v = 0; v < n; ++v) {
            const glm::vec3 p = out.positions[v];
            if (ring[v].empty()) {
                next[v] = p;
                continue;
            }
            glm::vec3 mean(0.0f);
            for (const uint32_t u : ring[v]) mean += out.positions[u];
            mean /= static_cast<float>(ring[v].size());
            const glm::vec3 g = field.gradient(p);
            const float gl = glm::length(g);
            glm::vec3 step = 0.5f * (mean - p);
            if (gl > 1e-6f) step -= glm::dot(step, g / gl) * (g / gl);  // tangential only
            next[v] = p + step;
        }
        for (size_t v = 0; v < n; ++v) {
            glm::vec3 p = next[v];
            for (int k = 0; k < 3; ++k) {  // Newton steps towards f = 0 along the gradient
                const glm::vec3 g = field.gradient(p);
                const float g2 = glm::dot(g, g);
                if (g2 < 1e-8f) break;
                glm::vec3 delta = field.sample(p) * g / g2;
                const float len = glm::length(delta);
                if (len > field.cell) delta *= field.cell / len;  // flat field: no long jumps
                p -= delta;
            }
            out.positions[v] = p;
        }
    }
    // Triangle order for the post-transform vertex cache, vertices in first-use order.
    std::vector<uint32_t> ordered(out.indices.size());
    meshopt_optimizeVertexCache(ordered.data(), out.indices.data(), out.indices.size(), out.positions.size());
    return compact(out.positions, ordered);
}

}  // namespace aloha
