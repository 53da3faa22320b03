#include "systems/motion/library/gait_clip.hpp"

#include "systems/motion/library/posing.hpp"

#include <algorithm>
#include <cmath>

namespace aloha {

namespace {

constexpr float kTwoPi = 6.28318530718f;

// Fractions of stance: heel rocker ends at s1 (foot flat), heel rises at s2 (forefoot rocker).
struct Rockers {
    float s1, s2;
};

// Ankle position (clip space) and foot pitch (toes up > 0) of one foot at time t.
struct FootPlan {
    glm::vec3 ankle;
    float pitch;
    float toe_pitch;  // absolute pitch of the toe segment
};

class GaitPlanner {
public:
    // `under_hip`: the fraction of stance at which the flat foot's ankle passes under its hip.
    GaitPlanner(const GaitCycle& g, const WalkRig& rig, const PoseBuilder& rest, float under_hip) : g_(g) {
        rockers_ = g.running ? Rockers{0.08f, 0.35f} : Rockers{0.12f, 0.5f};
        const float t_flatmid = under_hip * g.duty * g.period;
        for (int k = 0; k < 2; ++k) {
            contacts_[k] = foot_contacts(rig, rest, k);
            const float t0 = k == 0 ? 0.0f : 0.5f * g.period;
            flat_[k] = glm::vec3(rig.hip_offset[k].x, rig.ankle_height, g.speed * (t0 + t_flatmid) + rig.hip_offset[k].z);
        }
    }

    FootPlan foot(int side, float t) const {
        const float t0 = side == 0 ? 0.0f : 0.5f * g_.period;
        const float tau = (t - t0) / g_.period;
        const float cycle = std::floor(tau);
        const float phi = tau - cycle;
        if (phi < g_.duty) return stance(side, phi / g_.duty, cycle);
        const float sigma = (phi - g_.duty) / (1.0f - g_.duty);
        const FootPlan lo = stance(side, 1.0f, cycle), td = stance(side, 0.0f, cycle + 1.0f);
        const float u = smootherstep(std::clamp((sigma - 0.12f) / 0.76f, 0.0f, 1.0f));
        FootPlan out;
        out.ankle = glm::mix(lo.ankle, td.ankle, u);
        out.ankle.y += g_.clearance * std::sin(3.14159265f * sigma);
        out.pitch = glm::mix(lo.pitch, td.pitch, u);
        out.toe_pitch = glm::mix(lo.toe_pitch, out.pitch, smoothstep(std::min(1.0f, sigma / 0.3f)));
        return out;
    }

private:
    FootPlan stance(int side, float s, float cycle) const {
        const glm::vec3 flat = flat_[side] + glm::vec3(0.0f, 0.0f, cycle * g_.stride);
        FootPlan out;
        if (s < rockers_.s1) {  // heel rocker: rotate about the heel contact
            out.pitch = g_.heel_strike * (1.0f - smoothstep(s / rockers_.s1));
            const glm::vec3 pivot = flat + contacts_[side].heel;
            out.ankle = pivot - foot_pitch_rotation(out.pitch) * contacts_[side].heel;
            out.toe_pitch = out.pitch;
        } else if (s <= rockers_.s2) {  // foot flat
            out.pitch = 0.0f;
            out.ankle = flat;
            out.toe_pitch = 0.0f;
        } else {  // forefoot rocker: rotate about the ball, the toes stay flat
            out.pitch = -g_.toe_off * smoothstep((s - rockers_.s2) / (1.0f - rockers_.s2));
            const glm::vec3 pivot = flat + contacts_[side].ball;
            out.ankle = pivot - foot_pitch_rotation(out.pitch) * contacts_[side].ball;
            out.toe_pitch = 0.0f;
        }
        return out;
    }

