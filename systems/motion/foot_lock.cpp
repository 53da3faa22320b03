#include "systems/motion/foot_lock.hpp"

#include "engine/anim/rest_pose.hpp"
#include "systems/motion/local_to_model.hpp"
#include "systems/motion/motion_metrics.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace aloha {

namespace {

bool at_or_below(std::span<const int16_t> parents, int joint, int ancestor) {
    for (int j = joint; j >= 0; j = parents[static_cast<size_t>(j)])
        if (j == ancestor) return true;
    return false;
}

glm::vec3 horizontal(glm::vec3 v) { return glm::vec3(v.x, 0.0f, v.z); }

// M p = centre + q (p - centre), applied to a model matrix (rotation and position; scale kept).
glm::mat4 turn_about(const glm::vec3& centre, const glm::quat& q) {
    return glm::translate(glm::mat4(1.0f), centre) * glm::mat4_cast(q) * glm::translate(glm::mat4(1.0f), -centre);
}

}  // namespace

FootLock::FootLock(const Skeleton& skeleton, const WalkRig& rig, size_t capacity, FootLockParams params)
    : rig_(rig), params_(params) {
    const auto parents = skeleton.parents();
    for (int side = 0; side < 2; ++side) {
        Leg& leg = legs_[static_cast<size_t>(side)];
        for (int j = 0; j < skeleton.joint_count(); ++j) {
            if (at_or_below(parents, j, rig.ankle[static_cast<size_t>(side)])) leg.foot.push_back(j);
            else if (at_or_below(parents, j, rig.knee[static_cast<size_t>(side)])) leg.shin.push_back(j);
            else if (at_or_below(parents, j, rig.hip[static_cast<size_t>(side)])) leg.thigh.push_back(j);
        }
    }
    const size_t n = static_cast<size_t>(skeleton.joint_count());
    std::vector<glm::mat4> model(n);
    local_to_model(parents.data(), skeleton.rest_translations().data(), skeleton.rest_rotations().data(),
                   skeleton.rest_scales().data(), nullptr, model.data(), n);
    for (size_t side = 0; side < 2; ++side) {
        // The sole points under ankle and toe (as the skate meter takes them): the foot rolls about
        // them, not about its joints.
        const int joints[2] = {rig.ankle[side], rig.toe[side] >= 0 ? rig.toe[side] : rig.ankle[side]};
        const std::vector<glm::vec3> soles = sole_offsets(skeleton, joints);
        heel_sole_[side] = soles[0], toe_sole_[side] = soles[1];
        // The heel the foot rolls over at touchdown: on the ground behind the ankle (as the generated
        // gaits place it, library/gait_clip.hpp foot_contacts), in the ankle's frame.
        const glm::vec3 ankle(model[static_cast<size_t>(rig.ankle[side])][3]);
        const glm::vec3 ball = rig.toe[side] >= 0 ? glm::vec3(model[static_cast<size_t>(rig.toe[side])][3]) - ankle
                                                  : glm::vec3(0.0f, -rig.ankle_height, 0.18f * rig.leg_length);
        const glm::vec3 roll = ankle + glm::vec3(0.0f, -rig.ankle_height, -0.35f * std::max(0.05f * rig.leg_length, ball.z));
        roll_heel_[side] = glm::vec3(glm::inverse(model[static_cast<size_t>(rig.ankle[side])]) * glm::vec4(roll, 1.0f));
        rest_heel_[side] = glm::vec3(model[static_cast<size_t>(joints[0])] * glm::vec4(soles[0], 1.0f)).y;
        rest_toe_[side] = glm::vec3(model[static_cast<size_t>(joints[1])] * glm::vec4(soles[1], 1.0f)).y;
    }
    offset_.assign(2 * capacity, glm::vec3(0.0f));
    prev_heel_.assign(2 * capacity, glm::vec3(0.0f));
    prev_toe_.assign(2 * capacity, glm::vec3(0.0f));
    prev_roll_.assign(2 * capacity, glm::vec3(0.0f));
    low_heel_.assign(2 * capacity, 0.0f);
    low_toe_.assign(2 * capacity, 0.0f);
    locked_.assign(2 * capacity, 0);
    primed_.assign(capacity, 0);
}

void FootLock::reset(uint32_t c) {
    primed_[c] = 0;
    for (size_t i = 2 * c; i < 2 * c + 2; ++i) offset_[i] = glm::vec3(0.0f), locked_[i] = 0;
}

void FootLock::rebase(uint32_t c) {
    for (size_t i = 2 * c; i < 2 * c + 2; ++i) {
        prev_heel_[i] += offset_[i], prev_toe_[i] += offset_[i], prev_roll_[i] += offset_[i];
        offset_[i] = glm::vec3(0.0f);
    }
}

