#include "systems/geometry/spring_skin/strain_limit.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>

namespace aloha {

namespace {

// weld[v]: the first vertex at v's bind position (bitwise equal coordinates).
std::vector<uint32_t> weld_map(std::span<const glm::vec3> bind) {
    std::vector<uint32_t> order(bind.size()), weld(bind.size());
    for (uint32_t v = 0; v < order.size(); ++v) order[v] = v;
    auto key = [&](uint32_t v) { return std::array<float, 3>{bind[v].x, bind[v].y, bind[v].z}; };
    std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return key(a) < key(b); });
    for (size_t i = 0; i < order.size(); ++i)
        weld[order[i]] = i > 0 && key(order[i]) == key(order[i - 1]) ? weld[order[i - 1]] : order[i];
    return weld;
}

}  // namespace

SkinEdges build_skin_edges(std::span<const uint32_t> indices, std::span<const glm::vec3> bind) {
    const std::vector<uint32_t> weld = weld_map(bind);
    std::vector<uint64_t> keys;
    keys.reserve(indices.size());
    for (size_t f = 0; f + 2 < indices.size(); f += 3)
        for (int k = 0; k < 3; ++k) {
            const uint32_t a = weld[indices[f + k]], b = weld[indices[f + (k + 1) % 3]];
            if (a == b) continue;
            keys.push_back((uint64_t{std::min(a, b)} << 32) | std::max(a, b));
        }
    std::sort(keys.begin(), keys.end());
    keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
    SkinEdges out;
    for (uint32_t v = 0; v < weld.size(); ++v)
        if (weld[v] != v) out.copies.push_back(v), out.copies.push_back(weld[v]);
    out.ends.reserve(2 * keys.size());
    out.rest.reserve(keys.size());
    for (uint64_t key : keys) {
        const auto a = static_cast<uint32_t>(key >> 32), b = static_cast<uint32_t>(key);
        const float rest = glm::length(bind[a] - bind[b]);
        if (!(rest > 0.0f)) continue;
        out.ends.push_back(a);
        out.ends.push_back(b);
        out.rest.push_back(rest);
    }
    out.vertex_first.assign(bind.size() + 1, 0);
    for (uint32_t v : out.ends) ++out.vertex_first[v + 1];
    for (size_t v = 0; v < bind.size(); ++v) out.vertex_first[v + 1] += out.vertex_first[v];
    out.vertex_edges.resize(out.ends.size());
    std::vector<uint32_t> fill(out.vertex_first.begin(), out.vertex_first.end() - 1);
    for (size_t k = 0; k < out.ends.size(); ++k) out.vertex_edges[fill[out.ends[k]]++] = static_cast<uint32_t>(k / 2);
    return out;
}

bool StrainLimitJob::Validate(std::vector<std::string>* errors) const {
    bool ok = true;
    auto fail = [&](const std::string& m) {
        ok = false;
        if (errors) errors->push_back("StrainLimitJob: " + m);
    };
    if (!edges) {
        fail("no edges");
    } else {
        if (edges->ends.size() != 2 * edges->rest.size()) fail("edge ends and rest lengths differ in count");
        for (uint32_t v : edges->ends)
            if (v >= positions.size()) {
                fail("an edge end is outside the positions");
                break;
            }
        if (edges->copies.size() % 2 != 0) fail("welded copies are not pairs");
        if (edges->vertex_first.size() != positions.size() + 1 || edges->vertex_edges.size() != edges->ends.size())
            fail("the edges' vertex adjacency is for another surface");
        for (uint32_t v : edges->copies)
            if (v >= positions.size()) {
                fail("a welded vertex is outside the positions");
                break;
            }
    }
    if (!(limits.lo > 0.0f && limits.lo <= 1.0f)) fail("lo must be in (0, 1]");
    if (!(limits.hi >= 1.0f)) fail("hi must be at least 1");
    if (!(limits.accept_lo > 0.0f && limits.accept_lo <= limits.lo && limits.accept_hi >= limits.hi))
        fail("accepted bounds must hold [lo, hi] and accept_lo must be positive");
    return ok;
}