    GaitCycle g_;
    Rockers rockers_{};
    FootContacts contacts_[2];
    glm::vec3 flat_[2];
};

// Pelvis placement and rotations of the gait at phase phi (0 = left heel strike).
struct BodyPlan {
    glm::vec3 root_offset;  // sway and bob (x, y), added to the travelling root
    glm::quat pelvis;       // model delta of the root
    glm::quat thorax;       // model delta of the chest
    float arm[2];           // shoulder flexion, forward > 0
};

BodyPlan body_at(const GaitCycle& g, float phi) {
    BodyPlan b;
    const float mid = 0.5f * g.duty;  // left mid-stance
    const float c1 = std::cos(kTwoPi * (phi - mid));
    const float c2 = std::cos(2.0f * kTwoPi * (phi - mid));
    b.root_offset = glm::vec3(g.sway * c1, (g.running ? -g.bob : g.bob) * c2, 0.0f);
    const float yaw = -g.pelvis_yaw * std::cos(kTwoPi * phi);
    const float roll = g.pelvis_roll * c1;
    b.pelvis = glm::angleAxis(yaw, glm::vec3(0, 1, 0)) * glm::angleAxis(roll, glm::vec3(0, 0, 1)) *
               glm::angleAxis(0.3f * g.lean, glm::vec3(1, 0, 0));
    b.thorax = glm::angleAxis(-0.6f * yaw, glm::vec3(0, 1, 0)) * glm::angleAxis(g.lean, glm::vec3(1, 0, 0));
    b.arm[0] = g.arm_swing * std::cos(kTwoPi * (phi - 0.5f));  // left arm forward with the right leg
    b.arm[1] = g.arm_swing * std::cos(kTwoPi * phi);
    return b;
}

}  // namespace

FootContacts foot_contacts(const WalkRig& rig, const PoseBuilder& rest, int side) {
    FootContacts c;
    const glm::vec3 ankle = rest.rest_position(rig.ankle[side]);
    // The forefoot rolls about the ball joint (metatarsophalangeal) while the toes lie flat; a rig
    // without a toe joint rolls about a ground point a typical ball distance ahead of the ankle.
    c.ball = rig.toe[side] >= 0 ? rest.rest_position(rig.toe[side]) - ankle
                                : glm::vec3(0.0f, -rig.ankle_height, 0.18f * rig.leg_length);
    const float forward = std::max(0.05f * rig.leg_length, c.ball.z);
    c.heel = glm::vec3(0.0f, -rig.ankle_height, -0.35f * forward);
    return c;
}

GaitClip make_gait_clip(const Skeleton& skeleton, const WalkRig& rig, const HumanoidJoints& joints, float speed,
                        const std::string& name) {
    PoseBuilder pose(skeleton);
    const float hip_height = rig.ankle_height + rig.leg_length;
    GaitClip out;
    out.cycle = gait_cycle(speed, hip_height);
    const GaitCycle& g = out.cycle;
    const glm::vec3 rest_root = pose.rest_position(rig.root);
    const int keys = std::max(8, static_cast<int>(std::lround(g.period * kGeneratedKeyRate)));

    // The highest root that keeps every planned ankle within reach (knees never lock straight) for a
    // foot placement: where in stance the ankle passes under the hip.
    auto highest_root = [&](const GaitPlanner& plan) {
        float height = rest_root.y;
        for (int i = 0; i <= 4 * keys; ++i) {
            const float t = g.period * static_cast<float>(i) / static_cast<float>(4 * keys);
            const BodyPlan b = body_at(g, t / g.period);
            const glm::vec3 root(b.root_offset.x, b.root_offset.y, g.speed * t);
            for (int k = 0; k < 2; ++k) {
                const glm::vec3 hip = root + b.pelvis * rig.hip_offset[k];
                const glm::vec3 ankle = plan.foot(k, t).ankle;
                const float reach = 0.985f * (rig.thigh[k] + rig.shin[k]);
                const glm::vec2 d(ankle.x - hip.x, ankle.z - hip.z);
                const float vertical = std::sqrt(std::max(reach * reach - glm::dot(d, d), 0.0f));
                height = std::min(height, ankle.y + vertical - (hip.y - root.y) - b.root_offset.y);
            }
        }
        return height;
    };
    // Place the feet so the hips can stand as tall as the stride allows: the stance is balanced
    // between the reach at heel strike and at toe-off.
    float under_hip = 0.3f, root_height = -1e9f;
    for (float f = 0.1f; f <= 0.9f; f += 0.01f) {
        const float h = highest_root(GaitPlanner(g, rig, pose, f));
        if (h > root_height) root_height = h, under_hip = f;
    }
    const GaitPlanner planner(g, rig, pose, under_hip);

    ClipRecorder rec(skeleton, name);
    for (int i = 0; i <= keys; ++i) {
        const float t = g.period * static_cast<float>(i) / static_cast<float>(keys);
        const BodyPlan b = body_at(g, t / g.period);
        pose.reset();
        pose.translations[static_cast<size_t>(rig.root)] =
            glm::vec3(b.root_offset.x, root_height + b.root_offset.y, g.speed * t);
        pose.set_model_rotation(rig.root, b.pelvis * pose.rest_model_rotation(rig.root));
        pose_trunk(pose, joints, b.pelvis, b.thorax);
        for (int k = 0; k < 2; ++k) {
            const float abduction = (g.running ? 12.0f : 8.0f) * 0.0174533f;
            const float flex = g.elbow + 0.35f * std::max(0.0f, b.arm[k]);
            pose_arm(pose, joints, k, arm_swing(b.thorax, k, b.arm[k], abduction), flex);
            const FootPlan f = planner.foot(k, t);
            plant_leg(pose, rig, k, f.ankle, f.pitch, f.toe_pitch, b.pelvis * glm::vec3(0, 0, 1));
        }
        rec.add_key(t, pose);
    }
    out.clip = std::move(rec).finish();
    return out;
}

}  // namespace aloha
