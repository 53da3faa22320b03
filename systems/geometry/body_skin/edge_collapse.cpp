// Manifold-preserving quadric edge collapse (see edge_collapse.hpp).
#include "systems/geometry/body_skin/edge_collapse.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <queue>
#include <vector>

namespace aloha {
namespace {

// Symmetric 4x4 quadric sum of squared plane distances, upper triangle row by row.
struct Quadric {
    std::array<double, 10> q{};
    void add_plane(glm::dvec3 n, double d, double w) {
        const double a = n.x, b = n.y, c = n.z;
        const double v[10] = {a * a, a * b, a * c, a * d, b * b, b * c, b * d, c * c, c * d, d * d};
        for (int i = 0; i < 10; ++i) q[static_cast<size_t>(i)] += w * v[i];
    }
    Quadric& operator+=(const Quadric& o) {
        for (size_t i = 0; i < 10; ++i) q[i] += o.q[i];
        return *this;
    }
    [[nodiscard]] double error(glm::dvec3 p) const {
        const double x = p.x, y = p.y, z = p.z;
        return q[0] * x * x + 2 * q[1] * x * y + 2 * q[2] * x * z + 2 * q[3] * x + q[4] * y * y + 2 * q[5] * y * z +
               2 * q[6] * y + q[7] * z * z + 2 * q[8] * z + q[9];
    }
};

// Smallest sine of the three corner angles of triangle t with (unnormalised) normal n.
float min_sine(const glm::vec3 t[3], glm::vec3 n) {
    const float area2 = glm::length(n);
    float lo = 1.0f;
    for (int k = 0; k < 3; ++k) {
        const float l = glm::length(t[(k + 1) % 3] - t[k]) * glm::length(t[(k + 2) % 3] - t[k]);
        lo = std::min(lo, l > 0.0f ? area2 / l : 0.0f);
    }
    return lo;
}

// A queued collapse, 24 bytes (the heap's cache misses are most of the time): valid while neither
// vertex changed since it was pushed; the placement is recomputed from the unchanged positions.
struct Candidate {
    double cost;
    uint32_t u, v;        // collapse u into v
    uint32_t serial;      // push order; stale when u or v changed after it
    uint32_t midpoint;    // 1: place at the midpoint of u and v, 0: at v
    bool operator>(const Candidate& o) const { return cost > o.cost; }
};

class Collapser {
public:
    explicit Collapser(const TriangleSurface& mesh) : pos_(mesh.positions) {
        const size_t nf = mesh.indices.size() / 3, nv = pos_.size();
        faces_.resize(nf);
        alive_.assign(nf, 1);
        vf_.resize(nv);
        quadric_.resize(nv);
        changed_.assign(nv, 0);
        for (size_t f = 0; f < nf; ++f) {
            faces_[f] = {mesh.indices[3 * f], mesh.indices[3 * f + 1], mesh.indices[3 * f + 2]};
            const glm::dvec3 a(pos_[faces_[f][0]]), b(pos_[faces_[f][1]]), c(pos_[faces_[f][2]]);
            glm::dvec3 n = glm::cross(b - a, c - a);
            const double area2 = glm::length(n);
            if (area2 > 0.0) n /= area2;
            Quadric q;
            q.add_plane(n, -glm::dot(n, a), 0.5 * area2);
            for (const uint32_t v : faces_[f]) {
                vf_[v].push_back(static_cast<uint32_t>(f));
                quadric_[v] += q;
            }
        }
        live_faces_ = nf;
        for (size_t f = 0; f < nf; ++f)
            for (int k = 0; k < 3; ++k) {
                const uint32_t a = faces_[f][static_cast<size_t>(k)], b = faces_[f][static_cast<size_t>((k + 1) % 3)];
                if (a < b) push_edge(a, b);  // each interior edge once (its other triangle has b -> a)
            }
    }