void FootLock::apply(uint32_t c, float dt, const Transform& placement, std::span<glm::mat4> model, bool engage) {
    const float s = placement.scale;
    const glm::quat inv_rot = glm::inverse(placement.rotation);
    auto to_world = [&](const glm::vec3& m) { return placement.position + placement.rotation * (m * s); };
    const float contact = params_.contact_height / s;  // model units
    const float rise = params_.ground_rise * dt / s;
    const float floor = params_.ground_floor / s;
    const float decay = params_.release_time > 0.0f ? std::exp(-dt / params_.release_time) : 0.0f;
    const float max_offset = params_.max_offset * rig_.leg_length * s;
    for (size_t side = 0; side < 2; ++side) {
        const size_t i = 2 * c + side;
        const glm::mat4& ankle = model[static_cast<size_t>(rig_.ankle[side])];
        const glm::mat4& toe = rig_.toe[side] >= 0 ? model[static_cast<size_t>(rig_.toe[side])] : ankle;
        const glm::vec3 heel_m(ankle * glm::vec4(heel_sole_[side], 1.0f)), toe_m(toe * glm::vec4(toe_sole_[side], 1.0f));
        const glm::vec3 roll_m(ankle * glm::vec4(roll_heel_[side], 1.0f));
        const glm::vec3 roll_w = to_world(roll_m);
        const glm::vec3 heel_w = to_world(heel_m), toe_w = to_world(toe_m);
        if (!primed_[c]) {
            prev_heel_[i] = heel_w, prev_toe_[i] = toe_w, prev_roll_[i] = roll_w;
            low_heel_[i] = std::min(rest_heel_[side], heel_m.y);
            low_toe_[i] = std::min(rest_toe_[side], toe_m.y);
            offset_[i] = glm::vec3(0.0f), locked_[i] = 0;
        }
        // The lowest recent height, never more than the floor below the rest sole (a foot that a blend
        // dips under the ground must not make the ground seem lower for the steps after it).
        low_heel_[i] = std::max(std::min(low_heel_[i] + rise, heel_m.y), rest_heel_[side] - floor);
        low_toe_[i] = std::max(std::min(low_toe_[i] + rise, toe_m.y), rest_toe_[side] - floor);
        const bool heel_down = heel_m.y - low_heel_[i] < contact;
        const bool toe_down = toe_m.y - low_toe_[i] < contact;
        // The point the foot stands on: the lower of heel and toe (over its own lowest), so the foot
        // rolls over its heel at touchdown and over its toe at heel-off.
        const bool on_heel = heel_m.y - low_heel_[i] <= toe_m.y - low_toe_[i];
        // On the heel, the foot stands on the lower of the point under the ankle and the heel it rolls over.
        const glm::vec3 heel_moved = roll_m.y < heel_m.y ? roll_w - prev_roll_[i] : heel_w - prev_heel_[i];
        const glm::vec3 moved = horizontal(on_heel ? heel_moved : toe_w - prev_toe_[i]);
        // Let go at lift-off, and of a foot the pose swings fast (a low swing, a quick turn): held, it
        // would be dragged to the offset limit and slide back on the ground.
        if (locked_[i] && ((!heel_down && !toe_down) || glm::length(moved) > params_.release_speed * dt)) locked_[i] = 0;
        if (!locked_[i] && engage && (heel_down || toe_down) && glm::length(moved) < params_.engage_speed * dt)
            locked_[i] = 1;
        if (locked_[i]) offset_[i] -= moved;  // what the pose moved the contact point, undone
        // Never past the reach margin: a foot held that far is let go where the margin ends (whatever the
        // time since the last apply: a held foot must not pull the leg towards a spot the body has left).
        if (const float length = glm::length(offset_[i]); length > max_offset) {
            locked_[i] = 0;
            offset_[i] *= max_offset / length;
        }
        // A foot let go decays its offset in the air only: on the ground it keeps the offset and moves as
        // the pose moves it (a decay there would slide it slowly, the very skate the lock is for).
        if (!locked_[i] && !heel_down && !toe_down) offset_[i] *= decay;
        prev_heel_[i] = heel_w, prev_toe_[i] = toe_w, prev_roll_[i] = roll_w;
        if (glm::dot(offset_[i], offset_[i]) > 1e-12f)
            move_leg(static_cast<int>(side), glm::vec3(ankle[3]) + (inv_rot * offset_[i]) / s, model);
    }
    primed_[c] = 1;
}

void FootLock::move_leg(int side, const glm::vec3& target, std::span<glm::mat4> model) const {
    const Leg& leg = legs_[static_cast<size_t>(side)];
    const auto at = [&](int j) { return glm::vec3(model[static_cast<size_t>(j)][3]); };
    const glm::vec3 H = at(rig_.hip[static_cast<size_t>(side)]), K = at(rig_.knee[static_cast<size_t>(side)]),
                    A = at(rig_.ankle[static_cast<size_t>(side)]);
    // The knee keeps bending the way it bends now (forward when the leg is straight).
    glm::vec3 pole = K - 0.5f * (H + A);
    if (glm::dot(pole, pole) < 1e-8f) pole = glm::vec3(0, 0, 1);
    const TwoBoneSolution sol = solve_two_bone(H, K, A, target, pole);
    const glm::quat q1 = rotation_between(glm::normalize(K - H), glm::normalize(sol.middle - H));
    const glm::vec3 A1 = H + q1 * (A - H);
    const glm::quat q2 = rotation_between(glm::normalize(A1 - sol.middle), glm::normalize(sol.end - sol.middle));
    const glm::mat4 thigh = turn_about(H, q1);
    const glm::mat4 shin = turn_about(sol.middle, q2) * thigh;
    // The foot moves without turning: it stays as the pose had it, only carried to the held spot.
    const glm::mat4 foot = glm::translate(glm::mat4(1.0f), sol.end - A);
    for (const int j : leg.thigh) model[static_cast<size_t>(j)] = thigh * model[static_cast<size_t>(j)];
    for (const int j : leg.shin) model[static_cast<size_t>(j)] = shin * model[static_cast<size_t>(j)];
    for (const int j : leg.foot) model[static_cast<size_t>(j)] = foot * model[static_cast<size_t>(j)];
}

}  // namespace aloha
