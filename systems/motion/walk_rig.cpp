#include "systems/motion/walk_rig.hpp"

#include "systems/motion/local_to_model.hpp"

#include <algorithm>
#include <cmath>

namespace aloha {

glm::quat matrix_rotation(const glm::mat4& m) {
    const glm::mat3 r(glm::normalize(glm::vec3(m[0])), glm::normalize(glm::vec3(m[1])), glm::normalize(glm::vec3(m[2])));
    return glm::normalize(glm::quat_cast(r));
}

namespace {

bool descends_from(const Skeleton& skeleton, int joint, int ancestor) {
    for (int j = skeleton.parents()[static_cast<size_t>(joint)]; j >= 0; j = skeleton.parents()[static_cast<size_t>(j)])
        if (j == ancestor) return true;
    return false;
}

}  // namespace

Result<WalkRig> resolve_walk_rig(const Skeleton& skeleton, const std::string& source) {
    auto map = map_humanoid(skeleton);
    if (!map.ok()) return map.error();
    return resolve_walk_rig(skeleton, map.value(), source);
}

Result<WalkRig> resolve_walk_rig(const Skeleton& skeleton, const HumanoidMap& map, const std::string& source) {
    WalkRig rig;
    const char* side_names[2] = {"Left", "Right"};
    const char* roles[4] = {"Hip", "Knee", "Ankle", "Toe"};
    rig.root = map.find("Hips");
    if (rig.root < 0) return make_error(source, "walk rig: no pelvis (canonical 'Hips') in the humanoid map");
    for (int s = 0; s < 2; ++s)
        for (int r = 0; r < 4; ++r) {
            const std::string canonical = std::string(side_names[s]) + roles[r];
            const int found = map.find(canonical);
            if (found < 0 && r < 3)
                return make_error(source, "walk rig: no joint for canonical '" + canonical + "' in the humanoid map" +
                                              (map.convention.empty() ? std::string(" (no naming convention matched)")
                                                                      : " (convention " + map.convention + ")"));
            int* slot[4] = {&rig.hip[s], &rig.knee[s], &rig.ankle[s], &rig.toe[s]};
            *slot[r] = found;
        }
    const auto parents = skeleton.parents();
    for (int s = 0; s < 2; ++s) {
        if (!descends_from(skeleton, rig.knee[s], rig.hip[s]))
            return make_error(source, std::string("walk rig: ") + side_names[s] + " knee '" + skeleton.names()[static_cast<size_t>(rig.knee[s])] + "' is not below the hip in the hierarchy");
        if (!descends_from(skeleton, rig.ankle[s], rig.knee[s]))
            return make_error(source, std::string("walk rig: ") + side_names[s] + " ankle '" + skeleton.names()[static_cast<size_t>(rig.ankle[s])] + "' is not below the knee in the hierarchy");
        if (rig.toe[s] >= 0 && !descends_from(skeleton, rig.toe[s], rig.ankle[s])) rig.toe[s] = -1;
    }
    const size_t n = static_cast<size_t>(skeleton.joint_count());
    std::vector<glm::mat4> model(n);
    local_to_model(parents.data(), skeleton.rest_translations().data(), skeleton.rest_rotations().data(),
                   skeleton.rest_scales().data(), nullptr, model.data(), n);
    rig.rest_model_rotations.resize(n);
    for (size_t j = 0; j < n; ++j) rig.rest_model_rotations[j] = matrix_rotation(model[j]);
    auto pos = [&](int j) { return glm::vec3(model[static_cast<size_t>(j)][3]); };
    float lowest = pos(rig.ankle[0]).y;
    for (int s = 0; s < 2; ++s) {
        lowest = std::min(lowest, pos(rig.ankle[s]).y);
        if (rig.toe[s] >= 0) lowest = std::min(lowest, pos(rig.toe[s]).y);
        rig.thigh[s] = glm::length(pos(rig.knee[s]) - pos(rig.hip[s]));
        rig.shin[s] = glm::length(pos(rig.ankle[s]) - pos(rig.knee[s]));
        rig.hip_offset[s] = pos(rig.hip[s]) - pos(rig.root);
        if (rig.thigh[s] < 1e-4f || rig.shin[s] < 1e-4f)
            return make_error(source, std::string("walk rig: ") + side_names[s] + " leg has a zero-length bone");
    }
    rig.ankle_height = 0.5f * (pos(rig.ankle[0]).y + pos(rig.ankle[1]).y) - lowest;
    rig.hip_drop = pos(rig.root).y - 0.5f * (pos(rig.hip[0]).y + pos(rig.hip[1]).y);
    rig.leg_length = 0.5f * (rig.thigh[0] + rig.shin[0] + rig.thigh[1] + rig.shin[1]);
    return rig;
}

TwoBoneSolution solve_two_bone(const glm::vec3& H, const glm::vec3& K, const glm::vec3& A, const glm::vec3& target,
                               const glm::vec3& pole) {
    const float la = glm::length(K - H), lb = glm::length(A - K);
    const glm::vec3 to = target - H;
    const float dist = glm::length(to);
    const glm::vec3 u = dist > 1e-6f ? to / dist : glm::vec3(0, -1, 0);
    // Keep a 1e-4 m margin from full extension/folding so the middle angle stays well defined.
    const float d = std::clamp(dist, std::abs(la - lb) + 1e-4f, la + lb - 1e-4f);
    const float cos_h = std::clamp((la * la + d * d - lb * lb) / (2.0f * la * d), -1.0f, 1.0f);
    const float sin_h = std::sqrt(std::max(0.0f, 1.0f - cos_h * cos_h));
    glm::vec3 p = pole - glm::dot(pole, u) * u;
    if (glm::dot(p, p) < 1e-10f) p = glm::vec3(0, 0, 1) - u.z * u;
    p = glm::normalize(p);
    return TwoBoneSolution{H + la * (cos_h * u + sin_h * p), H + u * d};
}

void stand_rig_on_rest_ground(WalkRig& rig, const Skeleton& skeleton) {
    const size_t n = static_cast<size_t>(skeleton.joint_count());
    std::vector<glm::mat4> model(n);
    local_to_model(skeleton.parents().data(), skeleton.rest_translations().data(), skeleton.rest_rotations().data(),
                   skeleton.rest_scales().data(), nullptr, model.data(), n);
    rig.ankle_height = 0.5f * (model[static_cast<size_t>(rig.ankle[0])][3].y + model[static_cast<size_t>(rig.ankle[1])][3].y);
}

float solve_leg_ik(const WalkRig& rig, const Skeleton& skeleton, int side, const glm::vec3& target,
                   const glm::vec3& pole, const PoseView& pose) {
    const size_t h = static_cast<size_t>(rig.hip[side]);
    const size_t k = static_cast<size_t>(rig.knee[side]);
    const size_t a = static_cast<size_t>(rig.ankle[side]);
    const glm::vec3 H(pose.model[h][3]), K(pose.model[k][3]), A(pose.model[a][3]);
    const TwoBoneSolution sol = solve_two_bone(H, K, A, target, pole);
    const glm::vec3 Kd = sol.middle, Td = sol.end;
    const float dist = glm::length(target - H), d = glm::length(Td - H);
    const glm::quat q1 = rotation_between(glm::normalize(K - H), glm::normalize(Kd - H));
    const glm::vec3 A1 = H + q1 * (A - H);
    const glm::quat q2 = rotation_between(glm::normalize(A1 - Kd), glm::normalize(Td - Kd));
    // World rotations of each joint's parent after the change: the hip's parent is not moved, the
    // knee's parent (the hip or a twist joint below it) turns by q1, the ankle's by q2 q1.
    auto model_rotation = [&](int j) { return j >= 0 ? matrix_rotation(pose.model[static_cast<size_t>(j)]) : glm::quat(1, 0, 0, 0); };
    const glm::quat hip_parent_w = model_rotation(skeleton.parents()[h]);
    const glm::quat knee_parent_w = glm::normalize(q1 * model_rotation(skeleton.parents()[k]));
    const glm::quat ankle_parent_w = glm::normalize(q2 * q1 * model_rotation(skeleton.parents()[a]));
    const glm::quat hip_w = glm::normalize(q1 * matrix_rotation(pose.model[h]));
    const glm::quat knee_w = glm::normalize(q2 * q1 * matrix_rotation(pose.model[k]));
    pose.rotations[h] = glm::normalize(glm::inverse(hip_parent_w) * hip_w);
    pose.rotations[k] = glm::normalize(glm::inverse(knee_parent_w) * knee_w);
    pose.rotations[a] = glm::normalize(glm::inverse(ankle_parent_w) * rig.rest_model_rotations[a]);
    return std::max(0.0f, dist - d);
}

}  // namespace aloha
