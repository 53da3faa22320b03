#include "systems/geometry/muscle/muscle_fit.hpp"

#include "systems/geometry/muscle/superellipsoid.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace aloha {

namespace {

// Unit eigenvector of the largest eigenvalue of a symmetric 3x3 matrix (power iteration from a
// fixed start, so results are deterministic).
glm::vec3 principal_axis(const glm::dmat3& cov) {
    glm::dvec3 v(0.577, 0.578, 0.579);
    for (int it = 0; it < 64; ++it) {
        const glm::dvec3 w = cov * v;
        const double n = glm::length(w);
        if (n < 1e-30) return glm::vec3(0, 1, 0);
        v = w / n;
    }
    return glm::vec3(v);
}

// Any unit vector orthogonal to unit `a`.
glm::vec3 any_perpendicular(glm::vec3 a) {
    const glm::vec3 e = std::fabs(a.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
    return glm::normalize(glm::cross(a, e));
}

// First child of `joint` whose bind-pose position differs from the joint's, or -1.
int bone_child(const Skeleton& s, std::span<const glm::mat4> bind, int joint) {
    for (int c = joint + 1; c < s.joint_count(); ++c)
        if (s.parents()[static_cast<size_t>(c)] == joint &&
            glm::length(glm::vec3(bind[static_cast<size_t>(c)][3] - bind[static_cast<size_t>(joint)][3])) > 1e-5f)
            return c;
    return -1;
}

}  // namespace

Result<MuscleSet> fit_muscles_per_bone(const Skeleton& skeleton, std::span<const glm::mat4> bind_model,
                                       std::span<const glm::vec3> positions, std::span<const glm::ivec4> joints,
                                       std::span<const glm::vec4> weights, const MuscleFitOptions& options) {
    const std::string& src = options.source_name;
    const int nj = skeleton.joint_count();
    if (bind_model.size() != static_cast<size_t>(nj))
        return make_error(src, "bind pose has " + std::to_string(bind_model.size()) + " matrices for " + std::to_string(nj) + " joints");
    if (joints.size() != positions.size() || weights.size() != positions.size())
        return make_error(src, "positions, joints and weights differ in length (" + std::to_string(positions.size()) + ", " +
                                   std::to_string(joints.size()) + ", " + std::to_string(weights.size()) + ")");
    if (!(options.fat_thickness >= 0.0f)) return make_error(src, "fat thickness must be >= 0");
    // Dominant joint of every vertex (largest weight, first on ties).
    std::vector<int> owner(positions.size(), -1);
    std::vector<int> counts(static_cast<size_t>(nj), 0);
    for (size_t v = 0; v < positions.size(); ++v) {
        const glm::vec3 p = positions[v];
        if (!std::isfinite(p.x + p.y + p.z)) return make_error(src, "vertex " + std::to_string(v) + " has a non-finite position");
        float best = 0.0f;
        for (int k = 0; k < 4; ++k) {
            const int j = joints[v][k];
            const float w = weights[v][k];
            if (!(w > 0.0f)) continue;
            if (j < 0 || j >= nj)
                return make_error(src, "vertex " + std::to_string(v) + " is bound to joint " + std::to_string(j) +
                                           ", outside [0, " + std::to_string(nj) + ")");
            if (w > best) {
                best = w;
                owner[v] = j;
            }
        }
        if (owner[v] >= 0) ++counts[static_cast<size_t>(owner[v])];
    }
    MuscleSet set;
    set.joint_count = nj;
    std::vector<glm::vec3> local;
    for (int j = 0; j < nj; ++j) {
        if (counts[static_cast<size_t>(j)] < std::max(options.min_vertices, 4)) continue;
        const glm::mat4& M = bind_model[static_cast<size_t>(j)];
        const glm::mat4 Minv = glm::inverse(M);
        local.clear();
        glm::dvec3 mean(0.0);
        for (size_t v = 0; v < positions.size(); ++v) {
            if (owner[v] != j) continue;
            local.push_back(glm::vec3(Minv * glm::vec4(positions[v], 1.0f)));
            mean += glm::dvec3(local.back());
        }
        mean /= static_cast<double>(local.size());
        glm::dmat3 cov(0.0);
        for (const glm::vec3 q : local) {
            const glm::dvec3 d = glm::dvec3(q) - mean;
            cov += glm::outerProduct(d, d);
        }
        // Long axis: towards the child joint when the bone has length, else the principal axis.
        const int child = bone_child(skeleton, bind_model, j);
        glm::vec3 axis = child >= 0 ? glm::normalize(glm::vec3(Minv * bind_model[static_cast<size_t>(child)][3]))
                                    : principal_axis(cov);
        // Width axis: principal axis of the covariance restricted to the plane across the long axis.
        const glm::dmat3 P = glm::dmat3(1.0) - glm::outerProduct(glm::dvec3(axis), glm::dvec3(axis));
        glm::vec3 e2 = principal_axis(P * cov * P);
        e2 -= glm::dot(e2, axis) * axis;
        e2 = glm::length(e2) > 1e-4f ? glm::normalize(e2) : any_perpendicular(axis);
        const glm::vec3 e3 = glm::cross(axis, e2);
        glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
        const glm::vec3 c(mean);
        for (const glm::vec3 q : local) {
            const glm::vec3 d = q - c;
            const glm::vec3 s(glm::dot(d, axis), glm::dot(d, e2), glm::dot(d, e3));
            lo = glm::min(lo, s);
            hi = glm::max(hi, s);
        }
        const glm::vec3 half = 0.5f * (hi - lo), mid = 0.5f * (hi + lo);
        const float f = options.fat_thickness, keep = options.min_radius_fraction;
        const float hl = std::max(half.x - f, keep * half.x);
        const float ry = std::max(half.y - f, keep * half.y), rz = std::max(half.z - f, keep * half.z);
        if (!(hl > 1e-4f && ry > 1e-5f && rz > 1e-5f)) continue;  // flat or degenerate cloud: no muscle
        const glm::vec3 centre = c + axis * mid.x + e2 * mid.y + e3 * mid.z;
        const glm::vec3 o = centre - axis * hl, ins = centre + axis * hl;
        int ins_joint = j;
        glm::vec3 ins_off = ins;
        if (options.insertion_on_child && child >= 0) {
            ins_joint = child;
            ins_off = glm::vec3(glm::inverse(bind_model[static_cast<size_t>(child)]) * (M * glm::vec4(ins, 1.0f)));
        }
        const glm::vec2 ab(1.0f, 1.0f);
        const float vol = static_cast<float>(superellipsoid_volume(glm::dvec3(hl, ry, rz), ab.x, ab.y));
        set.push_back(skeleton.names()[static_cast<size_t>(j)] + "_muscle", j, o, ins_joint, ins_off, e3, vol, ry / rz, ab, f,
                      2.0f * hl);
    }
    return set;
}

}  // namespace aloha
