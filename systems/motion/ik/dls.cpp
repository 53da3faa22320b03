#include "systems/motion/ik/dls.hpp"

#include "systems/motion/ik/ccd.hpp"
#include "systems/motion/ik/chain_fk.hpp"
#include "systems/motion/ik/ik_chain.hpp"
#include "systems/motion/ik/joint_limits.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/LU>

#include <algorithm>
#include <cassert>
#include <cmath>

namespace aloha {

using namespace ik;  // NOLINT: IK helper namespace

namespace {

constexpr int kMaxRows = 6;
constexpr int kMaxCols = 3 * kMaxIkChain;
constexpr int kMaxTries = 6;

// Eigen types of fixed row count (3: position, 6: position and orientation) and bounded column count:
// the solver never allocates (it runs per character per frame). Sums in double, as J J^T of a long chain
// loses the small singular values in float and the iteration then stalls near the tolerance.
template <int R>
using Jacobian = Eigen::Matrix<double, R, Eigen::Dynamic, Eigen::RowMajor, R, kMaxCols>;
template <int R>
using RowSquare = Eigen::Matrix<double, R, R>;
template <int R>
using RowVector = Eigen::Matrix<double, R, 1>;

// Forward kinematics of the chain from a fixed parent matrix into `model`.
void chain_fk(const Skeleton& skeleton, std::span<const int> chain, const PoseView& pose, const glm::quat* local,
              const glm::mat4& base_parent, glm::mat4* model) {
    glm::mat4 m = base_parent;
    for (size_t k = 0; k < chain.size(); ++k) {
        const auto j = static_cast<size_t>(chain[k]);
        m = m * trs_matrix(pose.translations[j], local[k], pose.scales[j]);
        model[k] = m;
    }
    (void)skeleton;
}


// dq = J^T (J J^T + lambda2 I)^-1 e over the active columns (Eigen's Cholesky, LLT); false if the system
// is not symmetric positive definite.
template <int R>
bool dls_step_rows(const float jac[kMaxRows][kMaxCols], const bool* active, int cols, float lambda2, const float* e,
                   float* dq) {
    Jacobian<R> j(R, cols);
    RowVector<R> err;
    for (int i = 0; i < R; ++i) {
        err(i) = e[i];
        for (int c = 0; c < cols; ++c) j(i, c) = active[c] ? jac[i][c] : 0.0f;
    }
    RowSquare<R> a = j * j.transpose();
    a.diagonal().array() += static_cast<double>(lambda2);
    const Eigen::LLT<RowSquare<R>> llt(a);
    if (llt.info() != Eigen::Success) return false;
    const RowVector<R> y = llt.solve(err);
    for (int c = 0; c < cols; ++c) dq[c] = static_cast<float>(j.col(c).dot(y));
    return true;
}

bool dls_step(const float jac[kMaxRows][kMaxCols], const bool* active, int rows, int cols, float lambda2,
              const float* e, float* dq) {
    assert(rows == 3 || rows == 6);
    return rows == 3 ? dls_step_rows<3>(jac, active, cols, lambda2, e, dq) : dls_step_rows<6>(jac, active, cols, lambda2, e, dq);
}

// Geometric-mean singular value of the 3x3 position block of J J^T: det^(1/6).
float position_sigma(const float jac[kMaxRows][kMaxCols], int cols) {
    Jacobian<3> j(3, cols);
    for (int i = 0; i < 3; ++i)
        for (int c = 0; c < cols; ++c) j(i, c) = jac[i][c];
    const double det = (j * j.transpose()).determinant();
    return static_cast<float>(std::pow(std::max(det, 0.0), 1.0 / 6.0));
}

}  // namespace

IkResult solve_dls(const Skeleton& skeleton, std::span<const int> chain, PoseView pose, const IkTarget& target,
                   const IkSettings& settings, std::span<float> error_per_iteration) {
    assert(!chain.empty() && chain.size() <= static_cast<size_t>(kMaxIkChain));
    const size_t n = chain.size();
    const int rows = target.use_orientation ? 6 : 3;
    const int cols = static_cast<int>(3 * n);
    const float w = target.orientation_weight;
    const glm::quat target_rot = glm::normalize(target.orientation);
    const glm::mat4 base_parent = parent_model(skeleton, pose.model, chain[0]);

    // Free joints move by world rotation vectors; limited joints by their rest-relative Euler
    // angles (columns = the Euler axes), so box limits clamp single coordinates exactly.
    glm::quat local[kMaxIkChain];
    glm::quat trial[kMaxIkChain];
    glm::vec3 euler[kMaxIkChain];
    glm::vec3 trial_euler[kMaxIkChain];
    glm::mat4 model[kMaxIkChain];
    glm::mat4 trial_model[kMaxIkChain];
    float chain_length = 0.0f;
    for (size_t k = 0; k < n; ++k) {
        const auto j = static_cast<size_t>(chain[k]);
        local[k] = pose.rotations[j];
        model[k] = pose.model[j];
        euler[k] = relative_euler_xyz(skeleton.rest_rotations()[j], local[k]);
        if (k > 0) chain_length += glm::length(matrix_position(model[k]) - matrix_position(model[k - 1]));
    }
    // Singularity damping (Nakamura & Hanafusa): extra damping when the geometric-mean singular
    // value of the position Jacobian drops below sigma0.
    const float sigma0 = 0.1f * std::max(chain_length, 1e-3f);
    float lambda = settings.damping;
    const float lambda_min = 1e-4f * std::max(chain_length, 1e-3f);

    IkError err = ik_error(model[n - 1], target);
    int iterations = 0;
    while (err.combined > settings.tolerance && iterations < settings.max_iterations) {
        float jac[kMaxRows][kMaxCols];
        const glm::vec3 pe = matrix_position(model[n - 1]);
        for (size_t k = 0; k < n; ++k) {
            const auto j = static_cast<size_t>(chain[k]);
            const glm::vec3 r = pe - matrix_position(model[k]);
            glm::vec3 axes[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
            if (skeleton.limits()[j].limited) {
                euler_axes(skeleton.rest_rotations()[j], euler[k], axes);
                const glm::quat parent_rot = matrix_rotation(k == 0 ? base_parent : model[k - 1]);
                for (auto& ax : axes) ax = glm::normalize(parent_rot * ax);
            }
            for (int a = 0; a < 3; ++a) {
                const glm::vec3 lin = glm::cross(axes[a], r);  // column: [u x (P_c - p_k); w u]
                const int c = static_cast<int>(3 * k) + a;
                jac[0][c] = lin.x;
                jac[1][c] = lin.y;
                jac[2][c] = lin.z;
                if (rows == 6) {
                    jac[3][c] = w * axes[a].x;
                    jac[4][c] = w * axes[a].y;
                    jac[5][c] = w * axes[a].z;
                }
            }
        }
        float e[kMaxRows];
        const glm::vec3 dp = target.position - pe;
        e[0] = dp.x;
        e[1] = dp.y;
        e[2] = dp.z;
        if (rows == 6) {
            const glm::vec3 dr = w * rotation_vector(target_rot * glm::inverse(matrix_rotation(model[n - 1])));
            e[3] = dr.x;
            e[4] = dr.y;
            e[5] = dr.z;
        }
        const float sigma = position_sigma(jac, cols);
        const float sing = sigma < sigma0 ? settings.damping * (1.0f - sigma / sigma0) : 0.0f;

        bool accepted = false;
        for (int attempt = 0; attempt < kMaxTries && !accepted; ++attempt) {
            const float lambda2 = lambda * lambda + sing * sing;
            bool active[kMaxCols];
            for (int c = 0; c < cols; ++c) active[c] = true;
            float dq[kMaxCols];
            bool solved = dls_step(jac, active, rows, cols, lambda2, e, dq);
            // Clamping loop: drop limited DOFs that the step pushes past a limit, then re-solve.
            for (int pass = 0; solved && pass < 2; ++pass) {
                bool dropped = false;
                for (size_t k = 0; k < n; ++k) {
                    const JointLimit& l = skeleton.limits()[static_cast<size_t>(chain[k])];
                    if (!l.limited) continue;
                    for (int a = 0; a < 3; ++a) {
                        const int c = static_cast<int>(3 * k) + a;
                        const float v = euler[k][a] + dq[c];
                        if (active[c] && (v < l.min_angles[a] || v > l.max_angles[a])) {
                            active[c] = false;
                            dropped = true;
                        }
                    }
                }
                if (!dropped) break;
                solved = dls_step(jac, active, rows, cols, lambda2, e, dq);
            }
            if (!solved) {
                lambda *= 4.0f;
                continue;
            }
            for (size_t k = 0; k < n; ++k) {
                const auto j = static_cast<size_t>(chain[k]);
                const JointLimit& l = skeleton.limits()[j];
                const glm::vec3 d(dq[3 * k], dq[3 * k + 1], dq[3 * k + 2]);
                if (l.limited) {
                    trial_euler[k] = glm::clamp(euler[k] + d, l.min_angles, l.max_angles);
                    trial[k] = glm::normalize(skeleton.rest_rotations()[j] * quat_from_euler_xyz(trial_euler[k]));
                } else {
                    // World rotation about p_k mapped into the parent frame: L' = exp(P^-1 omega) L.
                    const glm::quat parent_rot = matrix_rotation(k == 0 ? base_parent : model[k - 1]);
                    trial[k] = glm::normalize(quat_from_rotation_vector(glm::inverse(parent_rot) * d) * local[k]);
                    trial_euler[k] = euler[k];
                }
            }
            chain_fk(skeleton, chain, pose, trial, base_parent, trial_model);
            const IkError trial_err = ik_error(trial_model[n - 1], target);
            if (trial_err.combined < err.combined) {
                accepted = true;
                err = trial_err;
                for (size_t k = 0; k < n; ++k) {
                    local[k] = trial[k];
                    euler[k] = trial_euler[k];
                    model[k] = trial_model[k];
                }
                lambda = std::max(lambda * 0.5f, lambda_min);
            } else {
                lambda *= 4.0f;
            }
        }
        if (static_cast<size_t>(iterations) < error_per_iteration.size())
            error_per_iteration[static_cast<size_t>(iterations)] = err.combined;
        ++iterations;
    }
    for (size_t k = 0; k < n; ++k) {
        const auto j = static_cast<size_t>(chain[k]);
        pose.rotations[j] = local[k];
        pose.model[j] = model[k];
    }
    return make_ik_result(err, iterations, settings.tolerance);
}

bool DlsJob::Validate(std::vector<std::string>* errors) const {
    return validate_ik_inputs(skeleton, chain, pose, settings, errors);
}

void DlsJob::Run() const {
    const IkResult r = solve_dls(*skeleton, chain, pose, target, settings, error_per_iteration);
    if (result) *result = r;
}

}  // namespace aloha
