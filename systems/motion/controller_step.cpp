// Phase 1 of the motion controller: every active character's bookkeeping for the frame (request
// switches, clocks and root motion, level-change transitions, which poses are due), in blocks of the
// active list that may run concurrently, merged in the order of one serial pass.
#include "systems/motion/controller.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstddef>
#include <mutex>

namespace aloha {

namespace {
// Seconds an animation level change is inertialized over: the entered level's cross-fade time.
float transition_seconds(const AnimLod& lod) { return lod.crossfade_s; }
}  // namespace

void MotionController::update_slots(uint32_t c, Character& ch) {
    uint8_t want = 0;
    const RequestKind k = ch.cur.req.kind;
    if (k == RequestKind::Reach) want = 1u << static_cast<unsigned>(MethodSlot::Reach);
    if (k == RequestKind::LookAt) want = 1u << static_cast<unsigned>(MethodSlot::LookAt);
    if (k == RequestKind::Walk && ch.has_walk_method && ch.walk_method == WalkMethod::Dynamic)
        want = 1u << static_cast<unsigned>(MethodSlot::DynamicWalk);
    const uint8_t dropped = static_cast<uint8_t>(ch.slots_in_use & ~want);
    ch.slots_in_use = want;
    if (dropped == 0) return;
    const std::lock_guard<std::mutex> lock(slots_mutex_);  // releases may run from concurrent blocks
    for (size_t s = 0; s < releases_.size(); ++s)
        if ((dropped >> s) & 1u && releases_[s]) releases_[s](hook_users_[s], c);
}

size_t MotionController::begin_update(float dt, std::span<const AnimLod> lods, std::span<MotionState> states,
                                      std::span<Transform> transforms, std::span<Velocity> velocities,
                                      std::span<const uint32_t> element_of_character) {
    return begin_update_blocks(dt, lods, states, transforms, velocities, element_of_character, nullptr);
}

size_t MotionController::begin_update_blocks(float dt, std::span<const AnimLod> lods, std::span<MotionState> states,
                                             std::span<Transform> transforms, std::span<Velocity> velocities,
                                             std::span<const uint32_t> element_of_character,
                                             const ChunkRunner* run_chunks) {
    due_.clear();
    between_.clear();
    lods_ = lods;
    transforms_ = transforms;
    velocities_ = velocities;
    assert(dt >= 0.0f);
    assert(element_of_character.empty() || element_of_character.size() >= chars_.size());
    refresh_walk(element_of_character, std::min({lods.size(), states.size(), transforms.size(), velocities.size()}));
    // Each character's step touches its own state only (slot pools and method releases are locked), so
    // blocks of walk_ run concurrently, merged in order: the due order is that of one pass in element order.
    const size_t m = walk_.size();
    const size_t blocks = run_chunks && *run_chunks && m > step_block_ ? (m + step_block_ - 1) / step_block_ : 1;
    if (blocks_.size() < blocks) blocks_.resize(blocks);
    auto run_block = [&](size_t j) {
        StepBlock& out = blocks_[j];
        out.due.clear(), out.between.clear(), out.resting.clear();
        out.steady = 0;
        const size_t b = j * step_block_, e = blocks == 1 ? m : std::min(m, b + step_block_);
        for (size_t k = b; k < e; ++k) {
            if (k + kStepPrefetch < e) prefetch_step(k + kStepPrefetch);
            if (steady_steps_ && step_steady(walk_[k], dt, states, out)) ++out.steady;
            else step_active(walk_[k], dt, states, out);
        }
    };
    if (blocks == 1) {
        run_block(0);
    } else {
        (*run_chunks)(blocks, 1, [&](size_t jb, size_t je) {
            for (size_t j = jb; j < je; ++j) run_block(j);
        });
    }
    steady_count_ = 0;
    for (size_t j = 0; j < blocks; ++j) {
        const StepBlock& out = blocks_[j];
        steady_count_ += out.steady;
        due_.insert(due_.end(), out.due.begin(), out.due.end());
        between_.insert(between_.end(), out.between.begin(), out.between.end());
        for (const uint32_t c : out.resting) {  // swap-removal from active_ (walk_ is rebuilt next update)
            const auto k = static_cast<size_t>(chars_[c].active_index);
            const uint32_t moved = active_.back();
            active_[k] = moved;
            chars_[moved].active_index = static_cast<int32_t>(k);
            chars_[c].active_index = -1;
            active_.pop_back();
            walk_dirty_ = true;
        }
    }
    ++frame_;
    return due_.size();
}

MotionController::Schedule MotionController::tick(uint32_t c, uint32_t e, Hot& h, MotionState& st, const AnimLod& lod,
                                                  float dt) {
    h.since_posed += dt;
    h.since_locked += dt;
    ++st.frames_since_update;
    // Throttled characters are spread over their interval by id, so the per-frame cost is flat.
    const uint64_t interval = std::max<uint64_t>(1, lod.update_interval);
    return {interval, (frame_ + c) % interval == 0, pose_use_.empty() ? PoseUse::EveryFrame : static_cast<PoseUse>(pose_use_[e])};
}

void MotionController::mark_due(uint32_t c, uint32_t e, Hot& h, MotionState& st, const Schedule& s, bool interpolate,
                                bool started, float dt, StepBlock& out) {
    h.stale = 0;
    out.due.push_back(Due{c, e, h.since_posed, started});
    st.frames_since_update = 0;
    h.since_posed = 0.0f;
    if (interpolate != (h.keys_slot >= 0)) {
        const std::lock_guard<std::mutex> lock(slots_mutex_);
        if (interpolate) h.keys_slot = static_cast<int32_t>(keys_.acquire());
        else keys_.release(static_cast<uint32_t>(h.keys_slot)), h.keys_slot = -1;
    }
    // The end key is the next scheduled update's pose: a forced pose off the schedule (a switch,
    // a transition start) spans only the frames left to it, so the keys join without a step.
    const uint64_t to_next = s.interval - (frame_ + c) % s.interval;
    h.keys_span = static_cast<float>(to_next) * dt;
}

void MotionController::refresh_walk(std::span<const uint32_t> element_of_character, size_t elements) {
    const size_t n = chars_.size();
    const std::span<const uint32_t> map = element_of_character.empty() ? element_of_character : element_of_character.first(n);
    if (!walk_dirty_ && map.size() == walk_map_.size()) {
        // The active set is the one walk_ holds: what moved is the characters whose element changed. A host
        // that regroups swaps elements among its characters; when the active ones that moved took each
        // other's elements, the walk keeps its elements and only the characters at them change.
        walk_moved_.clear();
        for (uint32_t c = 0; c < map.size(); ++c)
            if (map[c] != walk_map_[c]) walk_moved_.push_back(c);
        if (walk_moved_.empty()) return;
        walk_from_.clear(), walk_to_.clear();
        for (const uint32_t c : walk_moved_)
            if (chars_[c].active_index >= 0) walk_from_.push_back(walk_map_[c]), walk_to_.push_back(map[c]);
        std::sort(walk_from_.begin(), walk_from_.end());
        std::sort(walk_to_.begin(), walk_to_.end());
        const bool swapped = walk_from_ == walk_to_;
        for (const uint32_t c : walk_moved_) {
            if (swapped && chars_[c].active_index >= 0) {
                auto at = std::lower_bound(walk_.begin(), walk_.end(), map[c],
                                           [](const Walker& w, uint32_t e) { return w.element < e; });
                assert(at != walk_.end() && at->element == map[c]);
                at->character = c;
            }
            walk_map_[c] = map[c];
        }
        if (swapped) return;
    }
    walk_map_.assign(map.begin(), map.end());
    // Scatter the active characters to their elements, then gather them in element order.
    constexpr uint32_t kNone = 0xFFFFFFFFu;
    by_element_.assign(map.empty() ? n : elements, kNone);
    for (const uint32_t c : active_) {
        assert(map.empty() || map[c] < elements);
        by_element_[map.empty() ? c : map[c]] = c;
    }
    walk_.clear();
    for (size_t e = 0; e < by_element_.size(); ++e)
        if (by_element_[e] != kNone) walk_.push_back(Walker{by_element_[e], static_cast<uint32_t>(e)});
    walk_dirty_ = false;
}

void MotionController::prefetch_step(size_t k) const {
#if defined(__GNUC__) || defined(__clang__)
    // The character's Hot record: the walk is in element order, so each record is a cache miss of its own
    // (the element's rows stream in order).
    const char* rec = reinterpret_cast<const char*>(&hot_[walk_[k].character]);
    __builtin_prefetch(rec, 1, 3);
    __builtin_prefetch(rec + sizeof(Hot) - 1, 1, 3);
#else
    (void)k;
#endif
}

bool MotionController::jumped_at_wrap(const Channel& ch, float before) const {
    if (ch.req.kind != RequestKind::PlayClip || !ch.req.loop) return false;
    const AnimationClip* clip = clips_->find_looped(ch.req.clip);
    if (!clip || clip->ends_meet() || !(clip->duration() > 0.0f)) return false;
    return std::floor(before / clip->duration()) != std::floor(ch.time / clip->duration());
}

void MotionController::stop_before_wrap(Channel& ahead, float from) const {
    if (!jumped_at_wrap(ahead, from)) return;
    const float d = clips_->find_looped(ahead.req.clip)->duration();
    // Forward: the last instant before the next multiple of the duration; backward: the first after the one below.
    const bool forward = ahead.time > from;
    const float boundary = (std::floor(from / d) + (forward ? 1.0f : 0.0f)) * d;
    ahead.time = std::nextafter(boundary, forward ? -INFINITY : INFINITY);
}

void MotionController::step_active(const Walker& w, float dt, std::span<MotionState> states, StepBlock& out) {
    const uint32_t c = w.character, e = w.element;
    assert(e < lods_.size() && e < states.size() && e < transforms_.size() && e < velocities_.size());
    leave_steady(c);  // its clocks back into the Character: this step reads them there
    Character& ch = chars_[c];
    Hot& h = hot_[c];
    const AnimLod& lod = lods_[e];
    MotionState& st = states[e];
    Transform& x = transforms_[e];
    Velocity& v = velocities_[e];

    // Switch first: requests that ended last frame, or a queued request pre-empting one that would
    // run forever; the request started is then advanced by this frame's dt like any other.
    bool switched = false;
    for (size_t guard = 0; guard <= kQueueCapacity; ++guard) {
        const MotionRequest& r = ch.cur.req;
        const bool ends_by_itself = (r.kind == RequestKind::PlayClip && !r.loop) ||
                                    (r.kind == RequestKind::Walk && r.path != 0xFFFF);
        const bool preempted = ch.count > 0 && r.duration < 0.0f && !ends_by_itself;
        if (!ch.cur.done && !preempted) break;
        if (ch.count == 0 && r.kind == RequestKind::Rest && r.duration < 0.0f) break;
        start_next(c, ch);
        switched = true;
    }
    if (!switched && ch.cur.req.kind == RequestKind::Walk && ch.has_walk_method)
        sync_walk_clock(ch.cur, ch.walk_method, walk_method(lod));
    // Requests that end during this frame hand over at the start of the next one.
    const float clock_before = ch.cur.time;
    const Transform x_before = x;
    advance(ch.cur, lod, dt, &x, &v);
    if (ch.fade_left > 0.0f) {
        // A fade into or out of a clip whose root motion moves the character blends the two requests' motions as
        // their poses are blended (a request faded from as a frozen snapshot stands still), so the character's
        // speed changes over the fade, not at the switch. Other fades move the transform as the new request does.
        const bool blend_motion = root_moving_clip(ch.cur) || (!ch.fade_snapshot && root_moving_clip(ch.prev));
        Transform x_prev = x_before;
        Velocity v_prev{};
        if (!ch.fade_snapshot) advance(ch.prev, lod, dt, blend_motion ? &x_prev : nullptr, blend_motion ? &v_prev : nullptr);
        ch.fade_left = std::max(0.0f, ch.fade_left - dt);
        if (blend_motion) {
            const float faded = ch.fade_left / ch.fade_total;  // the weight of the request faded from, as its pose's
            x.position = glm::mix(x.position, x_prev.position, faded);
            x.rotation = glm::slerp(x.rotation, x_prev.rotation, faded);
            v.linear = glm::mix(v.linear, v_prev.linear, faded);
        }
    }
    if (ch.cur.req.kind == RequestKind::Walk) {
        ch.walk_method = walk_method(lod);
        ch.has_walk_method = 1;
    } else {
        ch.has_walk_method = 0;
        if (ch.cur.req.kind != RequestKind::Walk && switched && !root_moving_clip(ch.cur)) v.linear = glm::vec3(0.0f);
    }
    update_slots(c, ch);
    advance_overlay(ch.overlay, lod, dt);

    // An animation level change (walk method, IK, update interval) is inertialized from the pose
    // shown now; the character is posed at once so the change never waits for its update phase.
    const bool posing = ch.cur.req.kind != RequestKind::Rest || ch.overlay.on;
    const int64_t signature = anim_signature(lod);
    const bool level_changed = h.last_anim >= 0 && h.last_anim != signature;
    h.last_anim = signature;
    // Any level change is posed at once (even without a transition), so a throttled character's
    // keys restart on the new level's schedule instead of holding the old span's last key.
    // A looping clip whose ends do not meet is inertialized where it wraps, as a level change is.
    const bool wrapped = !switched && jumped_at_wrap(ch.cur, clock_before);
    const bool level_start = (level_changed || wrapped) && posing && !switched;
    if (ch.inertial_slot >= 0 && ch.inertial_done) {
        const std::lock_guard<std::mutex> lock(slots_mutex_);
        inertia_.release(static_cast<uint32_t>(ch.inertial_slot));
        ch.inertial_slot = -1;
    }
    if (level_start && transition_seconds(lod) > 0.0f && !h.stale) {  // a stale pose was never shown
        if (ch.inertial_slot < 0) {
            const std::lock_guard<std::mutex> lock(slots_mutex_);
            ch.inertial_slot = static_cast<int32_t>(inertia_.acquire());
        }
        ch.inertial_pending = 1;
        ch.inertial_done = 0;
        ch.inertial_wrap = wrapped && !level_changed ? 1 : 0;
        ch.inertial_elapsed = 0.0f;
        ch.inertial_total = transition_seconds(lod);
    } else if (ch.inertial_slot >= 0) {
        ch.inertial_elapsed += dt;
    }

    const Schedule sched = tick(c, e, h, st, lod, dt);
    const PoseUse use = sched.use;
    bool due = posing && (switched || level_start || sched.on_phase || (ch.overlay.on && ch.overlay.needs_pose()) ||
                          (h.stale && use != PoseUse::Unseen) || (h.keys_stale && use == PoseUse::EveryFrame));
    // Nobody reads the pose: a clip pose (a pure function of the clip clock, which ran on above) is left
    // stale and evaluated when the character is seen again. Methods with state of their own (walk
    // feet, IK, simulations), fades, overlays and inertialization are always posed.
    if (due && use == PoseUse::Unseen && clip_driven(ch, lod) && ch.fade_left <= 0.0f && !ch.overlay.on &&
        ch.inertial_slot < 0 && ch.slots_in_use == 0) {
        leave_stale(c, h);
        due = false;
    }
    if (due) {
        // Throttled clip playback and kinematic walks are shown interpolated between this update and
        // the next (a held pose would slide with the placement and jump at the next update).
        const bool interpolate = sched.interval > 1 && (clip_driven(ch, lod) || kinematic_walking(ch, lod)) && ch.fade_left <= 0.0f;
        mark_due(c, e, h, st, sched, interpolate, switched, dt, out);
    } else if (h.keys_slot >= 0 && ch.cur.req.kind != RequestKind::Rest && !h.stale && !h.keys_stale &&
               use == PoseUse::EveryFrame) {
        out.between.push_back(Due{c, e, h.since_posed, false});
    }

    st.active = ch.cur.req.kind;
    st.time = ch.cur.time;
    st.phase = ch.cur.walk.phase;
    st.travelling = ch.cur.req.kind == RequestKind::PlayClip ? ch.cur.travelling : 0;
    st.request_time = ch.cur.request_time;
    st.pose_slot = c;
    st.path_cursor = ch.cur.path_cursor;
    const bool resting =
        ch.cur.req.kind == RequestKind::Rest && ch.cur.req.duration < 0.0f && ch.count == 0 && !ch.overlay.on;
    st.at_rest = resting ? 1 : 0;
    if (resting) {
        v.linear = glm::vec3(0.0f);
        if (h.keys_slot >= 0 || ch.inertial_slot >= 0) {
            const std::lock_guard<std::mutex> lock(slots_mutex_);
            if (h.keys_slot >= 0) keys_.release(static_cast<uint32_t>(h.keys_slot)), h.keys_slot = -1;
            if (ch.inertial_slot >= 0) inertia_.release(static_cast<uint32_t>(ch.inertial_slot)), ch.inertial_slot = -1;
        }
        h.last_anim = -1;  // a level change while resting shows nothing: no transition on waking
        if (foot_lock_) foot_lock_->reset(c);  // this character's entries only
        out.resting.push_back(c);  // taken out of active_ after the blocks
        return;
    }
    if (steady_steps_) enter_steady(c, ch, x);
}

}  // namespace aloha
