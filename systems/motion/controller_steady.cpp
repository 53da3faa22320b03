// Phase 1's steady step: a character playing a looping clip, walking straight from a clip while facing its
// way, or reaching / looking, with nothing queued, fading, overlaid or inertialized, advances from its
// 80-byte Hot record and its element's rows alone (the ~460-byte Character stays out of the cache). The
// result is step_active's, bit for bit: the same operations on the same values in the same order.
#include "systems/motion/controller.hpp"

#include <cstring>
#include <algorithm>

namespace aloha {

namespace {
// True when `a` and `b` hold the same bits (what turn()'s fixed-point test compares).
template <class T>
bool same_bits(const T& a, const T& b) { return std::memcmp(&a, &b, sizeof(T)) == 0; }
}  // namespace

void MotionController::enter_steady(uint32_t c, const Character& ch, const Transform& placement) {
    Hot& h = hot_[c];
    h.steady = Steady::None;
    const Channel& cur = ch.cur;
    const MotionRequest& r = cur.req;
    // Nothing switches, fades, overlays or settles at the next step, and no clock ends it.
    if (cur.done || ch.count != 0 || ch.fade_left > 0.0f || ch.overlay.on || ch.inertial_slot >= 0 || !(r.duration < 0.0f) ||
        h.last_anim < 0 || cur.path_cursor != 0)
        return;
    Steady s = Steady::None;
    if (r.kind == RequestKind::PlayClip && r.loop) {
        // A clip that jumps where it wraps is inertialized there (step_active): not a steady request.
        const AnimationClip* clip = clips_->find_looped(r.clip);
        if (clip && !clip->ends_meet()) return;
        // advance(): the clock only (a looping clip never ends), and the root motion of one whose root moves.
        s = root_moving_clip(cur) ? Steady::RootClip : Steady::Clip;
        h.clip = r.clip;
        h.travelling = cur.travelling;
    } else if (r.kind == RequestKind::Walk && r.path == 0xFFFF && ch.has_walk_method &&
               ch.walk_method == WalkMethod::ClipPlayback && cur.walk_clip >= 0) {
        // Heading along its target (not along its own facing, which a turn would change), already facing
        // it: turn() returns the rotation unchanged while it and the turn step stay as they are.
        if (!(glm::length(glm::vec3(r.target.x, 0.0f, r.target.z)) > 1e-6f)) return;
        const glm::vec3 dir = straight_direction(r, placement.rotation);
        if (cur.faced_max_turn < 0.0f || !same_bits(cur.faced, placement.rotation) || !same_bits(cur.faced_dir, dir)) return;
        s = Steady::WalkClip;
        h.velocity = dir * std::max(r.speed, 0.0f);
        h.faced = cur.faced;
        h.faced_max_turn = cur.faced_max_turn;
    } else if (r.kind == RequestKind::Reach || r.kind == RequestKind::LookAt) {
        s = Steady::Hold;  // advance(): the request's seconds only
    } else {
        return;
    }
    if (s != Steady::Hold) h.rate = clock_rate(cur);
    h.time = cur.time;
    h.request_time = cur.request_time;
    h.phase = cur.walk.phase;
    h.kind = r.kind;
    h.steady = s;
}

bool MotionController::step_steady(const Walker& w, float dt, std::span<MotionState> states, StepBlock& out) {
    const uint32_t c = w.character, e = w.element;
    Hot& h = hot_[c];
    if (h.steady == Steady::None) return false;
    const AnimLod& lod = lods_[e];
    Transform& x = transforms_[e];
    // A level change (walk method, interval, IK) or a rotation the host changed takes the full step.
    if (anim_signature(lod) != h.last_anim) return false;
    if (h.steady == Steady::WalkClip && !(same_bits(x.rotation, h.faced) && same_bits(kTurnRate * dt, h.faced_max_turn)))
        return false;
    MotionState& st = states[e];

    // advance(): seconds, the clip clock, root motion (turn() leaves the rotation as it is; a root-moving clip's).
    h.request_time += dt;
    const float before = h.time;
    if (h.steady != Steady::Hold) h.time += dt * h.rate;
    if (h.steady == Steady::WalkClip) {
        x.position += h.velocity * dt;
        velocities_[e].linear = h.velocity;
    } else if (h.steady == Steady::RootClip) {
        KinematicWalkState walk;
        walk.phase = h.phase;
        move_by_root(*clips_->find_looped(h.clip), before, h.time, true, dt, x, &velocities_[e], walk, h.travelling);
        h.phase = walk.phase;
    }

    const Schedule sched = tick(c, e, h, st, lod, dt);
    const PoseUse use = sched.use;
    bool due = sched.on_phase || (h.stale && use != PoseUse::Unseen) || (h.keys_stale && use == PoseUse::EveryFrame);
    const bool clip = h.steady != Steady::Hold;  // clip_driven(): its pose is a function of the clip clock
    if (due && use == PoseUse::Unseen && clip) {
        leave_stale(c, h);
        due = false;
    }
    if (due) {
        mark_due(c, e, h, st, sched, sched.interval > 1 && clip, false, dt, out);  // pose_one takes the clocks from h
    } else if (h.keys_slot >= 0 && !h.stale && !h.keys_stale && use == PoseUse::EveryFrame) {
        out.between.push_back(Due{c, e, h.since_posed, false});
    }

    st.active = h.kind;
    st.time = h.time;
    st.phase = h.phase;
    st.request_time = h.request_time;
    st.pose_slot = c;
    st.path_cursor = 0;
    st.at_rest = 0;
    st.travelling = h.steady == Steady::RootClip ? h.travelling : 0;
    return true;
}

}  // namespace aloha
