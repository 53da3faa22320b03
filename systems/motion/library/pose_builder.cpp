#include "systems/motion/library/pose_builder.hpp"

#include "systems/motion/local_to_model.hpp"
#include "systems/motion/walk_rig.hpp"

#include <algorithm>
#include <cmath>

namespace aloha {

HumanoidJoints find_humanoid_joints(const Skeleton& s) {
    HumanoidJoints j;
    for (int i = 0; i < s.joint_count(); ++i)
        if (s.parents()[static_cast<size_t>(i)] < 0) { j.root = i; break; }
    auto mapped = map_humanoid(s);  // cannot fail without an explicit map
    if (!mapped.ok()) return j;
    const HumanoidMap& map = mapped.value();
    if (map.find("Hips") >= 0) j.root = map.find("Hips");
    const char* spine[3] = {"lowerback", "Chest", "Chest2"};
    for (int i = 0; i < 3; ++i) j.spine[i] = map.find(spine[i]);
    j.neck[0] = map.find("lowerneck");
    j.neck[1] = map.find("Neck");
    j.head = map.find("Head");
    const char* side[2] = {"Left", "Right"};
    for (int k = 0; k < 2; ++k) {
        const std::string p = side[k];
        j.collar[k] = map.find(p + "Collar");
        j.shoulder[k] = map.find(p + "Shoulder");
        j.elbow[k] = map.find(p + "Elbow");
        j.wrist[k] = map.find(p + "Wrist");
    }
    return j;
}

PoseBuilder::PoseBuilder(const Skeleton& skeleton) : skeleton_(&skeleton) {
    const size_t n = static_cast<size_t>(skeleton.joint_count());
    model_.resize(n);
    scales_.assign(skeleton.rest_scales().begin(), skeleton.rest_scales().end());
    reset();
    rest_model_.resize(n);
    rest_pos_.resize(n);
    for (size_t j = 0; j < n; ++j) {
        rest_model_[j] = matrix_rotation(model_[j]);
        rest_pos_[j] = glm::vec3(model_[j][3]);
    }
}

void PoseBuilder::reset() {
    translations.assign(skeleton_->rest_translations().begin(), skeleton_->rest_translations().end());
    rotations.assign(skeleton_->rest_rotations().begin(), skeleton_->rest_rotations().end());
    update();
}

void PoseBuilder::update() {
    local_to_model(skeleton_->parents().data(), translations.data(), rotations.data(), scales_.data(), nullptr,
                   model_.data(), model_.size());
}

glm::quat PoseBuilder::model_rotation(int j) const { return matrix_rotation(model_[static_cast<size_t>(j)]); }

void PoseBuilder::set_model_rotation(int j, const glm::quat& model_rotation) {
    const int p = skeleton_->parents()[static_cast<size_t>(j)];
    const glm::quat parent = p >= 0 ? matrix_rotation(model_[static_cast<size_t>(p)]) : glm::quat(1, 0, 0, 0);
    rotations[static_cast<size_t>(j)] = glm::normalize(glm::inverse(parent) * model_rotation);
    update();
}

void PoseBuilder::two_bone(int upper, int middle, int end, const glm::vec3& target, const glm::vec3& pole) {
    const glm::vec3 H = model_position(upper), K = model_position(middle), A = model_position(end);
    const TwoBoneSolution sol = solve_two_bone(H, K, A, target, pole);
    const glm::vec3 Kd = sol.middle;
    const glm::quat q1 = rotation_between(glm::normalize(K - H), glm::normalize(Kd - H));
    set_model_rotation(upper, glm::normalize(q1 * model_rotation(upper)));
    const glm::vec3 A1 = model_position(end), K1 = model_position(middle);
    const glm::quat q2 = rotation_between(glm::normalize(A1 - K1), glm::normalize(sol.end - K1));
    set_model_rotation(middle, glm::normalize(q2 * model_rotation(middle)));
}

ClipRecorder::ClipRecorder(const Skeleton& skeleton, std::string name) {
    clip_.name = std::move(name);
    clip_.tracks.resize(static_cast<size_t>(skeleton.joint_count()));
    for (int i = 0; i < skeleton.joint_count(); ++i)
        if (skeleton.parents()[static_cast<size_t>(i)] < 0) { root_ = i; break; }
}

void ClipRecorder::add_key(float time, const PoseBuilder& pose) {
    for (size_t j = 0; j < clip_.tracks.size(); ++j) {
        RawJointTracks& t = clip_.tracks[j];
        t.rotations.times.push_back(time);
        t.rotations.values.push_back(pose.rotations[j]);
        if (static_cast<int>(j) == root_) {
            t.translations.times.push_back(time);
            t.translations.values.push_back(pose.translations[j]);
        }
    }
    clip_.duration = time;
}

RawAnimation ClipRecorder::finish() && { return std::move(clip_); }

}  // namespace aloha
