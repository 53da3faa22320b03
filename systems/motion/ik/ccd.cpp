#include "systems/motion/ik/ccd.hpp"

#include "systems/motion/ik/chain_fk.hpp"
#include "systems/motion/ik/ik_chain.hpp"
#include "systems/motion/ik/joint_limits.hpp"

#include <cassert>
#include <cmath>

namespace aloha {

using namespace ik;  // NOLINT: IK helper namespace

namespace {

// Rotation R (world) maximising sum_i w_i b_i . (R a_i): Wahba's problem, solved by the iterative
// method of Mueller et al. 2016 ("A robust method to extract the rotational part of deformations")
// warm-started at the shortest arc of the first (position) pair.
glm::quat best_rotation(const glm::vec3* a, const glm::vec3* b, int count) {
    glm::quat r = shortest_arc(a[0], b[0]);
    for (int it = 0; it < 16; ++it) {
        glm::vec3 num(0.0f);
        float den = 0.0f;
        for (int i = 0; i < count; ++i) {
            const glm::vec3 ra = r * a[i];
            num += glm::cross(ra, b[i]);
            den += glm::dot(ra, b[i]);
        }
        const glm::vec3 omega = num / (std::abs(den) + 1e-9f);
        const float angle = glm::length(omega);
        if (angle < 1e-7f) break;
        r = glm::normalize(glm::angleAxis(angle, omega / angle) * r);
    }
    return r;
}

}  // namespace

IkResult solve_ccd(const Skeleton& skeleton, std::span<const int> chain, PoseView pose, const IkTarget& target,
                   const IkSettings& settings, std::span<float> error_per_iteration) {
    assert(!chain.empty() && chain.size() <= static_cast<size_t>(kMaxIkChain));
    const size_t n = chain.size();
    const auto eff = static_cast<size_t>(chain[n - 1]);
    const glm::quat target_rot = glm::normalize(target.orientation);
    const glm::mat3 target_axes = glm::mat3_cast(target_rot);
    const float w = target.orientation_weight;

    IkError err = ik_error(pose.model[eff], target);
    int iterations = 0;
    while (err.combined > settings.tolerance && iterations < settings.max_iterations) {
        for (size_t k = n; k-- > 0;) {
            if (k == n - 1 && !target.use_orientation) continue;  // rotating the tip cannot move P_c
            const auto j = static_cast<size_t>(chain[k]);
            const glm::vec3 pj = matrix_position(pose.model[j]);
            const glm::vec3 pe = matrix_position(pose.model[eff]);
            glm::vec3 a[4];
            glm::vec3 b[4];
            a[0] = pe - pj;
            b[0] = target.position - pj;
            int count = 1;
            if (target.use_orientation) {
                const glm::mat3 cur = glm::mat3_cast(matrix_rotation(pose.model[eff]));
                for (int c = 0; c < 3; ++c) {
                    a[count] = w * cur[c];  // u_ic scaled to metres
                    b[count] = w * target_axes[c];
                    ++count;
                }
            }
            const glm::quat parent_rot = matrix_rotation(parent_model(skeleton, pose.model, chain[k]));
            const JointLimit& limit = skeleton.limits()[j];
            const glm::quat rest = skeleton.rest_rotations()[j];
            glm::quat local;
            if (!limit.limited) {
                // Free ball joint: best 3-D rotation. W_j' = delta * W_j, W_j = P * L  =>  L' = P^-1 delta P L.
                const glm::quat delta = best_rotation(a, b, count);
                local = glm::normalize(glm::inverse(parent_rot) * delta * parent_rot * pose.rotations[j]);
            } else {
                // Limited joint: one Euler angle at a time (innermost first), each the exact 1-D
                // minimiser about its axis clamped to [min, max], as in revolute-joint CCD.
                glm::vec3 e = relative_euler_xyz(rest, pose.rotations[j]);
                for (int axis_index = 3; axis_index-- > 0;) {
                    glm::vec3 axes[3];
                    euler_axes(rest, e, axes);
                    const glm::vec3 u = glm::normalize(parent_rot * axes[axis_index]);
                    const float theta = best_angle_about(u, a, b, count);
                    const float next = glm::clamp(e[axis_index] + theta, limit.min_angles[axis_index],
                                                  limit.max_angles[axis_index]);
                    const glm::quat turn = glm::angleAxis(next - e[axis_index], u);
                    for (int i = 0; i < count; ++i) a[i] = turn * a[i];
                    e[axis_index] = next;
                }
                local = glm::normalize(rest * quat_from_euler_xyz(e));
            }
            local = clamp_to_limit(limit, rest, local);
            pose.rotations[j] = local;
            update_chain_model(skeleton, chain, pose, k);
        }
        err = ik_error(pose.model[eff], target);
        if (static_cast<size_t>(iterations) < error_per_iteration.size())
            error_per_iteration[static_cast<size_t>(iterations)] = err.combined;
        ++iterations;
    }
    return make_ik_result(err, iterations, settings.tolerance);
}

bool ik::validate_ik_inputs(const Skeleton* skeleton, std::span<const int> chain, const PoseView& pose,
                        const IkSettings& settings, std::vector<std::string>* errors) {
    bool ok = true;
    auto fail = [&](std::string msg) {
        ok = false;
        if (errors) errors->push_back(std::move(msg));
    };
    if (!skeleton) {
        fail("skeleton is null");
        return false;
    }
    const auto n = static_cast<size_t>(skeleton->joint_count());
    if (chain.empty()) fail("chain is empty");
    if (chain.size() > static_cast<size_t>(kMaxIkChain))
        fail("chain has " + std::to_string(chain.size()) + " joints; at most " + std::to_string(kMaxIkChain));
    for (size_t k = 0; k < chain.size(); ++k) {
        if (chain[k] < 0 || static_cast<size_t>(chain[k]) >= n) {
            fail("chain[" + std::to_string(k) + "] = " + std::to_string(chain[k]) + " is not a joint index");
        } else if (k > 0 && skeleton->parents()[static_cast<size_t>(chain[k])] != chain[k - 1]) {
            fail("chain[" + std::to_string(k) + "] is not a child of chain[" + std::to_string(k - 1) + "]");
        }
    }
    if (pose.translations.size() != n) fail("pose.translations size differs from the joint count");
    if (pose.rotations.size() != n) fail("pose.rotations size differs from the joint count");
    if (pose.scales.size() != n) fail("pose.scales size differs from the joint count");
    if (pose.model.size() != n) fail("pose.model size differs from the joint count");
    if (settings.max_iterations < 0) fail("settings.max_iterations is negative");
    if (!(settings.tolerance >= 0.0f)) fail("settings.tolerance is negative or NaN");
    if (!(settings.damping >= 0.0f)) fail("settings.damping is negative or NaN");
    return ok;
}

bool CcdJob::Validate(std::vector<std::string>* errors) const {
    return validate_ik_inputs(skeleton, chain, pose, settings, errors);
}

void CcdJob::Run() const {
    const IkResult r = solve_ccd(*skeleton, chain, pose, target, settings, error_per_iteration);
    if (result) *result = r;
}

}  // namespace aloha
