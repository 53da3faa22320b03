// Phase 2 of the motion controller: pose evaluation of the characters due this frame (clip
// sampling, walks, method hooks, cross-fade blending), serially or in parallel chunks on TBB.
#include "systems/motion/blend.hpp"
#include "systems/motion/controller.hpp"
#include "systems/motion/local_to_model.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <utility>

namespace aloha {

void MotionController::sample_walk_clip(Channel& ch, const PoseView& out) const {
    sample_walk_cycle(*clips_->find(static_cast<ClipId>(ch.walk_clip)), ch.time, &ch.cache, out);
}

void MotionController::evaluate(uint32_t c, Channel& ch, const AnimLod& lod, const PoseView& out, Transform& placement,
                                Velocity& velocity, float posed_dt, bool primary, bool first) {
    const int16_t* parents = skeleton_->parents().data();
    const size_t n = static_cast<size_t>(skeleton_->joint_count());
    auto l2m = [&] { local_to_model(parents, out.translations.data(), out.rotations.data(), out.scales.data(), nullptr, out.model.data(), n); };
    auto hook = [&](MethodSlot slot) {
        MethodContext ctx{c, &ch.req, skeleton_, &lod, out, &placement, &velocity, posed_dt, ch.request_time, first};
        hooks_[static_cast<size_t>(slot)](hook_users_[static_cast<size_t>(slot)], ctx);
    };
    switch (ch.req.kind) {
        case RequestKind::PlayClip: {
            // Played over and over, a clip whose ends nearly meet is sampled with its seam closed (ClipLibrary::set_looped).
            const AnimationClip* clip = ch.req.loop ? clips_->find_looped(ch.req.clip) : clips_->find(ch.req.clip);
            if (!clip) return;  // unknown clip: hold the pose
            const float t = wrap_clip_time(ch.time, clip->duration(), ch.req.loop != 0);
            int k = 0;
            float alpha = 0.0f;
            find_key(*clip, t, &ch.cache, &k, &alpha);
            sample_blocks(*clip, k, alpha, out.translations.data(), out.rotations.data(), out.scales.data());
            // A clip whose root motion moves the transform (advance()) is shown in place.
            if (root_moving_clip(ch))
                put_roots_in_place(clip->root_motion().at(t).inverse(), skeleton_->parents(), out.translations, out.rotations);
            l2m();
            return;
        }
        case RequestKind::Walk: {
            const WalkMethod m = walk_method(lod);
            const float speed = std::max(ch.req.speed, 0.0f);
            if (m == WalkMethod::ClipPlayback && ch.walk_clip >= 0) {
                sample_walk_clip(ch, out);
                l2m();
            } else if (rig_) {
                const AnimationClip* body = ch.walk_clip >= 0 ? clips_->find(static_cast<ClipId>(ch.walk_clip)) : nullptr;
                kinematic_walk_pose(*rig_, *skeleton_, ch.walk, speed, placement, out, gait_, body);
                if (m == WalkMethod::Dynamic && primary) {
                    hook(MethodSlot::DynamicWalk);
                    l2m();
                }
            }
            return;
        }
        case RequestKind::Reach:
        case RequestKind::LookAt: {
            const MethodSlot slot = ch.req.kind == RequestKind::Reach ? MethodSlot::Reach : MethodSlot::LookAt;
            if (!hooks_[static_cast<size_t>(slot)]) return;  // no IK registered: hold the pose
            l2m();
            hook(slot);
            l2m();
            return;
        }
        case RequestKind::Rest: return;
    }
}

void MotionController::pose_one(const Due& d, size_t worker) {
    const uint32_t c = d.character;
    Character& ch = chars_[c];
    Hot& h = hot_[c];
    if (h.steady != Steady::None) ch.cur.time = h.time, ch.cur.request_time = h.request_time;  // its clocks live in h
    const AnimLod& lod = lods_[d.element];
    Transform& x = transforms_[d.element];
    Velocity& v = velocities_[d.element];
    const PoseView out = pool_.view(c);
    const bool live_fade = ch.fade_left > 0.0f && !ch.fade_snapshot;
    const PoseView scratch = scratch_.view(worker);
    if (live_fade) {
        // The request faded from holds the pose shown so far if it cannot produce one: start the
        // scratch from it, so the result never depends on what another character left there.
        const ConstPoseView shown = std::as_const(pool_).view(c);
        std::copy(shown.translations.begin(), shown.translations.end(), scratch.translations.begin());
        std::copy(shown.rotations.begin(), shown.rotations.end(), scratch.rotations.begin());
        std::copy(shown.scales.begin(), shown.scales.end(), scratch.scales.begin());
        std::copy(shown.model.begin(), shown.model.end(), scratch.model.begin());
    }
    // A level change this frame: keep the pose shown so far before the new one overwrites it.
    if (ch.inertial_slot >= 0 && ch.inertial_pending) {
        inertia_.hold(static_cast<uint32_t>(ch.inertial_slot), skeleton_->parents().data(), std::as_const(pool_).view(c).model);
        if (foot_lock_) foot_lock_->rebase(c);  // the held pose carries the lock's corrections
    }
    evaluate(c, ch.cur, lod, out, x, v, d.posed_dt, true, d.started);
    ch.shown = 1;
    // Keys are only taken for a pose read every frame; one read at updates only shows this pose (the keys'
    // start) until its next update, so the pose one interval ahead is not evaluated.
    const bool keyed = pose_use_.empty() || pose_use_[d.element] == static_cast<uint8_t>(PoseUse::EveryFrame);
    h.keys_stale = h.keys_slot >= 0 && !keyed ? 1 : 0;
    if (h.keys_slot >= 0 && keyed) {
        // Key poses for the frames until the next update: now, and one interval ahead.
        const uint32_t slot = static_cast<uint32_t>(h.keys_slot);
        apply_overlay(c, ch, lod, out, x, v, d.posed_dt, true);
        settle_inertia(ch, out, ch.inertial_elapsed);
        keys_.capture(slot, false, out.model);
        Channel ahead = ch.cur;
        Transform x_ahead = x;
        advance_clock(ahead, h.keys_span);
        stop_before_wrap(ahead, ch.cur.time);
        if (kinematic_walking(ch, lod)) {
            // The walk one interval on: its phase advanced and the placement moved at its velocity (the
            // copy's planted feet stay in the world, so the keys carry them back as the root moves).
            advance_walk_phase(ahead.walk, *rig_, std::max(ahead.req.speed, 0.0f), h.keys_span, gait_);
            x_ahead.position += v.linear * h.keys_span;
        }
        evaluate(c, ahead, lod, scratch, x_ahead, v, h.keys_span, false, false);
        apply_overlay(c, ch, lod, scratch, x_ahead, v, h.keys_span, false);
        settle_inertia(ch, scratch, ch.inertial_elapsed + h.keys_span);
        keys_.capture(slot, true, std::as_const(scratch_).view(worker).model);
        return;
    }
    if (ch.fade_left > 0.0f) {
        const float w = ch.fade_left / ch.fade_total;  // weight of the pose faded from
        if (ch.fade_snapshot) {
            blend_into(out, std::as_const(snapshot_).view(c), w);
        } else {
            evaluate(c, ch.prev, lod, scratch, x, v, d.posed_dt, false, false);
            blend_into(out, std::as_const(scratch_).view(worker), w);
        }
        local_to_model(skeleton_->parents().data(), out.translations.data(), out.rotations.data(),
                       out.scales.data(), nullptr, out.model.data(), static_cast<size_t>(skeleton_->joint_count()));
    }
    apply_overlay(c, ch, lod, out, x, v, d.posed_dt, true);  // over the blended pose
    settle_inertia(ch, out, ch.inertial_elapsed);
}

void MotionController::settle_inertia(Character& ch, const PoseView& pose, float elapsed) {
    if (ch.inertial_slot < 0) return;
    const auto slot = static_cast<uint32_t>(ch.inertial_slot);
    if (ch.inertial_pending) {
        // The change happened this frame: the offset is what separates the new pose from the old.
        inertia_.relate(slot, ConstPoseView{pose.translations, pose.rotations, pose.scales, pose.model});
        if (ch.inertial_wrap) inertia_.keep_root_travel(slot);
        ch.inertial_pending = 0;
    }
    ch.inertial_done = ch.inertial_elapsed >= ch.inertial_total ? 1 : 0;
    const float w = inertial_weight(elapsed, ch.inertial_total);
    if (w <= 0.0f) return;
    inertia_.apply(slot, w, pose);
    local_to_model(skeleton_->parents().data(), pose.translations.data(), pose.rotations.data(), pose.scales.data(),
                   nullptr, pose.model.data(), static_cast<size_t>(skeleton_->joint_count()));
}

void MotionController::lock_feet(const Due& d) {
    if (!foot_lock_ || !foot_lock_on_) return;
    Character& ch = chars_[d.character];
    // Walks the controller poses kinematically or from clips; the dynamic walker's feet are its own.
    const bool walking = ch.cur.req.kind == RequestKind::Walk && ch.has_walk_method && ch.walk_method != WalkMethod::Dynamic;
    Hot& h = hot_[d.character];
    foot_lock_->apply(d.character, h.since_locked, transforms_[d.element], pool_.view(d.character).model, walking);
    h.since_locked = 0.0f;
}

void MotionController::leave_stale(uint32_t c, Hot& h) {
    h.stale = 1;
    if (foot_lock_) foot_lock_->reset(c);
}

void MotionController::evaluate_due(size_t begin, size_t end, size_t worker) {
    end = std::min(end, work_count());
    // Per level and cost class time of this chunk, added to level_ns_ once at the end (one clock read
    // per item).
    std::array<uint64_t, 256 * kAnimCostClasses> chunk_ns{};
    const bool timed = !level_ns_.empty();
    auto now = [] { return static_cast<uint64_t>(std::chrono::steady_clock::now().time_since_epoch().count()); };
    uint64_t last = timed ? now() : 0;
    for (size_t i = begin; i < end; ++i) {
        const Due& d = i < due_.size() ? due_[i] : between_[i - due_.size()];
        if (i < due_.size()) {
            pose_one(d, worker);
        } else {
            const Hot& h = hot_[d.character];
            keys_.interpolate(static_cast<uint32_t>(h.keys_slot), d.posed_dt / h.keys_span, pool_.view(d.character).model);
        }
        lock_feet(d);
        if (!timed) continue;
        const uint64_t t = now();
        chunk_ns[anim_cost_slot(lods_[d.element].level, chars_[d.character].cur.req.kind == RequestKind::Walk)] += t - last;
        last = t;
    }
    for (size_t l = 0; timed && l < level_ns_.size() && l < chunk_ns.size(); ++l)
        if (chunk_ns[l] != 0) std::atomic_ref<uint64_t>(level_ns_[l]).fetch_add(chunk_ns[l], std::memory_order_relaxed);
}

size_t MotionController::update(float dt, std::span<const AnimLod> lods, std::span<MotionState> states,
                                std::span<Transform> transforms, std::span<Velocity> velocities,
                                std::span<const uint32_t> element_of_character) {
    const size_t due = begin_update(dt, lods, states, transforms, velocities, element_of_character);
    evaluate_due(0, work_count(), 0);
    return due;
}

size_t MotionController::update_parallel(float dt, std::span<const AnimLod> lods, std::span<MotionState> states,
                                         std::span<Transform> transforms, std::span<Velocity> velocities,
                                         std::span<const uint32_t> element_of_character, size_t grain,
                                         const ChunkRunner& run_chunks) {
    const ChunkRunner tbb_chunks = [](size_t count, size_t g, const std::function<void(size_t, size_t)>& fn) {
        tbb::parallel_for(tbb::blocked_range<size_t>(0, count, g), [&](const tbb::blocked_range<size_t>& r) { fn(r.begin(), r.end()); });
    };
    const size_t due = begin_update_blocks(dt, lods, states, transforms, velocities, element_of_character,
                                           run_chunks ? &run_chunks : &tbb_chunks);
    const size_t work = work_count();
    if (grain == 0) grain = 64;
    if (work <= grain) {
        evaluate_due(0, work, 0);
        return due;
    }
    // One scratch slot per thread of the arena; results do not depend on which thread runs a chunk.
    const auto threads = static_cast<size_t>(std::max(1, tbb::this_task_arena::max_concurrency()));
    if (workers_ < threads) set_worker_slots(threads);
    auto chunk = [this](size_t begin, size_t end) {
        const int t = tbb::this_task_arena::current_thread_index();
        const size_t worker = t >= 0 && static_cast<size_t>(t) < workers_ ? static_cast<size_t>(t) : 0;
        evaluate_due(begin, end, worker);
    };
    if (run_chunks) {
        run_chunks(work, grain, chunk);
        return due;
    }
    tbb::parallel_for(tbb::blocked_range<size_t>(0, work, grain),
                      [&](const tbb::blocked_range<size_t>& r) { chunk(r.begin(), r.end()); });
    return due;
}

}  // namespace aloha
