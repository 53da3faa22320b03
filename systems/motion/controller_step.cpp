// Phase 1 of the motion controller: every active character's bookkeeping for the frame (request
// switches, clocks and root motion, level-change transitions, which poses are due), in blocks of the
// active list that may run concurrently, merged in the order of one serial pass.
#include "systems/motion/controller.hpp"

#include <algorithm>
#include <cassert>
#include <cstddef>
#include <mutex>

namespace aloha {

namespace {
// What of an AnimLod shapes the pose: level, walk method, IK solver and iterations, update interval.
int64_t anim_signature(const AnimLod& l) {
    return static_cast<int64_t>(l.level) | static_cast<int64_t>(l.walk) << 8 | static_cast<int64_t>(l.ik) << 16 |
           static_cast<int64_t>(l.ik_iterations) << 24 | static_cast<int64_t>(l.update_interval) << 32;
}

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
    // Each character's step touches its own state only (slot pools and method releases are locked), so
    // blocks of active_ run concurrently. Every block walks its part backwards and the blocks are merged
    // last to first: the due order, and active_ after the removals, are those of one backward pass.
    const size_t m = active_.size();
    const size_t blocks = run_chunks && *run_chunks && m > step_block_ ? (m + step_block_ - 1) / step_block_ : 1;
    if (blocks_.size() < blocks) blocks_.resize(blocks);
    auto run_block = [&](size_t j) {
        StepBlock& out = blocks_[j];
        out.due.clear(), out.between.clear(), out.resting.clear();
        const size_t b = j * step_block_, e = blocks == 1 ? m : std::min(m, b + step_block_);
        for (size_t k = e; k-- > b;) {
            if (k >= b + kStepPrefetch) prefetch_step(k - kStepPrefetch, states, element_of_character);
            step_active(k, dt, states, element_of_character, out);
        }
    };
    if (blocks == 1) {
        run_block(0);
    } else {
        (*run_chunks)(blocks, 1, [&](size_t jb, size_t je) {
            for (size_t j = jb; j < je; ++j) run_block(j);
        });
    }
    for (size_t j = blocks; j-- > 0;) {
        const StepBlock& out = blocks_[j];
        due_.insert(due_.end(), out.due.begin(), out.due.end());
        between_.insert(between_.end(), out.between.begin(), out.between.end());
        for (const uint32_t k : out.resting) {  // descending: swap-removal only moves visited entries
            const uint32_t moved = active_.back();
            chars_[active_[k]].active_index = -1;
            active_[k] = moved;
            if (k + 1 != active_.size()) chars_[moved].active_index = static_cast<int32_t>(k);
            active_.pop_back();
        }
    }
    ++frame_;
    return due_.size();
}

void MotionController::prefetch_step(size_t k, std::span<MotionState> states,
                                     std::span<const uint32_t> element_of_character) const {
#if defined(__GNUC__) || defined(__clang__)
    const uint32_t c = active_[k];
    const uint32_t e = element_of_character.empty() ? c : element_of_character[c];
    // The record's fields phase 1 reads (the hot head, up to the faded-from channel) and the element's
    // rows: the element order is not the id order, so each row is a cache miss of its own.
    const char* rec = reinterpret_cast<const char*>(&chars_[c]);
    for (size_t off = 0; off < offsetof(Character, prev); off += 64) __builtin_prefetch(rec + off, 1, 3);
    __builtin_prefetch(&lods_[e], 0, 3);
    __builtin_prefetch(&states[e], 1, 3);
    __builtin_prefetch(&transforms_[e], 1, 3);
    __builtin_prefetch(&velocities_[e], 1, 3);
    if (!pose_use_.empty()) __builtin_prefetch(&pose_use_[e], 0, 3);
#else
    (void)k, (void)states, (void)element_of_character;
#endif
}

void MotionController::step_active(size_t k, float dt, std::span<MotionState> states,
                                   std::span<const uint32_t> element_of_character, StepBlock& out) {
    const uint32_t c = active_[k];
    const uint32_t e = element_of_character.empty() ? c : element_of_character[c];
    assert(e < lods_.size() && e < states.size() && e < transforms_.size() && e < velocities_.size());
    Character& ch = chars_[c];
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
    advance(ch.cur, lod, dt, &x, &v);
    if (ch.fade_left > 0.0f) {
        if (!ch.fade_snapshot) advance(ch.prev, lod, dt, nullptr, nullptr);
        ch.fade_left = std::max(0.0f, ch.fade_left - dt);
    }
    if (ch.cur.req.kind == RequestKind::Walk) {
        ch.walk_method = walk_method(lod);
        ch.has_walk_method = 1;
    } else {
        ch.has_walk_method = 0;
        if (ch.cur.req.kind != RequestKind::Walk && switched) v.linear = glm::vec3(0.0f);
    }
    update_slots(c, ch);
    advance_overlay(ch.overlay, lod, dt);

    // An animation level change (walk method, IK, update interval) is inertialized from the pose
    // shown now; the character is posed at once so the change never waits for its update phase.
    const bool posing = ch.cur.req.kind != RequestKind::Rest || ch.overlay.on;
    const int64_t signature = anim_signature(lod);
    const bool level_changed = ch.last_anim >= 0 && ch.last_anim != signature;
    ch.last_anim = signature;
    // Any level change is posed at once (even without a transition), so a throttled character's
    // keys restart on the new level's schedule instead of holding the old span's last key.
    const bool level_start = level_changed && posing && !switched;
    if (ch.inertial_slot >= 0 && ch.inertial_done) {
        const std::lock_guard<std::mutex> lock(slots_mutex_);
        inertia_.release(static_cast<uint32_t>(ch.inertial_slot));
        ch.inertial_slot = -1;
    }
    if (level_start && transition_seconds(lod) > 0.0f && !ch.stale) {  // a stale pose was never shown
        if (ch.inertial_slot < 0) {
            const std::lock_guard<std::mutex> lock(slots_mutex_);
            ch.inertial_slot = static_cast<int32_t>(inertia_.acquire());
        }
        ch.inertial_pending = 1;
        ch.inertial_done = 0;
        ch.inertial_elapsed = 0.0f;
        ch.inertial_total = transition_seconds(lod);
    } else if (ch.inertial_slot >= 0) {
        ch.inertial_elapsed += dt;
    }

    ch.since_posed += dt;
    ch.since_locked += dt;
    ++st.frames_since_update;
    // Throttled characters are spread over their interval by id, so the per-frame cost is flat.
    const uint64_t interval = std::max<uint64_t>(1, lod.update_interval);
    const bool on_phase = (frame_ + c) % interval == 0;
    const PoseUse use = pose_use_.empty() ? PoseUse::EveryFrame : static_cast<PoseUse>(pose_use_[e]);
    bool due = posing && (switched || level_start || on_phase || (ch.overlay.on && ch.overlay.needs_pose()) ||
                          (ch.stale && use != PoseUse::Unseen) || (ch.keys_stale && use == PoseUse::EveryFrame));
    // Nobody reads the pose: a clip pose (a pure function of the clip clock, which ran on above) is left
    // stale and evaluated when the character is seen again. Methods with state of their own (walk
    // feet, IK, simulations), fades, overlays and inertialization are always posed.
    if (due && use == PoseUse::Unseen && clip_driven(ch, lod) && ch.fade_left <= 0.0f && !ch.overlay.on &&
        ch.inertial_slot < 0 && ch.slots_in_use == 0) {
        ch.stale = 1;
        due = false;
    }
    if (due) {
        ch.stale = 0;
        out.due.push_back(Due{c, e, ch.since_posed, switched});
        st.frames_since_update = 0;
        ch.since_posed = 0.0f;
        // Throttled clip playback and kinematic walks are shown interpolated between this update and
        // the next (a held pose would slide with the placement and jump at the next update).
        const bool interpolate = interval > 1 && (clip_driven(ch, lod) || kinematic_walking(ch, lod)) && ch.fade_left <= 0.0f;
        if (interpolate != (ch.keys_slot >= 0)) {
            const std::lock_guard<std::mutex> lock(slots_mutex_);
            if (interpolate) ch.keys_slot = static_cast<int32_t>(keys_.acquire());
            else keys_.release(static_cast<uint32_t>(ch.keys_slot)), ch.keys_slot = -1;
        }
        // The end key is the next scheduled update's pose: a forced pose off the schedule (a switch,
        // a transition start) spans only the frames left to it, so the keys join without a step.
        const uint64_t to_next = interval - (frame_ + c) % interval;
        ch.keys_span = static_cast<float>(to_next) * dt;
    } else if (ch.keys_slot >= 0 && ch.cur.req.kind != RequestKind::Rest && !ch.stale && !ch.keys_stale &&
               use == PoseUse::EveryFrame) {
        out.between.push_back(Due{c, e, ch.since_posed, false});
    }

    st.active = ch.cur.req.kind;
    st.time = ch.cur.time;
    st.phase = ch.cur.walk.phase;
    st.request_time = ch.cur.request_time;
    st.pose_slot = c;
    st.path_cursor = ch.cur.path_cursor;
    const bool resting =
        ch.cur.req.kind == RequestKind::Rest && ch.cur.req.duration < 0.0f && ch.count == 0 && !ch.overlay.on;
    st.at_rest = resting ? 1 : 0;
    if (resting) {
        v.linear = glm::vec3(0.0f);
        if (ch.keys_slot >= 0 || ch.inertial_slot >= 0) {
            const std::lock_guard<std::mutex> lock(slots_mutex_);
            if (ch.keys_slot >= 0) keys_.release(static_cast<uint32_t>(ch.keys_slot)), ch.keys_slot = -1;
            if (ch.inertial_slot >= 0) inertia_.release(static_cast<uint32_t>(ch.inertial_slot)), ch.inertial_slot = -1;
        }
        ch.last_anim = -1;  // a level change while resting shows nothing: no transition on waking
        if (foot_lock_) foot_lock_->reset(c);  // this character's entries only
        out.resting.push_back(static_cast<uint32_t>(k));  // taken out of active_ after the blocks
    }
}

}  // namespace aloha
