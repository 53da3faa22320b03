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

// Projects edge e back inside [lo, hi] x its rest length if it is outside; true when it was outside.
inline bool project_edge(glm::vec3* p, const uint32_t* ends, const float* rest, size_t e, float lo, float hi,
                         uint32_t& projected) {
    glm::vec3& a = p[ends[2 * e]];
    glm::vec3& b = p[ends[2 * e + 1]];
    const glm::vec3 d = b - a;
    const float len2 = glm::dot(d, d), rest2 = rest[e] * rest[e];
    if (len2 >= lo * lo * rest2 && len2 <= hi * hi * rest2) return false;
    const float len = std::sqrt(len2);
    if (!(len > 1e-12f * rest[e])) return true;  // collapsed to a point: no direction to push along
    // To just inside the limit (1e-4 of it), so float rounding does not leave it a hair outside.
    const float goal = (len2 < lo * lo * rest2 ? lo * (1.0f + 1e-4f) : hi * (1.0f - 1e-4f)) * rest[e];
    const glm::vec3 move = (0.5f * (len - goal) / len) * d;
    a += move;
    b -= move;
    ++projected;
    return true;
}

}  // namespace

StrainLimitResult StrainLimitJob::Run() const {
    // Full Gauss-Seidel passes, each projecting every edge outside [lo, hi], until a pass finds every
    // edge within the accepted bounds [accept_lo, accept_hi] (wider than [lo, hi]: the projections
    // aim inside by that margin, so a pass that starts within the accepted bounds ends near them) or
    // the passes are spent.
    const uint32_t* ends = edges->ends.data();
    const float* rest = edges->rest.data();
    const size_t count = edges->rest.size();
    const float lo = limits.lo, hi = limits.hi;
    const float accept_lo2 = limits.accept_lo * limits.accept_lo, accept_hi2 = limits.accept_hi * limits.accept_hi;
    glm::vec3* p = positions.data();
    StrainLimitResult result;
    bool unaccepted = true;
    for (uint32_t pass = 0; pass < limits.iterations && unaccepted; ++pass) {
        unaccepted = false;
        uint32_t projected = 0;
        for (size_t e = 0; e < count; ++e) {
            const glm::vec3 d = p[ends[2 * e + 1]] - p[ends[2 * e]];
            const float len2 = glm::dot(d, d), rest2 = rest[e] * rest[e];
            unaccepted |= len2 < accept_lo2 * rest2 || len2 > accept_hi2 * rest2;
            project_edge(p, ends, rest, e, lo, hi, projected);
        }
        result.projected += projected;
        if (projected == 0) unaccepted = false;
    }
    // Seams follow their welded vertex (only where something moved: otherwise the surface is as placed).
    for (size_t k = 0; result.projected > 0 && k < edges->copies.size(); k += 2) p[edges->copies[k]] = p[edges->copies[k + 1]];
    if (!unaccepted) return result;
    // Passes spent: count what is left outside the accepted bounds.
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
