// Multi-muscle skin binding and the blended fat springs (see blend_binding.hpp).
#include "systems/geometry/body_skin/blend_binding.hpp"

#include "systems/geometry/body_skin/blend_rest.hpp"
#include "systems/geometry/body_skin/weight_smoothing.hpp"
#include "systems/geometry/muscle/superellipsoid.hpp"
#include "systems/geometry/spring_skin/fat_spring_step.hpp"
#include "systems/geometry/surface_grid.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>

namespace aloha {
namespace {

bool finite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// A sampled influence: point and frame of muscle m in its grid cell.
GridFrame frame_of(std::span<const glm::vec3> positions, std::span<const glm::vec3> normals, uint32_t T, uint32_t P, uint32_t m,
                   const GridCell& cell) {
    const size_t V = grid_vertex_count(T, P);
    return sample_grid_frame(positions.subspan(m * V, V), normals.subspan(m * V, V), cell);
}

}  // namespace

GridParam superellipsoid_param(glm::vec3 q, glm::vec3 radii, float a, float b) {
    const glm::vec3 s = q / radii;
    if (glm::dot(s, s) < 1e-20f) return {};
    // Scale s onto the surface (F homogeneous: F(s / r) = 1 with r = F(s)^(A/2)).
    const glm::vec3 as = glm::abs(s);
    const float F = std::pow(std::pow(as.x, 2.0f / b) + std::pow(as.y, 2.0f / b), b / a) + std::pow(as.z, 2.0f / a);
    const glm::vec3 u = s / std::pow(F, 0.5f * a);
    // x = cos(phi)^A cos(theta)^B, y = cos(phi)^A sin(theta)^B, z = sin(phi)^A (unit radii).
    const float theta = std::atan2(signed_pow(u.y, 1.0f / b), signed_pow(u.x, 1.0f / b));
    const float cos_phi = std::pow(std::pow(std::abs(u.x), 2.0f / b) + std::pow(std::abs(u.y), 2.0f / b), 0.5f * b / a);
    const float phi = std::atan2(signed_pow(u.z, 1.0f / a), cos_phi);
    return {theta, phi};
}

glm::vec3 blend_root(std::span<const glm::vec3> muscle_positions, uint32_t theta_steps, uint32_t phi_steps,
                     const BlendBinding& b) {
    const size_t V = grid_vertex_count(theta_steps, phi_steps);
    glm::vec3 root(0.0f);
    for (int k = 0; k < kBlendInfluences; ++k)
        if (b.weight[k] > 0.0f)
            root += b.weight[k] * sample_grid(muscle_positions.subspan(size_t{b.muscle[k]} * V, V), b.cell[k]);
    return root;
}

bool BlendBindJob::Validate(std::vector<std::string>* errors) const {
    bool ok = true;
    auto fail = [&](std::string message) {
        ok = false;
        if (errors) errors->push_back("BlendBindJob: " + std::move(message));
    };
    if (theta_steps < 3 || phi_steps < 2) fail("tessellation needs T >= 3 and P >= 2");
    if (!(spread > 0.0f && std::isfinite(spread))) fail("spread must be > 0");
    const size_t M = centres.size();
    if (M == 0) fail("no muscles");
    if (rotations.size() != M || radii.size() != M || exponents.size() != M) fail("shape spans differ in size");
    if (theta_steps >= 3 && phi_steps >= 2 && muscle_positions.size() != M * grid_vertex_count(theta_steps, phi_steps))
        fail("muscle_positions must hold one grid per muscle");
    if (muscle_normals.size() != muscle_positions.size()) fail("muscle_normals size differs from muscle_positions");
    if (bindings.size() != skin_positions.size()) fail("bindings size differs from skin_positions");
    if (!muscle_groups.empty() && muscle_groups.size() != M) fail("muscle_groups needs one group per muscle or none");
    if (!(smooth_radius >= 0.0f && std::isfinite(smooth_radius))) fail("smooth_radius must be finite and >= 0");
    if (skin_indices.size() % 3 != 0) fail("skin_indices must hold whole triangles");
    for (const uint32_t v : skin_indices) {
        if (v >= skin_positions.size()) {
            fail("skin_indices names vertex " + std::to_string(v) + " past " + std::to_string(skin_positions.size()));
            break;
        }
    }
    for (size_t i = 0; i < skin_positions.size(); ++i) {
        if (!finite(skin_positions[i])) {
            fail("skin vertex " + std::to_string(i) + " is not finite");
            break;
        }
    }
    return ok;
}

void BlendBindJob::Run() const {
    assert(Validate());
    const uint32_t M = static_cast<uint32_t>(centres.size());
    const size_t V = grid_vertex_count(theta_steps, phi_steps);
    constexpr int K = kBlendInfluences;
    auto compatible = [&](uint32_t a, uint32_t b) {
        if (muscle_groups.empty()) return true;
        const uint8_t g = muscle_groups[a], h = muscle_groups[b];
        return g == 0 || h == 0 || g == h;
    };
    auto param_of = [&](glm::vec3 p, uint32_t m) {
        const glm::vec3 q = glm::conjugate(rotations[m]) * (p - centres[m]);
        return superellipsoid_param(q, radii[m], exponents[m].x, exponents[m].y);
    };
    // 1. Kernel weights of the nearest compatible muscles (distance to the radially projected point).
    struct Candidate {
        float distance;
        uint32_t muscle;
    };
    std::vector<Candidate> all(M);
    std::vector<SparseWeights> weights(skin_positions.size());
    for (size_t i = 0; i < skin_positions.size(); ++i) {
        const glm::vec3 p = skin_positions[i];
        for (uint32_t m = 0; m < M; ++m) {
            const glm::vec3 point = sample_grid(muscle_positions.subspan(m * V, V), theta_steps, phi_steps, param_of(p, m));
            all[m] = {glm::length(p - point), m};
        }
        std::sort(all.begin(), all.end(), [](const Candidate& a, const Candidate& b) {
            return a.distance < b.distance || (a.distance == b.distance && a.muscle < b.muscle);
        });
        // Nearest first, skipping muscles of another limb than one already kept.
        size_t keep = 0;
        for (size_t c = 0; c < M && keep < static_cast<size_t>(K) + 1; ++c) {
            bool ok = true;
            for (size_t k = 0; k < keep && ok; ++k) ok = compatible(all[c].muscle, all[k].muscle);
            if (ok) all[keep++] = all[c];
        }
        // Kernels relative to the nearest (the common factor cancels in the normalisation).
        const float d0 = all[0].distance;
        const float cut = keep > static_cast<size_t>(K) ? std::exp(-(all[K].distance - d0) / spread) : 0.0f;
        SparseWeights& w = weights[i];
        float sum = 0.0f;
        w.count = static_cast<int>(std::min<size_t>(K, keep));
        for (int k = 0; k < w.count; ++k) {
            w.muscle[k] = all[k].muscle;
            w.weight[k] = std::max(std::exp(-(all[k].distance - d0) / spread) - cut, 0.0f);
            sum += w.weight[k];
        }
        if (!(sum > 1e-12f)) {  // equidistant set: the nearest alone
            w.count = 1;
            w.weight[0] = sum = 1.0f;
        }
        for (int k = 0; k < w.count; ++k) w.weight[k] /= sum;
    }
    // 2. Smoothed over the skin graph (a transition band of about smooth_radius across joints).
    const bool smooth = !skin_indices.empty() && smooth_radius > 0.0f;
    if (smooth) {
        const VertexGraph graph = build_vertex_graph(skin_positions, skin_indices);
        smooth_weights(graph, smoothing_rounds(smooth_radius, graph.mean_edge), weights);
    }
    // 3. The K largest pairwise compatible weights, renormalised, with their points and offsets.
    for (size_t i = 0; i < skin_positions.size(); ++i) {
        const glm::vec3 p = skin_positions[i];
        const SparseWeights& w = weights[i];
        BlendBinding& out = bindings[i];
        out = BlendBinding{};
        int used = 0;
        float sum = 0.0f;
        for (int c = 0; c < w.count && used < K; ++c) {
            if (!(w.weight[c] > 0.0f)) continue;
            bool ok = true;
            // Smoothed weights already blend two limbs only where the surface joins them through
            // the trunk (the crotch, the gluteal cleft): dropping one there would tear the skin.
            for (int k = 0; k < used && ok && !smooth; ++k) ok = compatible(w.muscle[c], out.muscle[k]);
            if (!ok) continue;
            out.muscle[used] = w.muscle[c];
            out.weight[used] = w.weight[c];
            sum += w.weight[c];
            ++used;
        }
        for (int k = 0; k < used; ++k) {
            out.weight[k] /= sum;
            out.param[k] = param_of(p, out.muscle[k]);
            out.cell[k] = grid_cell(theta_steps, phi_steps, out.param[k]);
            const GridFrame f = frame_of(muscle_positions, muscle_normals, theta_steps, phi_steps, out.muscle[k], out.cell[k]);
            const glm::vec3 d = p - f.point;
            out.offset[k] = {glm::dot(d, f.tangent), glm::dot(d, f.bitangent), glm::dot(d, f.normal)};
        }
    }
}

bool BlendSpringJob::Validate(std::vector<std::string>* errors) const {
    bool ok = true;
    auto fail = [&](std::string message) {
        ok = false;
        if (errors) errors->push_back("BlendSpringJob: " + std::move(message));
    };
    if (theta_steps < 3 || phi_steps < 2) fail("tessellation needs T >= 3 and P >= 2");
    if (muscle_count == 0) fail("muscle_count must be > 0");
    if (theta_steps >= 3 && phi_steps >= 2 && muscle_positions.size() != size_t{muscle_count} * grid_vertex_count(theta_steps, phi_steps))
        fail("muscle_positions must hold muscle_count grids");
    if (muscle_normals.size() != muscle_positions.size()) fail("muscle_normals size differs from muscle_positions");
    if (muscle_positions.size() > UINT32_MAX / sizeof(glm::vec3)) fail("muscle_positions must be under 4 GiB (32-bit offsets)");
    if (!(std::isfinite(params.dt) && params.dt > 0.0f)) fail("params.dt must be finite and > 0");
    if (!(params.normal_hz > 0.0f && params.lateral_hz > 0.0f && params.normal_damping >= 0.0f && params.max_strain > 0.0f))
        fail("spring frequencies, damping and strain limit must be positive");
    const size_t n = bindings.size();
    if (state.end.size() != n) fail("state.end needs one entry per binding");
    if (springs && (state.velocity.size() != n || state.prev_rest.size() != n || state.initialised.size() != 1))
        fail("spring state needs velocity and prev_rest per binding and one initialised flag");
    if (!vertex_region.empty()) {
        if (vertex_region.size() != n) fail("vertex_region needs one entry per binding (or none)");
        if (region_params.empty() || region_params.size() > kMaxSpringTunings)
            fail("region_params needs 1 to " + std::to_string(kMaxSpringTunings) + " tunings");
        for (const uint8_t r : vertex_region)
            if (r >= region_params.size()) {
                fail("vertex_region names tuning " + std::to_string(r) + " past region_params");
                break;
            }
        for (const FatSpringParams& p : region_params)
            if (!(p.normal_hz > 0.0f && p.lateral_hz > 0.0f && p.normal_damping >= 0.0f && p.max_strain > 0.0f && p.dt > 0.0f))
                fail("region spring frequencies, damping, strain limit and dt must be positive");
    }
    const uint32_t V = theta_steps >= 3 && phi_steps >= 2 ? grid_vertex_count(theta_steps, phi_steps) : 0;
    for (size_t i = 0; i < n; ++i) {
        bool bad = false, off_grid = false;
        for (int k = 0; k < kBlendInfluences; ++k) {
            if (!(bindings[i].weight[k] > 0.0f)) continue;
            bad |= bindings[i].muscle[k] >= muscle_count;
            for (const uint32_t c : bindings[i].cell[k].corner) off_grid |= c >= V;
        }
        if (bad) {
            fail("binding " + std::to_string(i) + " names a muscle past " + std::to_string(muscle_count));
            break;
        }
        if (off_grid) {
            fail("binding " + std::to_string(i) + " has a grid cell past V(T, P) = " + std::to_string(V) +
                 " (bound at another tessellation?)");
            break;
        }
    }
    return ok;
}

void BlendSpringJob::Run() const {
    assert(Validate());
    const uint32_t V = grid_vertex_count(theta_steps, phi_steps);
    const SpringStepper stepper(params);
    std::array<SpringStepper, kMaxSpringTunings> regions;  // per-region tunings (vertex_region)
    for (size_t r = 0; r < region_params.size() && !vertex_region.empty(); ++r) regions[r] = SpringStepper(region_params[r]);
    // start: placed at rest this frame; adopt: placed last frame, this step moves them with their rest ends
    // (fat_spring.hpp's kSpringsStarted).
    const bool start = springs && state.initialised[0] == kSpringsRestart;
    const bool adopt = springs && state.initialised[0] == kSpringsStarted;
    const size_t n = bindings.size();
    float roots[3][4], rests[3][4];  // four vertices' roots and rest ends, [axis][lane]
    for (size_t first = 0; first < n; first += 4) {
        // Four vertices at once where none has a degenerate frame (same bits as one by one).
        const size_t lanes = std::min<size_t>(4, n - first);
        const bool four = lanes == 4 && blend_rest_x4(muscle_positions, muscle_normals, V, &bindings[first], roots, rests);
        if (four && springs && !start && !adopt) {
            const SpringStepper* tuned[4];
            for (size_t lane = 0; lane < 4; ++lane) tuned[lane] = vertex_region.empty() ? &stepper : &regions[vertex_region[first + lane]];
            spring_step_x4(roots, rests, tuned, &state.end[first], &state.velocity[first], &state.prev_rest[first]);
            continue;
        }
        for (size_t lane = 0; lane < lanes; ++lane) {
            const size_t i = first + lane;
            glm::vec3 root, rest;
            if (four) {
                root = {roots[0][lane], roots[1][lane], roots[2][lane]};
                rest = {rests[0][lane], rests[1][lane], rests[2][lane]};
            } else {
                blend_rest(muscle_positions, muscle_normals, V, bindings[i], root, rest);
            }
            if (!springs) {
                state.end[i] = rest;
                continue;
            }
            if (start) {
                state.end[i] = rest;
                state.prev_rest[i] = rest;
                state.velocity[i] = glm::vec3(0.0f);
                continue;
            }
            const glm::vec3 axis = rest - root;
            const float h = glm::length(axis);
            const glm::vec3 normal = h > 1e-6f ? axis / h : glm::vec3(0.0f, 0.0f, 1.0f);
            const SpringStepper& tuned = vertex_region.empty() ? stepper : regions[vertex_region[i]];
            if (adopt) state.velocity[i] = (rest - state.prev_rest[i]) * tuned.inv_dt;
            tuned.step(rest, normal, h, state.end[i], state.velocity[i], state.prev_rest[i]);
        }
    }
    if (start) state.initialised[0] = kSpringsStarted;
    if (adopt) state.initialised[0] = kSpringsRunning;
}

}  // namespace aloha
