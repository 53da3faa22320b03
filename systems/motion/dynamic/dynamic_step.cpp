// One step of the dynamic walk: build constraint rows, solve the coupled system for impulses,
// integrate, write the pose.
#include "engine/anim/pose.hpp"
#include "systems/motion/dynamic/dense_solve.hpp"
#include "systems/motion/dynamic/dynamic_walk.hpp"

#include <algorithm>
#include <cmath>

namespace aloha {

namespace {

constexpr size_t kRowFloats = 14;
enum RowKind : int { kBilateral = 0, kNormal = 1, kFriction = 2 };

glm::vec3 rotvec(const glm::quat& q_in) {
    const glm::quat q = q_in.w < 0.0f ? -q_in : q_in;
    const glm::vec3 v(q.x, q.y, q.z);
    const float s = glm::length(v);
    if (s < 1e-9f) return 2.0f * v;
    return v * (2.0f * std::atan2(s, q.w) / s);
}

glm::quat exp_rotvec(const glm::vec3& v) {
    const float a = glm::length(v);
    if (a < 1e-9f) return glm::normalize(glm::quat(1.0f, 0.5f * v.x, 0.5f * v.y, 0.5f * v.z));
    return glm::angleAxis(a, v / a);
}

// Appends one Jacobian row touching body b0 (and b1 >= 0) with its right-hand side and softness.
struct RowWriter {
    DynamicWalkState& s;
    size_t count = 0;
    void add(int b0, glm::vec3 lin0, glm::vec3 ang0, int b1, glm::vec3 lin1, glm::vec3 ang1, float rhs, float gamma,
             int kind, int normal_row = -1) {
        float* d = &s.row_data[count * kRowFloats];
        const glm::vec3 parts[4] = {lin0, ang0, lin1, ang1};
        for (int p = 0; p < 4; ++p)
            for (int c = 0; c < 3; ++c) d[3 * p + c] = parts[p][c];
        d[12] = rhs;
        d[13] = gamma;
        int* info = &s.row_info[count * 4];
        info[0] = b0;
        info[1] = b1;
        info[2] = kind;
        info[3] = normal_row;
        ++count;
    }
};

float velocity_along(const DynamicWalkState& s, size_t row) {
    const float* d = &s.row_data[row * kRowFloats];
    const int* info = &s.row_info[row * 4];
    const DynamicBody& a = s.bodies[static_cast<size_t>(info[0])];
    float v = d[0] * a.v.x + d[1] * a.v.y + d[2] * a.v.z + d[3] * a.w.x + d[4] * a.w.y + d[5] * a.w.z;
    if (info[1] >= 0) {
        const DynamicBody& b = s.bodies[static_cast<size_t>(info[1])];
        v += d[6] * b.v.x + d[7] * b.v.y + d[8] * b.v.z + d[9] * b.w.x + d[10] * b.w.y + d[11] * b.w.z;
    }
    return v;
}

// Soft-constraint coefficients for an implicit spring k / damper c over step h (impulse form):
// (A + gamma) lambda = -J v - (beta / h) C.
void soft(float k, float c, float h, float& gamma, float& beta) {
    const float denom = h * k + c;
    gamma = denom > 0.0f ? 1.0f / (h * denom) : 0.0f;
    beta = denom > 0.0f ? h * k / denom : 0.0f;
}

void build_rows(DynamicWalkState& s, float h, const glm::vec3& root_target, const glm::vec3& root_target_vel,
                RowWriter& rows, size_t& bilateral) {
    const DynamicWalkSettings& st = s.settings;
    const float w = st.constraint_frequency;
    const glm::vec3 axes[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    for (size_t i = 1; i < s.bodies.size(); ++i) {
        const DynamicBody& b = s.bodies[i];
        const auto pi = static_cast<size_t>(b.parent);
        const DynamicBody& p = s.bodies[pi];
        // Point constraint C = (x_b + r_b) - (x_p + r_p), Barzel & Barr: C'' + 2wC' + w^2 C = 0
        // discretised at velocity level, plus the velocity-product (centripetal) term over h.
        const glm::vec3 rb = b.q * (-b.com);
        const glm::vec3 rp = p.q * (b.anchor - p.com);
        const glm::vec3 c = (b.x + rb) - (p.x + rp);
        const glm::vec3 cdot = (b.v + glm::cross(b.w, rb)) - (p.v + glm::cross(p.w, rp));
        const glm::vec3 second = (exp_rotvec(h * b.w) * rb - rb - h * glm::cross(b.w, rb)) -
                                 (exp_rotvec(h * p.w) * rp - rp - h * glm::cross(p.w, rp));
        const glm::vec3 desired = (1.0f - 2.0f * w * h) * cdot - h * w * w * c - second / h;
        for (int k = 0; k < 3; ++k) {
            const glm::vec3& e = axes[k];
            rows.add(static_cast<int>(i), e, glm::cross(rb, e), static_cast<int>(pi), -e, -glm::cross(rp, e), desired[k],
                     0.0f, kBilateral);
        }
        // PD motor toward the target relative rotation, implicit (soft constraint).
        const glm::quat target_rel = glm::inverse(s.target_world[static_cast<size_t>(p.joint)]) *
                                     s.target_world[static_cast<size_t>(b.joint)];
        const glm::vec3 err = rotvec(b.q * glm::inverse(p.q * target_rel));
        float gamma = 0.0f;
        float beta = 0.0f;
        soft(b.motor_k, b.motor_c, h, gamma, beta);
        for (int k = 0; k < 3; ++k)
            rows.add(static_cast<int>(i), glm::vec3(0.0f), axes[k], static_cast<int>(pi), glm::vec3(0.0f), -axes[k],
                     -(beta / h) * err[k], gamma, kBilateral);
    }
    // Balance aid: PD on the pelvis joint position (toward the root target and its velocity) and
    // on the pelvis orientation (toward the target's world orientation).
    const DynamicBody& root = s.bodies[0];
    const float wb = st.balance_frequency;
    float gamma = 0.0f;
    float beta = 0.0f;
    const glm::vec3 r0 = root.q * (-root.com);
    const glm::vec3 pos_err = (root.x + r0) - root_target;
    soft(s.total_mass * wb * wb, 2.0f * st.balance_damping_ratio * wb * s.total_mass, h, gamma, beta);
    for (int k = 0; k < 3; ++k)
        rows.add(0, axes[k], glm::cross(r0, axes[k]), -1, {}, {}, root_target_vel[k] - (beta / h) * pos_err[k], gamma,
                 kBilateral);
    const glm::vec3 rot_err = rotvec(root.q * glm::inverse(s.target_world[static_cast<size_t>(root.joint)]));
    soft(s.balance_inertia * wb * wb, 2.0f * st.balance_damping_ratio * wb * s.balance_inertia, h, gamma, beta);
    for (int k = 0; k < 3; ++k)
        rows.add(0, glm::vec3(0.0f), axes[k], -1, {}, {}, -(beta / h) * rot_err[k], gamma, kBilateral);
    bilateral = rows.count;
    // Ground contacts (y = 0): non-penetration with Baumgarte push-out, two friction rows.
    for (const DynamicContact& ct : s.contacts) {
        const DynamicBody& b = s.bodies[static_cast<size_t>(ct.body)];
        const glm::vec3 r = b.q * (ct.local - b.com);
        const float y = b.x.y + r.y;
        if (y > 0.01f) continue;
        const float push = 0.2f / h * std::max(-y - 0.002f, 0.0f);
        const int normal_row = static_cast<int>(rows.count);
        rows.add(ct.body, axes[1], glm::cross(r, axes[1]), -1, {}, {}, push, 0.0f, kNormal);
        rows.add(ct.body, axes[0], glm::cross(r, axes[0]), -1, {}, {}, 0.0f, 0.0f, kFriction, normal_row);
        rows.add(ct.body, axes[2], glm::cross(r, axes[2]), -1, {}, {}, 0.0f, 0.0f, kFriction, normal_row);
    }
}

// Calls change(body, linear, angular) with lambda_r M^-1 J_r^T for each body of rows [0, rows): the velocity
// change of an impulse solve, or the displacement of a position projection.
template <class Change>
void for_each_row_change(const DynamicWalkState& s, const double* lambda, size_t rows, Change change) {
    for (size_t r = 0; r < rows; ++r) {
        const auto l = static_cast<float>(lambda[r]);
        const float* mj = &s.row_mj[r * 12];
        const int* info = &s.row_info[r * 4];
        for (int side = 0; side < 2; ++side) {
            if (info[side] < 0) continue;
            change(static_cast<size_t>(info[side]), l * glm::vec3(mj[6 * side], mj[6 * side + 1], mj[6 * side + 2]),
                   l * glm::vec3(mj[6 * side + 3], mj[6 * side + 4], mj[6 * side + 5]));
        }
    }
}

// Solves (A + Gamma) lambda = rhs - J v for bilateral rows exactly (Cholesky) and contact rows by
// projected Gauss-Seidel on their Schur complement, then applies the impulses. False (nothing
// applied) when the bilateral block cannot be factorised.
bool solve_and_apply(DynamicWalkState& s, size_t n, size_t nb) {
    for (size_t r = 0; r < n; ++r) {
        const float* d = &s.row_data[r * kRowFloats];
        const int* info = &s.row_info[r * 4];
        float* mj = &s.row_mj[r * 12];
        for (int side = 0; side < 2; ++side) {
            const int bi = info[side];
            if (bi < 0) {
                for (int c = 0; c < 6; ++c) mj[6 * side + c] = 0.0f;
                continue;
            }
            const DynamicBody& b = s.bodies[static_cast<size_t>(bi)];
            const glm::vec3 lin = glm::vec3(d[6 * side], d[6 * side + 1], d[6 * side + 2]) / b.mass;
            const glm::vec3 ang = s.world_inv_inertia[static_cast<size_t>(bi)] *
                                  glm::vec3(d[6 * side + 3], d[6 * side + 4], d[6 * side + 5]);
            for (int c = 0; c < 3; ++c) {
                mj[6 * side + c] = lin[c];
                mj[6 * side + 3 + c] = ang[c];
            }
        }
    }
    double* a = s.matrix.data();
    for (size_t i = 0; i < n; ++i) {
        const float* di = &s.row_data[i * kRowFloats];
        const int* ii = &s.row_info[i * 4];
        for (size_t j = 0; j <= i; ++j) {
            const float* mj = &s.row_mj[j * 12];
            const int* ij = &s.row_info[j * 4];
            double v = 0.0;
            for (int si = 0; si < 2; ++si)
                for (int sj = 0; sj < 2; ++sj)
                    if (ii[si] >= 0 && ii[si] == ij[sj])
                        for (int c = 0; c < 6; ++c) v += static_cast<double>(di[6 * si + c]) * mj[6 * sj + c];
            a[i * n + j] = a[j * n + i] = v;
        }
        a[i * n + i] += di[13];
    }
    double* rhs = s.lambda.data();
    for (size_t r = 0; r < n; ++r) rhs[r] = s.row_data[r * kRowFloats + 12] - velocity_along(s, r);
    for (size_t r = 0; r < nb; ++r) a[r * n + r] += 1e-9;  // keeps redundant rows factorisable
    if (!dyn::cholesky_factor(a, nb, n)) {
        // Not positive definite (a degenerate link): no impulses rather than a solve with a broken
        // factor; counted so the divergence guard hands the character back.
        ++s.failed_factorisations;
        return false;
    }
    dyn::cholesky_solve(a, nb, n, rhs);  // y = A_bb^-1 r_b
    const size_t nc = n - nb;
    if (nc > 0) {
        double* x = s.work.data();          // nc columns of length nb: X = A_bb^-1 A_bc
        double* sc = x + nc * nb;           // nc x nc Schur complement
        double* rc = sc + nc * nc;          // reduced contact rhs
        double* lc = rc + nc;               // contact impulses
        for (size_t c = 0; c < nc; ++c) {
            double* col = x + c * nb;
            for (size_t r = 0; r < nb; ++r) col[r] = a[(nb + c) * n + r];
            dyn::cholesky_solve(a, nb, n, col);
        }
        for (size_t i = 0; i < nc; ++i) {
            double r = rhs[nb + i];
            for (size_t k = 0; k < nb; ++k) r -= a[(nb + i) * n + k] * rhs[k];
            rc[i] = r;
            lc[i] = 0.0;
            for (size_t j = 0; j < nc; ++j) {
                double v = a[(nb + i) * n + nb + j];
                for (size_t k = 0; k < nb; ++k) v -= a[(nb + i) * n + k] * x[j * nb + k];
                sc[i * nc + j] = v;
            }
        }
        const double mu = s.settings.friction;
        for (int it = 0; it < 30; ++it) {
            for (size_t i = 0; i < nc; ++i) {
                double r = rc[i];
                for (size_t j = 0; j < nc; ++j) r -= sc[i * nc + j] * lc[j];
                double v = lc[i] + r / std::max(sc[i * nc + i], 1e-12);
                const int* info = &s.row_info[(nb + i) * 4];
                if (info[2] == kNormal) {
                    v = std::max(v, 0.0);
                } else {
                    const double lim = mu * lc[static_cast<size_t>(info[3]) - nb];
                    v = std::clamp(v, -lim, lim);
                }
                lc[i] = v;
            }
        }
        for (size_t c = 0; c < nc; ++c)
            for (size_t r = 0; r < nb; ++r) rhs[r] -= x[c * nb + r] * lc[c];
        for (size_t c = 0; c < nc; ++c) rhs[nb + c] = lc[c];
    }
    for_each_row_change(s, rhs, n, [&](size_t body, const glm::vec3& linear, const glm::vec3& angular) {
        s.bodies[body].v += linear;
        s.bodies[body].w += angular;
    });
    return true;
}

// Post-stabilisation (Cline & Pai): after integration, one linearised projection of the point
// constraints back to C = 0 using the factor of this substep's bilateral system (motor and balance
// rows get a zero right-hand side), applied as position/orientation displacements.
// The displacement of a body is the SUM over rows of lambda_r M^-1 J_r^T, applied once: the rows'
// rotations are individually large (up to ~0.04 rad on the light collar and hand links, cancelling
// in the sum) and applying them one after another as finite rotations adds their commutators, an
// error of order theta_r theta_s |r| that the next substep's projection amplifies until the body
// comes apart (the plaza_budget divergence, docs/PERFORMANCE.md).
void post_stabilise(DynamicWalkState& s, size_t n, size_t nb) {
    double* rhs = s.lambda.data();
    for (size_t r = 0; r < nb; ++r) rhs[r] = 0.0;
    for (size_t i = 1; i < s.bodies.size(); ++i) {
        const DynamicBody& b = s.bodies[i];
        const DynamicBody& p = s.bodies[static_cast<size_t>(b.parent)];
        const glm::vec3 c = (b.x + b.q * (-b.com)) - (p.x + p.q * (b.anchor - p.com));
        for (int k = 0; k < 3; ++k) rhs[6 * (i - 1) + static_cast<size_t>(k)] = -c[k];
    }
    dyn::cholesky_solve(s.matrix.data(), nb, n, rhs);
    std::fill(s.shift_position.begin(), s.shift_position.end(), glm::vec3(0.0f));
    std::fill(s.shift_rotation.begin(), s.shift_rotation.end(), glm::vec3(0.0f));
    for_each_row_change(s, rhs, nb, [&](size_t body, const glm::vec3& linear, const glm::vec3& angular) {
        s.shift_position[body] += linear;
        s.shift_rotation[body] += angular;
    });
    for (size_t i = 0; i < s.bodies.size(); ++i) {
        DynamicBody& b = s.bodies[i];
        b.x += s.shift_position[i];
        b.q = glm::normalize(exp_rotvec(s.shift_rotation[i]) * b.q);
    }
}

}  // namespace

void step_dynamic_walk(const Skeleton& skeleton, std::span<const glm::quat> target_local_rotations,
                       const glm::vec3& target_root_position, float dt, DynamicWalkState& s, PoseView out,
                       glm::mat4* out_root_world, std::span<const glm::vec3> target_local_translations) {
    const auto n = static_cast<size_t>(skeleton.joint_count());
    // Target world rotations (welded joints keep their start-pose local rotation).
    const glm::quat root_rot = glm::normalize(glm::quat_cast(glm::mat3(s.root_world)));
    for (size_t j = 0; j < n; ++j) {
        const int p = skeleton.parents()[j];
        // Joints outside the simulated subtree and joints owning a body follow the target; welded ones keep theirs.
        const bool owns = s.owner[j] < 0 || s.bodies[static_cast<size_t>(s.owner[j])].joint == static_cast<int>(j);
        const glm::quat local = glm::normalize(owns ? target_local_rotations[j] : s.welded_local[j]);
        s.target_world[j] = p < 0 ? root_rot * local : s.target_world[static_cast<size_t>(p)] * local;
    }
    const glm::vec3 root_target = glm::vec3(s.root_world * glm::vec4(target_root_position, 1.0f));
    const glm::vec3 root_target_vel = s.has_prev_target ? (root_target - s.prev_target_root) / dt : glm::vec3(0.0f);
    s.prev_target_root = root_target;
    s.has_prev_target = true;

    const int substeps = s.settings.substeps;
    const float h = dt / static_cast<float>(substeps);
    const glm::vec3 gravity(0.0f, -9.81f, 0.0f);
    for (int sub = 0; sub < substeps; ++sub) {
        for (size_t i = 0; i < s.bodies.size(); ++i) {
            const glm::mat3 r = glm::mat3_cast(s.bodies[i].q);
            s.world_inv_inertia[i] = r * s.bodies[i].inv_inertia * glm::transpose(r);
        }
        RowWriter rows{s};
        size_t bilateral = 0;
        // Rows use the pre-gravity velocities for C'; gravity enters through J v* below.
        build_rows(s, h, root_target, root_target_vel, rows, bilateral);
        for (DynamicBody& b : s.bodies) b.v += h * gravity;
        s.bodies[0].v += (h / s.bodies[0].mass) * s.pelvis_force;
        s.last_rows = rows.count;
        s.last_bilateral = bilateral;
        const bool solved = solve_and_apply(s, rows.count, bilateral);
        for (DynamicBody& b : s.bodies) {
            b.x += h * b.v;
            b.q = glm::normalize(exp_rotvec(h * b.w) * b.q);
        }
        if (solved) post_stabilise(s, rows.count, bilateral);
    }
    // Output pose in the character frame.
    const glm::mat4 inv_root = glm::inverse(s.root_world);
    glm::quat world_rot_parent{1, 0, 0, 0};
    for (size_t j = 0; j < n; ++j) {
        const int p = skeleton.parents()[j];
        world_rot_parent = p < 0 ? root_rot : s.target_world[static_cast<size_t>(p)];
        out.translations[j] = s.translations[j];
        out.scales[j] = s.scales[j];
        if (s.owner[j] < 0) {  // outside the simulated subtree: the target's rotation (target_world[j] already holds it)
            out.rotations[j] = glm::normalize(target_local_rotations[j]);
            if (!target_local_translations.empty()) out.translations[j] = target_local_translations[j];
        } else {
            const DynamicBody& b = s.bodies[static_cast<size_t>(s.owner[j])];
            const bool owns = b.joint == static_cast<int>(j);
            // target_world is reused below as the simulated world rotation of each joint.
            const glm::quat wj = owns ? b.q : world_rot_parent * s.welded_local[j];
            s.target_world[j] = wj;
            out.rotations[j] = glm::normalize(glm::inverse(world_rot_parent) * wj);
            if (static_cast<int>(j) == s.root_joint) {  // placed where the simulation put it, under its parent if any
                const glm::vec3 at = glm::vec3(inv_root * glm::vec4(body_joint_position(b), 1.0f));
                out.translations[j] = p < 0 ? at : glm::vec3(glm::inverse(out.model[static_cast<size_t>(p)]) * glm::vec4(at, 1.0f));
            }
        }
        const glm::mat4 local = trs_matrix(out.translations[j], out.rotations[j], out.scales[j]);
        out.model[j] = p < 0 ? local : out.model[static_cast<size_t>(p)] * local;
    }
    if (out_root_world) *out_root_world = s.root_world;
}

}  // namespace aloha