    void run(size_t target) {
        while (live_faces_ > target && !heap_.empty()) {
            const Candidate c = heap_.top();
            heap_.pop();
            if (changed_[c.u] >= c.serial || changed_[c.v] >= c.serial) continue;  // stale
            collapse(c.u, c.v, c.midpoint ? 0.5f * (pos_[c.u] + pos_[c.v]) : pos_[c.v]);
        }
    }

    [[nodiscard]] TriangleSurface result() const {
        TriangleSurface out;
        out.positions = pos_;
        for (size_t f = 0; f < faces_.size(); ++f)
            if (alive_[f]) out.indices.insert(out.indices.end(), faces_[f].begin(), faces_[f].end());
        return out;
    }

private:
    static constexpr uint32_t kDead = UINT32_MAX;

    // The vertices sharing a triangle with v, sorted and unique, into `n` (reused: no allocation once warm).
    void neighbours(uint32_t v, std::vector<uint32_t>& n) const {
        n.clear();
        for (const uint32_t f : vf_[v])
            for (const uint32_t w : faces_[f])
                if (w != v) n.push_back(w);
        std::sort(n.begin(), n.end());
        n.erase(std::unique(n.begin(), n.end()), n.end());
    }

    // Queues the cheaper direction of edge ab with its best placement.
    void push_edge(uint32_t a, uint32_t b) {
        Quadric q = quadric_[a];
        q += quadric_[b];
        const glm::vec3 options[3] = {pos_[b], pos_[a], 0.5f * (pos_[a] + pos_[b])};
        int best = 0;
        double cost = q.error(glm::dvec3(options[0]));
        for (int k = 1; k < 3; ++k) {
            const double e = q.error(glm::dvec3(options[k]));
            if (e < cost) cost = e, best = k;
        }
        // Shortest edges first (the skin wants even triangles: it is a spring mesh, and every vertex is
        // projected back onto the body afterwards), penalised by the squared deviation the collapse
        // makes (quadric error / edge length^2 ~ deviation^2): a deviation of a tenth of the edge
        // doubles the cost.
        const double len2 = std::max(glm::dot(glm::dvec3(pos_[a] - pos_[b]), glm::dvec3(pos_[a] - pos_[b])), 1e-18);
        cost = len2 + 100.0 * std::max(cost, 0.0) / len2;
        if (best == 1) std::swap(a, b);  // placement at a: collapse b into a
        heap_.push({cost, a, b, ++serial_, best == 2 ? 1u : 0u});
    }

    // Area-weighted normal of the triangles around u and v (the reference for triangles whose own
    // normal is not defined: marching tetrahedra leave near-degenerate ones).
    glm::vec3 fan_normal(uint32_t u, uint32_t v) const {
        glm::vec3 n(0.0f);
        for (const uint32_t w : {u, v})
            for (const uint32_t f : vf_[w]) {
                const auto& t = faces_[f];
                n += glm::cross(pos_[t[1]] - pos_[t[0]], pos_[t[2]] - pos_[t[0]]);
            }
        return n;
    }

    // True when every triangle of `v` that survives the collapse of v and `other` into `target` keeps
    // its orientation (its normal turns by less than ~80 degrees, or stays on the side of `fan` when
    // it had no well-defined normal) and does not become a sliver it was not already.
    bool faces_ok(uint32_t v, uint32_t other, glm::vec3 target, glm::vec3 fan) const {
        for (const uint32_t f : vf_[v]) {
            const auto& t = faces_[f];
            if (std::find(t.begin(), t.end(), other) != t.end()) continue;  // removed by the collapse
            glm::vec3 p[3], q[3];
            for (int k = 0; k < 3; ++k) {
                p[k] = pos_[t[static_cast<size_t>(k)]];
                q[k] = t[static_cast<size_t>(k)] == v ? target : p[k];
            }
            const glm::vec3 n0 = glm::cross(p[1] - p[0], p[2] - p[0]);
            const glm::vec3 n1 = glm::cross(q[1] - q[0], q[2] - q[0]);
            const float s0 = min_sine(p, n0), s1 = min_sine(q, n1);
            const glm::vec3 reference = s0 > 1e-3f ? n0 : fan;
            if (glm::dot(reference, n1) <= 0.17f * glm::length(reference) * glm::length(n1)) return false;
            // Minimum angle (sin = |n| / (|e1| |e2|) at each corner) kept above ~2 degrees unless the
            // triangle was already that thin and does not get much thinner.
            if (s1 < 0.035f && s1 < 0.5f * s0) return false;
        }
        return true;
    }

