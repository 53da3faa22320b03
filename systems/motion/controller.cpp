#include "systems/motion/controller.hpp"

#include "systems/motion/blend.hpp"
#include "systems/motion/local_to_model.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstring>
#include <string>
#include <utility>

namespace aloha {

namespace {
bool is_live(RequestKind k) { return k == RequestKind::PlayClip || k == RequestKind::Walk; }

glm::vec3 horizontal(const glm::vec3& v) { return glm::vec3(v.x, 0.0f, v.z); }

// Turns `rotation` about Y towards facing `dir` (unit, horizontal) by at most `max_angle` radians.
glm::quat turn_towards(const glm::quat& rotation, const glm::vec3& dir, float max_angle) {
    const glm::vec3 f = horizontal(rotation * glm::vec3(0, 0, 1));
    const float cur = std::atan2(f.x, f.z);
    const float want = std::atan2(dir.x, dir.z);
    float d = want - cur;
    while (d > 3.14159265f) d -= 6.2831853f;
    while (d < -3.14159265f) d += 6.2831853f;
    d = std::clamp(d, -max_angle, max_angle);
    return glm::angleAxis(cur + d, glm::vec3(0, 1, 0));
}

// True when `a` and `b` hold the same bits (+0 and -0 differ: atan2 tells them apart).
template <class T>
bool same_bits(const T& a, const T& b) { return std::memcmp(&a, &b, sizeof(T)) == 0; }
}  // namespace

glm::quat MotionController::turn(Channel& ch, const glm::quat& rotation, const glm::vec3& dir, float max_angle) {
    if (same_bits(ch.faced, rotation) && same_bits(ch.faced_dir, dir) && same_bits(ch.faced_max_turn, max_angle))
        return rotation;  // turn_towards(faced, faced_dir, faced_max_turn) == faced, bit for bit
    const glm::quat out = turn_towards(rotation, dir, max_angle);
    if (same_bits(out, rotation)) ch.faced = rotation, ch.faced_dir = dir, ch.faced_max_turn = max_angle;
    return out;
}

MotionController::MotionController(const Skeleton& skeleton, const ClipLibrary& clips, size_t capacity)
    : skeleton_(&skeleton), clips_(&clips), chars_(capacity), hot_(capacity), queues_(capacity), pool_(skeleton.joint_count(), capacity, &skeleton),
      snapshot_(skeleton.joint_count(), capacity, nullptr), scratch_(skeleton.joint_count(), 1, nullptr),
      keys_(skeleton.joint_count()), inertia_(skeleton.joint_count()) {
    active_.reserve(capacity);
    due_.reserve(capacity);
}

void MotionController::leave_steady(uint32_t c) {
    Hot& h = hot_[c];
    if (h.steady == Steady::None) return;
    chars_[c].cur.time = h.time;
    chars_[c].cur.request_time = h.request_time;
    if (h.steady == Steady::RootClip) chars_[c].cur.walk.phase = h.phase, chars_[c].cur.travelling = h.travelling;
    h.steady = Steady::None;
}

void MotionController::leave_steady_all() {
    for (uint32_t c = 0; c < hot_.size(); ++c) leave_steady(c);
}

void MotionController::set_steady_steps(bool on) {
    leave_steady_all();
    steady_steps_ = on;
}

void MotionController::set_worker_slots(size_t count) {
    workers_ = std::max<size_t>(1, count);
    scratch_ = PosePool(skeleton_->joint_count(), workers_, nullptr);
}

void MotionController::set_walk_rig(WalkRig rig, GaitParams gait) {
    leave_steady_all();  // the walk methods the levels resolve to may change
    rig_ = std::move(rig);
    gait_ = gait;
    foot_lock_.emplace(*skeleton_, *rig_, chars_.size(), foot_lock_params_);
}

void MotionController::set_foot_lock(bool on, FootLockParams params) {
    foot_lock_params_ = params;
    foot_lock_on_ = on;
    if (rig_) foot_lock_.emplace(*skeleton_, *rig_, chars_.size(), params);
}

void MotionController::set_walk_clip(ClipId clip) { set_walk_clips(std::span<const ClipId>(&clip, 1)); }

void MotionController::set_walk_clips(std::span<const ClipId> clips) {
    leave_steady_all();  // the walk methods the levels resolve to may change
    walk_clips_.clear();
    walk_clip_speeds_.clear();
    for (ClipId id : clips) {
        const AnimationClip* clip = clips_->find(id);
        if (!clip) continue;
        walk_clips_.push_back(id);
        walk_clip_speeds_.push_back(clip->root_speed());
    }
}

void MotionController::set_stance(const AnimationClip& clip) {
    assert(clip.joint_count() == skeleton_->joint_count());
    PosePool stance(skeleton_->joint_count(), 1);
    stance.set_stance(0, clip, *skeleton_);
    const ConstPoseView from = std::as_const(stance).view(0);
    for (size_t c = 0; c < chars_.size(); ++c) {
        if (chars_[c].shown) continue;
        const PoseView to = pool_.view(c);
        std::copy(from.translations.begin(), from.translations.end(), to.translations.begin());
        std::copy(from.rotations.begin(), from.rotations.end(), to.rotations.begin());
        std::copy(from.scales.begin(), from.scales.end(), to.scales.begin());
        std::copy(from.model.begin(), from.model.end(), to.model.begin());
    }
}

int32_t MotionController::pick_walk_clip(float speed) const {
    int32_t best = -1;
    float best_error = 0.0f;
    for (size_t i = 0; i < walk_clips_.size(); ++i) {
        // Compare speeds by ratio: warping 0.5 m/s to 0.8 is as far as 1.6 to 2.56.
        const float natural = walk_clip_speeds_[i];
        const float error = natural > 1e-4f && speed > 1e-4f ? std::abs(std::log(speed / natural)) : 1e9f;
        if (best < 0 || error < best_error) best = static_cast<int32_t>(walk_clips_[i]), best_error = error;
    }
    return best;
}

void MotionController::set_method_hook(MethodSlot slot, MethodHook hook, void* user, MethodRelease release) {
    leave_steady_all();  // the walk methods the levels resolve to may change
    hooks_[static_cast<size_t>(slot)] = hook;
    hook_users_[static_cast<size_t>(slot)] = user;
    releases_[static_cast<size_t>(slot)] = hook ? release : nullptr;
}

uint16_t MotionController::add_path(std::vector<glm::vec3> waypoints, bool loop) {
    paths_.push_back(WalkPath{std::move(waypoints), loop});
    return static_cast<uint16_t>(paths_.size() - 1);
}

void MotionController::activate(uint32_t c) {
    Character& ch = chars_[c];
    if (ch.active_index >= 0) return;
    ch.active_index = static_cast<int32_t>(active_.size());
    active_.push_back(c);
    walk_dirty_ = true;
}

bool MotionController::push_request(uint32_t character, const MotionRequest& request) {
    if (character >= chars_.size()) return false;
    Character& ch = chars_[character];
    if (ch.count >= kQueueCapacity) return false;
    leave_steady(character);  // a queued request may pre-empt the current one
    queues_[character][(ch.head + ch.count) % kQueueCapacity] = request;
    ++ch.count;
    activate(character);
    return true;
}

bool MotionController::interrupt(uint32_t character, const MotionRequest& request) {
    if (character >= chars_.size()) return false;
    Character& ch = chars_[character];
    leave_steady(character);
    ch.count = 0;
    ch.head = 0;
    ch.cur.done = 1;  // the current request ends at the next update
    return push_request(character, request);
}

void MotionController::begin_fade(uint32_t c, Character& ch, float seconds, bool live_prev) {
    if (!(seconds > 0.0f) || hot_[c].stale) {  // a stale pose was never shown: nothing to fade from
        ch.fade_left = 0.0f;
        return;
    }
    ch.fade_total = seconds;
    ch.fade_left = seconds;
    ch.fade_snapshot = live_prev ? 0 : 1;
    if (!live_prev) {
        // Freeze the pose shown now as the fade source.
        const ConstPoseView from = std::as_const(pool_).view(c);
        const PoseView to = snapshot_.view(c);
        std::copy(from.translations.begin(), from.translations.end(), to.translations.begin());
        std::copy(from.rotations.begin(), from.rotations.end(), to.rotations.begin());
        std::copy(from.scales.begin(), from.scales.end(), to.scales.begin());
    }
}

void MotionController::start_next(uint32_t c, Character& ch) {
    MotionRequest next;  // Rest (forever) when the queue is empty
    next.crossfade_s = 0.0f;
    if (ch.count > 0) {
        next = queues_[c][ch.head];
        ch.head = static_cast<uint8_t>((ch.head + 1) % kQueueCapacity);
        --ch.count;
    }
    // A character's first request starts from nothing shown: it is not faded in from the rest pose.
    const bool fade = ch.shown && next.kind != RequestKind::Rest && next.crossfade_s > 0.0f;
    // Fade from the live previous request when it can be re-evaluated; from a frozen snapshot of the
    // pose shown now otherwise (rest, IK holds, or a fade already in progress).
    // A dynamic walk is never re-evaluated as the source of a fade (that would step its simulation twice).
    const bool dynamic = ch.cur.req.kind == RequestKind::Walk && ch.has_walk_method && ch.walk_method == WalkMethod::Dynamic;
    const bool live = fade && is_live(ch.cur.req.kind) && !dynamic && ch.fade_left <= 0.0f;
    if (fade) {
        if (live) ch.prev = ch.cur;
        begin_fade(c, ch, next.crossfade_s, live);
    } else {
        ch.fade_left = 0.0f;
    }
    Channel started;
    started.req = next;
    if (next.kind == RequestKind::PlayClip) started.time = next.start_time;
    if (next.kind == RequestKind::Walk) started.walk_clip = pick_walk_clip(next.speed);
    if (started.walk_clip >= 0) started.walk_natural = clips_->find(static_cast<ClipId>(started.walk_clip))->root_speed();
    if (next.kind == RequestKind::Walk && ch.cur.req.kind == RequestKind::Walk) started.walk = ch.cur.walk;  // keep feet planted
    ch.cur = started;
}

WalkMethod MotionController::walk_method(const AnimLod& lod) const {
    const bool clip = !walk_clips_.empty();
    const bool kin = rig_.has_value();
    switch (lod.walk) {
        case WalkMethod::Dynamic:
            if (kin && hooks_[static_cast<size_t>(MethodSlot::DynamicWalk)]) return WalkMethod::Dynamic;
            return kin ? WalkMethod::Kinematic : WalkMethod::ClipPlayback;
        case WalkMethod::Kinematic: return kin || !clip ? WalkMethod::Kinematic : WalkMethod::ClipPlayback;
        case WalkMethod::ClipPlayback: return clip || !kin ? WalkMethod::ClipPlayback : WalkMethod::Kinematic;
    }
    return WalkMethod::ClipPlayback;
}

bool MotionController::clip_driven(const Character& ch, const AnimLod& lod) const {
    const RequestKind k = ch.cur.req.kind;
    return k == RequestKind::PlayClip ||
           (k == RequestKind::Walk && ch.cur.walk_clip >= 0 && walk_method(lod) == WalkMethod::ClipPlayback);
}

bool MotionController::kinematic_walking(const Character& ch, const AnimLod& lod) const {
    return ch.cur.req.kind == RequestKind::Walk && rig_ && walk_method(lod) == WalkMethod::Kinematic;
}

const AnimationClip* MotionController::root_moving_clip(const Channel& ch) const {
    if (ch.req.kind != RequestKind::PlayClip || ch.req.root_motion == 0) return nullptr;
    const AnimationClip* clip = ch.req.loop ? clips_->find_looped(ch.req.clip) : clips_->find(ch.req.clip);
    return clip && clip->root_motion().moves() ? clip : nullptr;
}

void MotionController::move_by_root(const AnimationClip& clip, float before, float after, bool loop, float dt, Transform& placement,
                                   Velocity* velocity, KinematicWalkState& walk, uint8_t& travelling) const {
    const GroundMotion m = clip.root_motion().between(before, after, loop);
    const glm::vec3 step = placement.rotation * (placement.scale * glm::vec3(m.offset.x, 0.0f, m.offset.y));
    placement.position += step;
    placement.rotation = glm::normalize(placement.rotation * m.rotation());
    const float speed = dt > 0.0f ? glm::length(step) / dt : 0.0f;
    if (velocity) velocity->linear = dt > 0.0f ? step / dt : glm::vec3(0.0f);
    // Travelling: the walk phase runs at the stride the rig takes at this speed (the body's own size), for what shows
    // it as a walk cycle (impostors).
    travelling = rig_ && speed >= kTravellingSpeed ? 1 : 0;
    if (travelling) advance_walk_phase(walk, *rig_, speed / std::max(placement.scale, 1e-6f), dt, gait_);
}

float MotionController::clock_rate(const Channel& ch) {
    if (ch.req.kind == RequestKind::PlayClip) return ch.req.speed;
    const float natural = ch.walk_natural;
    return natural > 1e-4f ? std::max(ch.req.speed, 0.0f) / natural : 1.0f;
}

void MotionController::advance_clock(Channel& ch, float seconds) const {
    if (ch.req.kind == RequestKind::PlayClip || (ch.req.kind == RequestKind::Walk && ch.walk_clip >= 0))
        ch.time += seconds * clock_rate(ch);
}

glm::vec3 MotionController::straight_direction(const MotionRequest& r, const glm::quat& rotation) {
    const glm::vec3 h = horizontal(r.target);
    const float len = glm::length(h);
    glm::vec3 dir = len > 1e-6f ? h / len : horizontal(rotation * glm::vec3(0, 0, 1));
    if (glm::length(dir) > 0.0f) dir = glm::normalize(dir);
    return dir;
}

void MotionController::sync_walk_clock(Channel& ch, WalkMethod from, WalkMethod to) const {
    if (from == to || ch.req.kind != RequestKind::Walk || ch.walk_clip < 0) return;
    const float d = clips_->find(static_cast<ClipId>(ch.walk_clip))->duration();
    if (!(d > 0.0f)) return;
    if (to == WalkMethod::ClipPlayback) {
        ch.time = (std::floor(ch.time / d) + ch.walk.phase) * d;
    } else if (from == WalkMethod::ClipPlayback) {
        const float cycles = ch.time / d;
        ch.walk.phase = cycles - std::floor(cycles);
        ch.walk.initialised = 0;
    }
}

void MotionController::advance(Channel& ch, const AnimLod& lod, float dt, Transform* placement, Velocity* velocity) {
    ch.request_time += dt;
    const MotionRequest& r = ch.req;
    if (r.kind == RequestKind::PlayClip) {
        const float before = ch.time;
        advance_clock(ch, dt);
        const AnimationClip* clip = clips_->find(r.clip);
        if (!r.loop && (!clip || (r.speed >= 0.0f ? ch.time >= clip->duration() : ch.time <= 0.0f))) ch.done = 1;
        // Root motion: the transform moves as the clip's root did between the two clock readings (the pose is
        // shown in place: evaluate()).
        if (const AnimationClip* played = placement ? root_moving_clip(ch) : nullptr)
            move_by_root(*played, before, ch.time, r.loop != 0, dt, *placement, velocity, ch.walk, ch.travelling);
    } else if (r.kind == RequestKind::Walk) {
        const float speed = std::max(r.speed, 0.0f);
        const WalkMethod m = walk_method(lod);
        if (m == WalkMethod::ClipPlayback && ch.walk_clip >= 0) {
            advance_clock(ch, dt);
        } else if (rig_) {
            advance_walk_phase(ch.walk, *rig_, speed, dt, gait_);
        }
        if (placement && !ch.done) {
            glm::vec3 dir(0.0f);
            if (r.path != 0xFFFF && r.path < paths_.size()) {
                const WalkPath& path = paths_[r.path];
                const auto& wps = path.points;
                // A loop wraps to its first waypoint; one lap with every waypoint within reach (all
                // of them on one spot) ends the walk instead of spinning.
                for (size_t tried = 0; ch.path_cursor < wps.size() && tried <= wps.size(); ++tried) {
                    const glm::vec3 to = horizontal(wps[ch.path_cursor] - placement->position);
                    const float len = glm::length(to);
                    if (len > std::max(1e-3f, speed * dt)) {
                        dir = to / len;
                        break;
                    }
                    ++ch.path_cursor;  // reached (or reachable this frame): head for the next one
                    if (path.loop && ch.path_cursor == wps.size()) ch.path_cursor = 0;
                }
                if (ch.path_cursor >= wps.size() || glm::length(dir) == 0.0f) ch.done = 1;
            } else {
                dir = straight_direction(r, placement->rotation);
            }
            if (!ch.done) {
                placement->position += dir * speed * dt;
                placement->rotation = turn(ch, placement->rotation, dir, kTurnRate * dt);
                if (velocity) velocity->linear = dir * speed;
            } else if (velocity) {
                velocity->linear = glm::vec3(0.0f);
            }
        }
    }
    if (r.duration >= 0.0f && ch.request_time >= r.duration) ch.done = 1;
}

bool MotionUpdateJob::Validate(std::vector<std::string>* errors) const {
    bool ok = true;
    auto fail = [&](const std::string& m) { ok = false; if (errors) errors->push_back("MotionUpdateJob: " + m); };
    if (!controller) {
        fail("controller is null");
        return false;
    }
    const size_t n = controller->capacity();
    if (!(std::isfinite(dt) && dt >= 0.0f)) fail("dt must be finite and >= 0");
    auto check = [&](size_t size, const char* name) {
        if (element_of_character.empty() && size < n)
            fail(std::string(name) + " span is shorter than the controller capacity (" + std::to_string(n) + ")");
    };
    check(lods.size(), "lods");
    check(states.size(), "states");
    check(transforms.size(), "transforms");
    check(velocities.size(), "velocities");
    if (!pose_use.empty()) {
        const size_t elements = std::min({lods.size(), states.size(), transforms.size(), velocities.size()});
        if (pose_use.size() < elements)
            fail("pose_use has " + std::to_string(pose_use.size()) + " entries, fewer than the spans (" + std::to_string(elements) + ")");
        for (size_t i = 0; i < pose_use.size(); ++i)
            if (pose_use[i] > static_cast<uint8_t>(PoseUse::EveryFrame)) {
                fail("pose_use[" + std::to_string(i) + "] = " + std::to_string(pose_use[i]) + " is not a PoseUse");
                break;
            }
    }
    if (!element_of_character.empty()) {
        if (element_of_character.size() < n) {
            fail("element_of_character has " + std::to_string(element_of_character.size()) +
                 " entries, fewer than the controller capacity (" + std::to_string(n) + ")");
        } else {
            const size_t limit = std::min({lods.size(), states.size(), transforms.size(), velocities.size()});
            std::vector<uint8_t> seen(limit, 0);
            for (size_t c = 0; c < n; ++c) {
                const uint32_t e = element_of_character[c];
                if (e >= limit) {
                    fail("element_of_character[" + std::to_string(c) + "] = " + std::to_string(e) +
                         " is out of range of the spans (" + std::to_string(limit) + " elements)");
                } else if (seen[e]++) {
                    fail("element_of_character[" + std::to_string(c) + "] = " + std::to_string(e) +
                         " is used by another character");
                }
            }
        }
    }
    return ok;
}

size_t MotionUpdateJob::Run() const {
    controller->set_pose_use(pose_use);
    if (grain > 0)
        return controller->update_parallel(dt, lods, states, transforms, velocities, element_of_character, grain, run_chunks);
    return controller->update(dt, lods, states, transforms, velocities, element_of_character);
}

}  // namespace aloha
