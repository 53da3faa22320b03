// Building skin layers: the generated body skin and authored meshes, bound to the muscles.
#include "systems/geometry/controller/skin_layer.hpp"

#include "systems/geometry/body_skin/skin_remesh.hpp"
#include "systems/geometry/controller/character_geometry.hpp"
#include "systems/geometry/muscle/muscle_shape_job.hpp"
#include "systems/geometry/muscle/muscle_tessellate_job.hpp"
#include "systems/geometry/spring_skin/skin_mesh.hpp"
#include "systems/geometry/surface_grid.hpp"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <numbers>

namespace aloha {
namespace {

// Rest-pose muscle shapes and their tessellation at the tables' (T, P).
struct RestMuscles {
    std::vector<glm::vec3> centres, radii, positions, normals;
    std::vector<glm::quat> rotations;
};

RestMuscles rest_muscles(const MuscleSet& muscles, std::span<const glm::mat4> rest_model, const SuperEllipsoidTables* tables) {
    const size_t M = static_cast<size_t>(muscles.size());
    RestMuscles r;
    r.centres.resize(M);
    r.radii.resize(M);
    r.rotations.resize(M);
    const MuscleShapeJob shape{&muscles, rest_model, r.centres, r.rotations, r.radii};
    shape.Run();
    if (!tables) return r;
    const size_t V = tables->vertices_per_muscle();
    r.positions.resize(M * V);
    r.normals.resize(M * V);
    const MuscleTessellateJob tess{tables, r.centres, r.rotations, r.radii, r.positions, r.normals};
    tess.Run();
    return r;
}

// Field group of every joint: 0 for the trunk (the chain from the root to the highest joint at rest:
// pelvis, spine, neck, head), 1, 2, ... for each limb (a subtree hanging off the trunk chain: legs,
// arms), numbered in joint order. Limbs blend with the trunk but not with each other, so a hand
// hanging by the thigh or two thighs side by side stay separate surfaces instead of a blended web.
std::vector<uint8_t> limb_groups(std::span<const int16_t> parents, std::span<const glm::mat4> rest_model) {
    const size_t n = parents.size();
    size_t top = 0;
    for (size_t j = 1; j < n; ++j)
        if (rest_model[j][3].y > rest_model[top][3].y) top = j;
    std::vector<uint8_t> trunk(n, 0);
    for (int j = static_cast<int>(top); j >= 0; j = parents[static_cast<size_t>(j)]) trunk[static_cast<size_t>(j)] = 1;
    std::vector<uint8_t> group(n, 0);
    uint8_t next = 1;
    for (size_t j = 0; j < n; ++j) {  // parents come before their children
        const int p = parents[j];
        if (trunk[j] || p < 0) continue;
        group[j] = trunk[static_cast<size_t>(p)] ? (next < 255 ? next++ : next) : group[static_cast<size_t>(p)];
    }
    return group;
}

// Group of every muscle: its joints' limb when origin and insertion are on the same limb, else the
// trunk's (a muscle from the trunk onto a limb, e.g. pectoralis, joins the two).
std::vector<uint8_t> muscle_groups(const MuscleSet& muscles, std::span<const uint8_t> joint_group) {
    std::vector<uint8_t> out(static_cast<size_t>(muscles.size()));
    for (size_t m = 0; m < out.size(); ++m) {
        const uint8_t go = joint_group[static_cast<size_t>(muscles.origin_joint[m])];
        const uint8_t gi = joint_group[static_cast<size_t>(muscles.insertion_joint[m])];
        out[m] = go == gi ? gi : 0;
    }
    return out;
}

// Binds `layer.rest_positions` to the rest muscles at the tables' (T, P).
void bind_layer(SkinLayer& layer, const MuscleSet& muscles, std::span<const int16_t> parents, std::span<const glm::mat4> rest_model,
                const SuperEllipsoidTables& tables, float length_scale) {
    const RestMuscles r = rest_muscles(muscles, rest_model, &tables);
    const std::vector<uint8_t> groups = muscle_groups(muscles, limb_groups(parents, rest_model));
    layer.theta_steps = tables.theta_steps();
    layer.phi_steps = tables.phi_steps();
    layer.bindings.resize(layer.rest_positions.size());
    const BlendBindJob bind{layer.theta_steps, layer.phi_steps, kBindSpread * length_scale, r.centres, r.rotations, r.radii, muscles.exponents,
                            r.positions, r.normals, layer.rest_positions, layer.bindings, groups, layer.indices,
                            kBindSmoothing * length_scale};
    assert(bind.Validate());
    bind.Run();
    layer.dominant_muscle.resize(layer.bindings.size());
    for (size_t i = 0; i < layer.bindings.size(); ++i) {
        const BlendBinding& b = layer.bindings[i];
        const int k = static_cast<int>(std::max_element(b.weight, b.weight + kBlendInfluences) - b.weight);
        layer.dominant_muscle[i] = static_cast<uint16_t>(b.muscle[k]);
    }
    layer.rest_normals.assign(layer.rest_positions.size(), glm::vec3(0.0f));
    accumulate_vertex_normals(layer.rest_positions, layer.indices, layer.rest_normals);
}

// Index of the grid vertex nearest to (theta, phi) on a (T, P) grid.
uint32_t nearest_grid_vertex(uint32_t T, uint32_t P, GridParam param) {
    constexpr float kPi = std::numbers::pi_v<float>;
    const auto ring = static_cast<uint32_t>(std::lround(std::clamp((param.phi + 0.5f * kPi) / kPi, 0.0f, 1.0f) * static_cast<float>(P)));
    if (ring == 0) return 0;
    if (ring >= P) return grid_vertex_count(T, P) - 1;
    const auto t = static_cast<uint32_t>(std::lround((param.theta + kPi) / (2.0f * kPi) * static_cast<float>(T))) % T;
    return grid_ring_vertex(T, ring, t);
}

}  // namespace

float body_length_scale(float height) {
    if (!(height > 0.0f) || !std::isfinite(height)) return 1.0f;
    return height / std::clamp(height, 0.5f, 2.5f);
}

BodySurface build_body_surface(const MuscleSet& muscles, const Skeleton& skeleton, std::span<const glm::mat4> rest_model,
                               std::span<const float> proxy_radii, float length_scale) {
    const RestMuscles r = rest_muscles(muscles, rest_model, nullptr);
    const std::span<const int16_t> parents = skeleton.parents();
    std::vector<uint8_t> group = limb_groups(parents, rest_model);
    // A trunk_skin muscle's origin joint (a deltoid's clavicle) is part of the trunk's surface, with the bone from it.
    for (size_t m = 0; m < muscles.trunk_skin.size(); ++m)
        if (muscles.trunk_skin[m]) group[static_cast<size_t>(muscles.origin_joint[m])] = 0;
    BodyField field;
    field.blend = kBodySkinBlend * length_scale;
    field.trunk_fill = kBodySkinTrunkFill * length_scale;
    for (size_t m = 0; m < r.centres.size(); ++m)
        field.ellipsoids.push_back({r.centres[m], r.rotations[m], r.radii[m] + glm::vec3(muscles.fat_thickness[m]), muscles.exponents[m]});
    field.ellipsoid_group = muscle_groups(muscles, group);
    for (size_t j = 0; j < parents.size(); ++j) {
        if (parents[j] < 0) continue;
        const glm::vec3 a(rest_model[static_cast<size_t>(parents[j])][3]), b(rest_model[j][3]);
        if (glm::length(b - a) < 1e-4f) continue;
        field.capsules.push_back({a, b, 0.5f * proxy_radii[j]});
        field.capsule_group.push_back(group[static_cast<size_t>(parents[j])] == group[j] ? group[j] : 0);
    }
    BodySurface out;
    out.field = sample_body_field(field, kBodySkinCell * length_scale);
    out.dense = polygonise(out.field);
    return out;
}

SkinLayer build_generated_skin(const BodySurface& body, const MuscleSet& muscles, std::span<const int16_t> parents,
                               std::span<const glm::mat4> rest_model,
                               const SuperEllipsoidTables& tables, const GeneratedBindMesh& generated, float length_scale) {
    // The collapse keeps the dense surface's topology: one closed manifold (the tests check it).
    return bind_generated_skin(simplify_and_relax(body.dense, body.field, generated_skin_triangles(muscles, tables)), muscles,
                               parents, rest_model, tables, generated, length_scale);
}

uint32_t generated_skin_triangles(const MuscleSet& muscles, const SuperEllipsoidTables& tables) {
    return static_cast<uint32_t>(muscles.size()) * grid_vertex_count(tables.theta_steps(), tables.phi_steps());
}

SkinLayer bind_generated_skin(TriangleSurface skin, const MuscleSet& muscles, std::span<const int16_t> parents,
                              std::span<const glm::mat4> rest_model, const SuperEllipsoidTables& tables,
                              const GeneratedBindMesh& generated, float length_scale) {
    const uint32_t T = tables.theta_steps(), P = tables.phi_steps(), V = grid_vertex_count(T, P);
    SkinLayer layer;
    layer.rest_positions = std::move(skin.positions);
    layer.indices = std::move(skin.indices);
    bind_layer(layer, muscles, parents, rest_model, tables, length_scale);
    // LBS weights: the grid mesh's weights at each influence's nearest grid vertex, blended by the
    // binding weights, the four largest kept and renormalised.
    const size_t n = layer.rest_positions.size();
    layer.joints.resize(n);
    layer.weights.resize(n);
    for (size_t i = 0; i < n; ++i) {
        const BlendBinding& b = layer.bindings[i];
        std::vector<std::pair<float, uint16_t>> acc;
        for (int k = 0; k < kBlendInfluences; ++k) {
            if (b.weight[k] <= 0.0f) continue;
            const size_t g = size_t{b.muscle[k]} * V + nearest_grid_vertex(T, P, b.param[k]);
            for (int q = 0; q < 4; ++q) {
                const float w = b.weight[k] * generated.weights[g][q];
                if (w <= 0.0f) continue;
                const uint16_t j = generated.joints[g][q];
                auto it = std::find_if(acc.begin(), acc.end(), [&](const auto& e) { return e.second == j; });
                if (it == acc.end()) acc.emplace_back(w, j);
                else it->first += w;
            }
        }
        std::sort(acc.begin(), acc.end(), [](const auto& a, const auto& c) { return a.first > c.first || (a.first == c.first && a.second < c.second); });
        acc.resize(std::min<size_t>(acc.size(), 4));
        float sum = 0.0f;
        for (const auto& e : acc) sum += e.first;
        for (size_t q = 0; q < acc.size(); ++q) {
            layer.joints[i][static_cast<int>(q)] = acc[q].second;
            layer.weights[i][static_cast<int>(q)] = acc[q].first / sum;
        }
    }
    return layer;
}

SkinLayer build_mesh_skin(std::span<const glm::vec3> rest_positions, std::span<const uint32_t> indices, const MuscleSet& muscles,
                          std::span<const int16_t> parents, std::span<const glm::mat4> rest_model, const SuperEllipsoidTables& tables,
                          float length_scale) {
    SkinLayer layer;
    layer.rest_positions.assign(rest_positions.begin(), rest_positions.end());
    layer.indices.assign(indices.begin(), indices.end());
    bind_layer(layer, muscles, parents, rest_model, tables, length_scale);
    return layer;
}

}  // namespace aloha