    bool collapse(uint32_t u, uint32_t v, glm::vec3 target) {
        if (live_faces_ <= 4) return false;
        // Link condition: common neighbours are exactly the two vertices opposite the edge.
        neighbours(u, nu_);
        neighbours(v, nv_);
        common_.clear();
        std::set_intersection(nu_.begin(), nu_.end(), nv_.begin(), nv_.end(), std::back_inserter(common_));
        uint32_t shared = 0;
        for (const uint32_t f : vf_[u]) {
            const auto& t = faces_[f];
            shared += std::find(t.begin(), t.end(), v) != t.end();
        }
        if (shared != 2 || common_.size() != 2) return false;
        const glm::vec3 fan = fan_normal(u, v);
        if (!faces_ok(u, v, target, fan) || !faces_ok(v, u, target, fan)) return false;
        // Remove the two triangles on uv, move u's others onto v.
        for (const uint32_t f : vf_[u]) {
            auto& t = faces_[f];
            if (std::find(t.begin(), t.end(), v) != t.end()) {
                alive_[f] = 0;
                --live_faces_;
                for (const uint32_t w : t)
                    if (w != u) std::erase(vf_[w], f);
            } else {
                for (uint32_t& w : t)
                    if (w == u) w = v;
                vf_[v].push_back(f);
            }
        }
        vf_[u].clear();
        pos_[v] = target;
        quadric_[v] += quadric_[u];
        changed_[u] = kDead;
        changed_[v] = ++serial_;  // every queued edge at v is stale from here
        neighbours(v, nv_);
        for (const uint32_t w : nv_) push_edge(std::min(v, w), std::max(v, w));  // only edges at v changed
        return true;
    }

    std::vector<glm::vec3> pos_;
    std::vector<std::array<uint32_t, 3>> faces_;
    std::vector<uint8_t> alive_;
    std::vector<std::vector<uint32_t>> vf_;
    std::vector<Quadric> quadric_;
    std::vector<uint32_t> changed_;  // serial of the vertex's last change (kDead once collapsed away)
    uint32_t serial_ = 0;
    size_t live_faces_ = 0;
    std::vector<uint32_t> nu_, nv_, common_;  // scratch of collapse()
    std::priority_queue<Candidate, std::vector<Candidate>, std::greater<>> heap_;
};

}  // namespace

TriangleSurface collapse_edges(const TriangleSurface& mesh, uint32_t target_triangles) {
    return collapse_edges_progressive(mesh, std::span(&target_triangles, 1)).front();
}

std::vector<TriangleSurface> collapse_edges_progressive(const TriangleSurface& mesh, std::span<const uint32_t> target_triangles) {
    // Largest target first: run(a) then run(b) with b <= a pops exactly what run(b) alone would, so each
    // snapshot equals a collapse straight from `mesh` to its target.
    std::vector<size_t> order(target_triangles.size());
    std::iota(order.begin(), order.end(), size_t{0});
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return target_triangles[a] > target_triangles[b]; });
    std::vector<TriangleSurface> out(target_triangles.size());
    Collapser c(mesh);
    for (const size_t i : order) {
        c.run(target_triangles[i]);
        out[i] = c.result();
    }
    return out;
}

}  // namespace aloha