namespace {

// Per-thread scratch of the passes after the first: generation stamps of the vertices moved and of
// the edges queued in the current pass, and the lists themselves.
struct PassScratch {
    std::vector<uint32_t> vertex_stamp, edge_stamp, moved, queued;
    uint32_t generation = 0;
    // A new generation (stamps from earlier ones mean nothing), sized for `vertices` and `edges`.
    uint32_t next(size_t vertices, size_t edges) {
        if (vertex_stamp.size() < vertices) vertex_stamp.resize(vertices, 0);
        if (edge_stamp.size() < edges) edge_stamp.resize(edges, 0);
        if (++generation == 0) {
            std::fill(vertex_stamp.begin(), vertex_stamp.end(), 0u);
            std::fill(edge_stamp.begin(), edge_stamp.end(), 0u);
            generation = 1;
        }
        return generation;
    }
};

// Measures edge e (clears `accepted` when it is outside [accept_lo, accept_hi] x its rest length) and
// projects it back inside [lo, hi] when outside; true when its ends moved.
inline bool limit_edge(glm::vec3* p, const uint32_t* ends, const float* rest, size_t e, const StrainLimits& l,
                       bool& accepted) {
    glm::vec3& a = p[ends[2 * e]];
    glm::vec3& b = p[ends[2 * e + 1]];
    const glm::vec3 d = b - a;
    const float len2 = glm::dot(d, d), rest2 = rest[e] * rest[e];
    if (len2 < l.accept_lo * l.accept_lo * rest2 || len2 > l.accept_hi * l.accept_hi * rest2) accepted = false;
    if (len2 >= l.lo * l.lo * rest2 && len2 <= l.hi * l.hi * rest2) return false;
    const float len = std::sqrt(len2);
    if (!(len > 1e-12f * rest[e])) return false;  // collapsed to a point: no direction to push along
    // To just inside the limit (1e-4 of it), so float rounding does not leave it a hair outside.
    const float goal = (len2 < l.lo * l.lo * rest2 ? l.lo * (1.0f + 1e-4f) : l.hi * (1.0f - 1e-4f)) * rest[e];
    const glm::vec3 move = (0.5f * (len - goal) / len) * d;
    a += move;
    b -= move;
    return true;
}

}  // namespace

StrainLimitResult StrainLimitJob::Run() const {
    const uint32_t* ends = edges->ends.data();
    const float* rest = edges->rest.data();
    const size_t count = edges->rest.size(), vertices = positions.size();
    glm::vec3* p = positions.data();
    StrainLimitResult result;
    if (limits.iterations == 0 || count == 0) return result;
    thread_local PassScratch scratch;
    PassScratch& s = scratch;
    // Moves of a pass: both ends of edge e, each recorded once per generation.
    auto note_moved = [&](size_t e, uint32_t gen) {
        ++result.projected;
        for (int k = 0; k < 2; ++k) {
            const uint32_t v = ends[2 * e + k];
            if (s.vertex_stamp[v] != gen) s.vertex_stamp[v] = gen, s.moved.push_back(v);
        }
    };
    // Pass 1: every edge.
    uint32_t gen = s.next(vertices, count);
    s.moved.clear();
    bool accepted = true;
    for (size_t e = 0; e < count; ++e)
        if (limit_edge(p, ends, rest, e, limits, accepted)) note_moved(e, gen);
    // Later passes: the edges at the vertices the pass before moved; stop once a pass finds every one
    // of them accepted (the others have not changed since they were accepted).
    for (uint32_t pass = 1; pass < limits.iterations && !accepted && !s.moved.empty(); ++pass) {
        gen = s.next(vertices, count);
        s.queued.clear();
        for (uint32_t v : s.moved)
            for (uint32_t k = edges->vertex_first[v]; k < edges->vertex_first[v + 1]; ++k) {
                const uint32_t e = edges->vertex_edges[k];
                if (s.edge_stamp[e] != gen) s.edge_stamp[e] = gen, s.queued.push_back(e);
            }
        s.moved.clear();
        accepted = true;
        for (uint32_t e : s.queued)
            if (limit_edge(p, ends, rest, e, limits, accepted)) note_moved(e, gen);
    }
    // Seams follow their welded vertex (only where something moved: otherwise the surface is as placed).
    for (size_t k = 0; result.projected > 0 && k < edges->copies.size(); k += 2) p[edges->copies[k]] = p[edges->copies[k + 1]];
    if (accepted) return result;
    // Passes spent: count what is left outside the accepted bounds.
    const float accept_lo2 = limits.accept_lo * limits.accept_lo, accept_hi2 = limits.accept_hi * limits.accept_hi;
    for (size_t e = 0; e < count; ++e) {
        const glm::vec3 d = p[ends[2 * e + 1]] - p[ends[2 * e]];
        const float len2 = glm::dot(d, d), rest2 = rest[e] * rest[e];
        result.outside += len2 < accept_lo2 * rest2 || len2 > accept_hi2 * rest2;
    }
    return result;
}

bool limit_skin_strain(const SkinEdges& edges, std::span<glm::vec3> positions, uint32_t iterations) {
    if (edges.rest.empty()) return false;
    StrainLimits limits = kSkinStrain;
    limits.iterations = iterations;
    const StrainLimitJob job{&edges, limits, positions};
    assert(job.Validate());
    return job.Run().projected > 0;
}

}  // namespace aloha
