// Nearest-muscle-point binding of a mesh and its per-frame placement.
#include "systems/geometry/spring_skin/skin_binding.hpp"

#include "systems/geometry/body_skin/surface_map.hpp"  // closest_barycentric

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace aloha {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;

// One grid triangle with its corners' vertex indices and continuous (ring, column) coordinates.
struct ParamTriangle {
    uint32_t v[3];
    glm::vec2 rc[3];  // (ring in [0, P], column, unwrapped so the triangle does not straddle the seam)
};

// Triangles of one grid in append_grid_triangles order, with parameter coordinates.
std::vector<ParamTriangle> grid_param_triangles(uint32_t T, uint32_t P) {
    std::vector<ParamTriangle> tris;
    const uint32_t north = grid_vertex_count(T, P) - 1;
    const float fp = static_cast<float>(P);
    for (uint32_t t = 0; t < T; ++t) {
        const float ft = static_cast<float>(t);
        tris.push_back({{0, grid_ring_vertex(T, 1, t + 1), grid_ring_vertex(T, 1, t)}, {{0, ft + 0.5f}, {1, ft + 1}, {1, ft}}});
    }
    for (uint32_t r = 1; r + 1 < P; ++r) {
        for (uint32_t t = 0; t < T; ++t) {
            const float fr = static_cast<float>(r), ft = static_cast<float>(t);
            const uint32_t a = grid_ring_vertex(T, r, t), b = grid_ring_vertex(T, r, t + 1);
            const uint32_t c = grid_ring_vertex(T, r + 1, t + 1), d = grid_ring_vertex(T, r + 1, t);
            tris.push_back({{a, b, c}, {{fr, ft}, {fr, ft + 1}, {fr + 1, ft + 1}}});
            tris.push_back({{a, c, d}, {{fr, ft}, {fr + 1, ft + 1}, {fr + 1, ft}}});
        }
    }
    for (uint32_t t = 0; t < T; ++t) {
        const float ft = static_cast<float>(t);
        tris.push_back({{north, grid_ring_vertex(T, P - 1, t), grid_ring_vertex(T, P - 1, t + 1)},
                        {{fp, ft + 0.5f}, {fp - 1, ft}, {fp - 1, ft + 1}}});
    }
    return tris;
}

bool finite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

}  // namespace

bool SkinBindJob::Validate(std::vector<std::string>* errors) const {
    bool ok = true;
    auto fail = [&](std::string message) {
        ok = false;
        if (errors) errors->push_back("SkinBindJob: " + std::move(message));
    };
    if (theta_steps < 3 || phi_steps < 2) fail("tessellation needs T >= 3 and P >= 2");
    else if (muscle_positions.empty() || muscle_positions.size() % grid_vertex_count(theta_steps, phi_steps) != 0)
        fail("muscle_positions must hold one or more whole grids");
    if (muscle_normals.size() != muscle_positions.size()) fail("muscle_normals size differs from muscle_positions");
    if (bindings.size() != mesh_positions.size()) fail("bindings size differs from mesh_positions");
    for (size_t i = 0; i < mesh_positions.size(); ++i) {
        if (!finite(mesh_positions[i])) {
            fail("mesh vertex " + std::to_string(i) + " is not finite");
            break;
        }
    }
    return ok;
}

void SkinBindJob::Run() const {
    assert(Validate());
    const uint32_t T = theta_steps, P = phi_steps, V = grid_vertex_count(T, P);
    const size_t muscles = muscle_positions.size() / V;
    const std::vector<ParamTriangle> tris = grid_param_triangles(T, P);
    for (size_t i = 0; i < mesh_positions.size(); ++i) {
        const glm::vec3 p = mesh_positions[i];
        float best = std::numeric_limits<float>::infinity();
        size_t best_muscle = 0;
        glm::vec2 best_rc(0.0f);
        for (size_t m = 0; m < muscles; ++m) {
            const glm::vec3* mp = muscle_positions.data() + m * V;
            for (const ParamTriangle& tri : tris) {
                const glm::vec3 bary = closest_barycentric(p, mp[tri.v[0]], mp[tri.v[1]], mp[tri.v[2]]);
                const glm::vec3 q = bary.x * mp[tri.v[0]] + bary.y * mp[tri.v[1]] + bary.z * mp[tri.v[2]];
                const float dist2 = glm::dot(p - q, p - q);
                if (dist2 < best) {  // strict: the first (lowest index) of equals wins, deterministic
                    best = dist2;
                    best_muscle = m;
                    best_rc = bary.x * tri.rc[0] + bary.y * tri.rc[1] + bary.z * tri.rc[2];
                }
            }
        }
        SkinBinding& b = bindings[i];
        b.muscle = static_cast<uint32_t>(best_muscle);
        b.param = {-kPi + best_rc.y * 2.0f * kPi / static_cast<float>(T), -0.5f * kPi + best_rc.x * kPi / static_cast<float>(P)};
        const GridFrame f = sample_grid_frame(muscle_positions.subspan(best_muscle * V, V),
                                              muscle_normals.subspan(best_muscle * V, V), T, P, b.param);
        const glm::vec3 d = p - f.point;
        b.offset = {glm::dot(d, f.tangent), glm::dot(d, f.bitangent), glm::dot(d, f.normal)};
    }
}

bool BoundSkinJob::Validate(std::vector<std::string>* errors) const {
    bool ok = true;
    auto fail = [&](std::string message) {
        ok = false;
        if (errors) errors->push_back("BoundSkinJob: " + std::move(message));
    };
    if (theta_steps < 3 || phi_steps < 2) fail("tessellation needs T >= 3 and P >= 2");
    if (muscle_count == 0) fail("muscle_count must be > 0");
    size_t characters = 0;
    if (theta_steps >= 3 && phi_steps >= 2 && muscle_count > 0) {
        const size_t per_character = size_t{muscle_count} * grid_vertex_count(theta_steps, phi_steps);
        if (muscle_positions.size() % per_character != 0) fail("muscle_positions is not a whole number of characters");
        characters = muscle_positions.size() / per_character;
    }
    if (muscle_normals.size() != muscle_positions.size()) fail("muscle_normals size differs from muscle_positions");
    if (positions.size() != characters * bindings.size()) fail("positions must hold one vertex per binding per character");
    for (size_t i = 0; i < bindings.size(); ++i) {
        if (bindings[i].muscle >= muscle_count) {
            fail("binding " + std::to_string(i) + " names muscle " + std::to_string(bindings[i].muscle) +
                 " of " + std::to_string(muscle_count));
            break;
        }
    }
    return ok;
}

void BoundSkinJob::Run() const {
    assert(Validate());
    const uint32_t T = theta_steps, P = phi_steps, V = grid_vertex_count(T, P);
    const size_t per_character = size_t{muscle_count} * V, n = bindings.size();
    const size_t characters = muscle_positions.size() / per_character;
    for (size_t c = 0; c < characters; ++c) {
        for (size_t i = 0; i < n; ++i) {
            const SkinBinding& b = bindings[i];
            const size_t base = c * per_character + size_t{b.muscle} * V;
            const GridFrame f = sample_grid_frame(muscle_positions.subspan(base, V), muscle_normals.subspan(base, V), T, P, b.param);
            positions[c * n + i] = f.point + b.offset.x * f.tangent + b.offset.y * f.bitangent + b.offset.z * f.normal;
        }
    }
}

}  // namespace aloha
