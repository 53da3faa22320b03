// build_generated_mesh: the peeled bind mesh generated from a type's muscles (character_geometry.hpp).
#include "systems/geometry/controller/character_geometry.hpp"

#include "systems/geometry/muscle/muscle_shape_job.hpp"
#include "systems/geometry/muscle/muscle_tessellate_job.hpp"
#include "systems/geometry/spring_skin/skin_mesh.hpp"
#include "systems/geometry/surface_grid.hpp"

#include <algorithm>
#include <cassert>

namespace aloha {

namespace {

// Joints whose matrices skin muscle m of the generated mesh: the chain from the origin joint down
// to the insertion joint (origin first), at most 4, with each pivot's rest position. A pivot that
// coincides with the next one is dropped (the next joint's matrix carries its rotation, and the
// optimal cumulative weight of two coincident pivots is the same). Origin not an ancestor of the
// insertion: just the two joints, the insertion joint's position as the pivot.
struct MuscleChain {
    int count = 0;
    uint16_t joints[4] = {0, 0, 0, 0};
    glm::vec3 pivots[4];  // pivots[k] = rest position of joints[k] (k >= 1)
};

MuscleChain muscle_chain(std::span<const int16_t> parents, std::span<const glm::mat4> rest_model, int origin, int insertion) {
    MuscleChain chain;
    std::vector<int> path;  // insertion up to (excluding) origin
    int j = insertion;
    while (j >= 0 && j != origin) {
        path.push_back(j);
        j = parents[static_cast<size_t>(j)];
    }
    if (j != origin) path.assign(1, insertion);
    std::vector<int> kept;
    for (size_t k = path.size(); k-- > 0;) {  // origin side first
        const glm::vec3 p(rest_model[static_cast<size_t>(path[k])][3]);
        if (k > 0 && glm::length(p - glm::vec3(rest_model[static_cast<size_t>(path[k - 1])][3])) < 1e-4f) continue;
        kept.push_back(path[k]);
    }
    if (kept.size() > 3) kept.erase(kept.begin(), kept.end() - 3);  // keep the pivots nearest the insertion
    chain.joints[0] = static_cast<uint16_t>(origin);
    chain.count = 1;
    for (const int k : kept) {
        chain.joints[chain.count] = static_cast<uint16_t>(k);
        chain.pivots[chain.count] = glm::vec3(rest_model[static_cast<size_t>(k)][3]);
        ++chain.count;
    }
    return chain;
}

}  // namespace

GeneratedBindMesh build_generated_mesh(const MuscleSet& muscles, std::span<const int16_t> parents,
                                       std::span<const glm::mat4> rest_model, const SuperEllipsoidTables& tables) {
    const size_t M = static_cast<size_t>(muscles.size());
    const uint32_t T = tables.theta_steps(), P = tables.phi_steps(), V = grid_vertex_count(T, P);
    std::vector<glm::vec3> centres(M), radii(M), mpos(M * V), mnrm(M * V);
    std::vector<glm::quat> rotations(M);
    const MuscleShapeJob shape{&muscles, rest_model, centres, rotations, radii};
    assert(shape.Validate());
    shape.Run();
    const MuscleTessellateJob tess{&tables, centres, rotations, radii, mpos, mnrm};
    assert(tess.Validate());
    tess.Run();

    GeneratedBindMesh out;
    out.theta_steps = T;
    out.phi_steps = P;
    out.positions.resize(M * V);
    out.normals.resize(M * V);
    out.joints.resize(M * V);
    out.weights.resize(M * V);
    for (size_t m = 0; m < M; ++m) {
        const float h = muscles.fat_thickness[m];
        const glm::vec3 axis = glm::mat3_cast(rotations[m])[0];
        const glm::vec3 o = centres[m] - radii[m].x * axis, ins = centres[m] + radii[m].x * axis;  // tendons at rest
        const MuscleChain chain = muscle_chain(parents, rest_model, muscles.origin_joint[m], muscles.insertion_joint[m]);
        for (size_t i = m * V; i < (m + 1) * V; ++i) {
            out.positions[i] = mpos[i] + h * mnrm[i];
            // Position along the muscle axis: u = 0 at the origin tendon, 1 at the insertion.
            const float u = std::clamp(0.5f * (glm::dot(mpos[i] - centres[m], axis) / radii[m].x + 1.0f), 0.0f, 1.0f);
            // Cumulative weight past pivot k: a small rotation d at the pivot moves the straight muscle's
            // point at u by u * d x (ins - pivot) but an LBS vertex with weight W past the pivot by
            // W * d x (point - pivot); W = u a_i / (u a_i + (1 - u) a_o) balances the two tendon
            // lever arms a_o = |o - pivot|, a_i = |ins - pivot| (exact at both tendons, smooth in u).
            float W[5] = {1.0f, 0.0f, 0.0f, 0.0f, 0.0f};
            for (int k = 1; k < chain.count; ++k) {
                const float ai = u * glm::length(ins - chain.pivots[k]), ao = (1.0f - u) * glm::length(o - chain.pivots[k]);
                W[k] = ai + ao > 1e-9f ? ai / (ai + ao) : u;
                W[k] = std::min(W[k], W[k - 1]);  // weights stay non-negative along the chain
            }
            glm::vec4 w(0.0f);
            for (int k = 0; k < chain.count; ++k) w[k] = W[k] - W[k + 1];
            out.joints[i] = glm::u16vec4(chain.joints[0], chain.joints[1], chain.joints[2], chain.joints[3]);
            out.weights[i] = w;
        }
    }
    const SkinJob normals{T, P, out.positions, mnrm, out.normals};
    assert(normals.Validate());
    normals.Run();
    return out;
}

}  // namespace aloha
