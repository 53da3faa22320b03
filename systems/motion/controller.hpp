// The motion controller: per-character request queues, state vectors, cross-fades, root motion,
// the pose pool, and a packed list of active characters so characters at rest cost nothing.
// Clip playback and walking (clip playback / kinematic) are built in; reach, look-at and dynamic
// walking are dispatched to hooks that the IK and dynamics modules register (register_ik_hooks in
// ik/ik_hooks.hpp, register_dynamic_walk_hook in dynamic/dynamic_hook.hpp). Host arrays may be in
// any order (element_of_character); pose evaluation can run in parallel chunks (update_parallel).
#pragma once

#include "components/lod.hpp"
#include "components/motion.hpp"
#include "components/transform.hpp"
#include "systems/motion/clip.hpp"
#include "systems/motion/controller_types.hpp"
#include "systems/motion/foot_lock.hpp"
#include "systems/motion/inertialize.hpp"
#include "systems/motion/kinematic_walk.hpp"
#include "systems/motion/pose_pool.hpp"
#include "systems/motion/sampling.hpp"
#include "systems/motion/throttle_keys.hpp"

#include <algorithm>
#include <array>
#include <functional>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace aloha {

/// Owns the motion state of up to `capacity` characters of one skeleton (character i uses pose
/// slot i). An update runs in two phases: serial bookkeeping (requests, fades, time, root motion,
/// which characters are due for a pose) and pose evaluation of the due characters, which
/// update_parallel splits into chunks on TBB. Each character's pose depends only on its own data,
/// so serial and parallel updates give the same bits. One update at a time.
class MotionController {
public:
    /// Requests each character can have queued behind the active one.
    static constexpr size_t kQueueCapacity = 8;

    /// Sets up `capacity` characters, all at rest in the skeleton's rest pose. `skeleton` and
    /// `clips` must outlive the controller; clips must be built for `skeleton`.
    MotionController(const Skeleton& skeleton, const ClipLibrary& clips, size_t capacity);

    /// Enables WalkMethod::Kinematic (and the fallback for Dynamic) with this leg rig.
    void set_walk_rig(WalkRig rig, GaitParams gait = {});
    /// The leg rig set by set_walk_rig (null before).
    [[nodiscard]] const WalkRig* walk_rig() const { return rig_ ? &*rig_ : nullptr; }
    /// Turns the foot lock (foot_lock.hpp) of walking characters on or off (on by default once a walk
    /// rig is set) and sets its parameters; clears every character's lock state. Not during an update.
    void set_foot_lock(bool on, FootLockParams params = {});
    /// The foot lock's state (null without a walk rig).
    [[nodiscard]] const FootLock* foot_lock() const { return foot_lock_ ? &*foot_lock_ : nullptr; }
    /// Enables WalkMethod::ClipPlayback with this looping walk clip (its root motion sets the natural speed).
    void set_walk_clip(ClipId clip);
    /// Enables WalkMethod::ClipPlayback with several looping gait cycles (e.g. a walk and run ladder):
    /// each walk request plays the clip whose natural speed (root travel per second) is nearest its
    /// speed, at the rate that matches the speed exactly (stride kept, cadence warped), so stance
    /// feet stay planted. Unknown ids and clips without travel are left out.
    void set_walk_clips(std::span<const ClipId> clips);
    /// Every character not posed yet holds `clip`'s first pose instead of the skeleton's rest pose until a request
    /// poses it: the stance it keeps where its requests move nothing (the arm a reach does not use, the body under a
    /// look-at, a rest request). The root keeps its rest translation (the clip's horizontal offset is no placement).
    /// A type whose rest is a T- or A-pose stands in its idle. Not during an update. Requires `clip` built on this
    /// controller's skeleton (same joint count).
    void set_stance(const AnimationClip& clip);
    /// The walk clip a walk at `speed` m/s plays (the natural speed nearest by ratio), or -1 without walk clips.
    [[nodiscard]] int32_t pick_walk_clip(float speed) const;
    /// Registers the implementation of a method (nullptr removes it) and optionally its release
    /// callback. Not during an update.
    void set_method_hook(MethodSlot slot, MethodHook hook, void* user, MethodRelease release = nullptr);
    /// Adds a walk path (world waypoints, at least one) and returns its id for MotionRequest::path.
    /// A walker on a `loop` path heads for the first waypoint again after the last and walks until
    /// its request's duration runs out; on an open path its walk ends at the last waypoint.
    uint16_t add_path(std::vector<glm::vec3> waypoints, bool loop = false);
    /// How many paths were added.
    [[nodiscard]] size_t path_count() const { return paths_.size(); }

    /// Queues `request` for `character` (starts after the current one; a current request that would
    /// run forever is cross-faded out at the next update). Wakes a resting character.
    /// Returns false when the queue is full or the character is out of range.
    bool push_request(uint32_t character, const MotionRequest& request);
    /// Drops the queue and makes `request` the next one (cross-faded in at the next update).
    bool interrupt(uint32_t character, const MotionRequest& request);
    /// Layers a reach or look-at (`request.kind` Reach or LookAt) over whatever `character` does: the
    /// walk or clip beneath goes on (root motion included) and only the IK chain is overridden, by
    /// `weight` (clamped to [0, 1]). A new overlay fades in over `request.crossfade_s` seconds; calling
    /// again with the same kind and effector moves the target (and weight) without restarting. While
    /// the character's AnimLod has IkSolver::None the overlay fades out and back in when IK returns.
    /// Returns false for another kind or a character out of range. Wakes a resting character.
    bool set_overlay(uint32_t character, const MotionRequest& request, float weight = 1.0f);
    /// Fades the overlay of `character` out over `seconds` (0 = at the next update); no-op without one.
    void clear_overlay(uint32_t character, float seconds = 0.2f);
    /// Weight the overlay of `character` is shown with now (0 when it has none).
    [[nodiscard]] float overlay_weight(uint32_t character) const;

    /// Advances every active character by `dt` seconds and poses those due this frame (per
    /// AnimLod::update_interval; a character with interval N is posed when (frame + id) % N == 0,
    /// or at once when its request changes, so throttled characters spread evenly over N frames).
    /// Spans are indexed by element_of_character[c] for character c (empty = by character id);
    /// every index used must be in range of every span. Returns the number of characters posed.
    /// Requires dt >= 0.
    size_t update(float dt, std::span<const AnimLod> lods, std::span<MotionState> states,
                  std::span<Transform> transforms, std::span<Velocity> velocities,
                  std::span<const uint32_t> element_of_character = {});
    /// Runs fn(begin, end) over [0, count) in chunks of `grain`, possibly in parallel on the calling
    /// TBB arena (a host scheduler's parallel_for, so its traces and thread count apply).
    using ChunkRunner = std::function<void(size_t count, size_t grain, const std::function<void(size_t, size_t)>& fn)>;

    /// update() with the pose evaluation split into chunks of `grain` due characters (grain 0 = 64)
    /// run by `run_chunks` (empty = tbb::parallel_for). Same results, bit for bit, as update().
    /// Hooks must be thread-safe per character.
    size_t update_parallel(float dt, std::span<const AnimLod> lods, std::span<MotionState> states,
                           std::span<Transform> transforms, std::span<Velocity> velocities,
                           std::span<const uint32_t> element_of_character = {}, size_t grain = 0,
                           const ChunkRunner& run_chunks = {});

    /// Phase 1 of an update (serial): the bookkeeping of update(); returns the number of
    /// characters due for a pose this frame. The spans must stay valid until evaluate_due is done.
    size_t begin_update(float dt, std::span<const AnimLod> lods, std::span<MotionState> states,
                        std::span<Transform> transforms, std::span<Velocity> velocities,
                        std::span<const uint32_t> element_of_character = {});
    /// Phase 2: work items [begin, end) of the last begin_update (see work_count()) using scratch slot
    /// `worker` (< worker_slots()). Disjoint ranges with distinct workers may run concurrently.
    void evaluate_due(size_t begin, size_t end, size_t worker = 0);
    /// Sets the number of scratch slots for concurrent evaluate_due calls (at least 1). Not during an update.
    void set_worker_slots(size_t count);
    /// Active characters per block of update_parallel's phase 1 (blocks run concurrently; default 2048,
    /// at least 1). Results do not depend on it. Not during an update.
    void set_step_block(size_t count) { step_block_ = std::max<size_t>(1, count); }
    /// Lets phase 1 step characters in a steady request (a looping clip, a straight clip walk facing its
    /// way, a reach or look-at) from a small record of their own (on by default); off, every step is the
    /// full one. Results do not depend on it. Not during an update.
    void set_steady_steps(bool on);
    /// Characters the last update stepped by the steady step (work counter).
    [[nodiscard]] size_t steady_count() const { return steady_count_; }
    /// Scratch slots available to evaluate_due.
    [[nodiscard]] size_t worker_slots() const { return workers_; }
    /// Where evaluate_due adds the wall time (ns) of each work item, at anim_cost_slot(AnimLod::level,
    /// walking) (walking: the character's current request is a walk; slots past the end are not
    /// timed); empty (the default) times nothing. The frame budget's animation part learns its costs
    /// per level and cost class from it. The span must outlive the updates.
    void set_level_timing(std::span<uint64_t> level_ns) { level_ns_ = level_ns; }
    /// What the next updates may leave out, per element (indexed like the update's spans; values
    /// PoseUse). Empty (the default): every pose is read every frame. The span must outlive the updates.
    void set_pose_use(std::span<const uint8_t> use) { pose_use_ = use; }
    /// Characters whose pooled pose is stale (left out while PoseUse::Unseen).
    [[nodiscard]] bool stale(uint32_t character) const { return hot_[character].stale != 0; }
    /// Characters due in the last begin_update, in evaluation order.
    [[nodiscard]] size_t due_count() const { return due_.size(); }
    /// Work items of the last begin_update for evaluate_due: the due characters, then the throttled
    /// characters shown interpolated between their updates.
    [[nodiscard]] size_t work_count() const { return due_.size() + between_.size(); }
    /// Characters currently interpolating between throttled updates.
    [[nodiscard]] size_t interpolating() const { return keys_.in_use(); }

    /// Characters in motion, packed (characters at rest are not in it).
    [[nodiscard]] std::span<const uint32_t> active() const { return active_; }
    /// Number of characters.
    [[nodiscard]] size_t capacity() const { return chars_.size(); }
    /// Requests waiting behind the current one for `character`.
    [[nodiscard]] size_t queued(uint32_t character) const { return chars_[character].count; }
    /// The request `character` is executing (kind Rest when idle).
    [[nodiscard]] const MotionRequest& current(uint32_t character) const { return chars_[character].cur.req; }
    /// True while `character` is cross-fading into its current request.
    [[nodiscard]] bool fading(uint32_t character) const { return chars_[character].fade_left > 0.0f; }
    /// True while `character` is in any transition: a request cross-fade or an inertialized level change.
    [[nodiscard]] bool in_transition(uint32_t character) const {
        const Character& ch = chars_[character];
        return ch.fade_left > 0.0f || (ch.inertial_slot >= 0 && !ch.inertial_done);
    }
    /// Characters whose pose carries a decaying offset from an animation level change.
    [[nodiscard]] size_t inertializing() const { return inertia_.in_use(); }
    /// The walk method `lod` gives with the methods this controller has (a level asking for a method
    /// the character lacks falls back: dynamic -> kinematic -> clip playback).
    [[nodiscard]] WalkMethod resolved_walk_method(const AnimLod& lod) const { return walk_method(lod); }
    /// The pose pool (slot i = character i).
    [[nodiscard]] const PosePool& poses() const { return pool_; }
    /// The skeleton animated.
    [[nodiscard]] const Skeleton& skeleton() const { return *skeleton_; }

private:
    struct Channel {
        MotionRequest req;
        float time = 0.0f;          // clip time (PlayClip / ClipPlayback walk)
        float request_time = 0.0f;  // seconds since start
        uint32_t path_cursor = 0;
        int32_t walk_clip = -1;     // gait cycle a Walk request plays at the ClipPlayback level
        float walk_natural = 0.0f;  // that clip's root_speed() (m/s), read every frame the clock runs
        uint8_t done = 0;
        uint8_t travelling = 0;     // PlayClip: its root motion moved the character at kTravellingSpeed or more this frame
        SamplingCache cache;
        KinematicWalkState walk;
        // A turn that left the rotation as it was: the same rotation, direction and step (bit for bit)
        // leave it again, so a walker facing its way skips turn_towards (max_turn < 0: none yet).
        glm::quat faced{1.0f, 0.0f, 0.0f, 0.0f};
        glm::vec3 faced_dir{0.0f};
        float faced_max_turn = -1.0f;
    };
    struct Overlay {
        MotionRequest req;
        float time = 0.0f;      // seconds since it was set
        float presence = 0.0f;  // 0..1, ramps linearly towards 1 (0 once cleared or while the LOD has no IK)
        float weight = 0.0f;    // the caller's weight; shown as weight * smoothstep(presence)
        float fade_s = 0.0f;    // seconds for a whole 0 <-> 1 ramp of presence
        uint8_t on = 0;         // set and not yet faded out
        uint8_t first = 0;      // not evaluated since it was set
        uint8_t cleared = 0;    // fading out for good
        uint8_t shown_zero = 0; // last posed at weight 0
        /// True when the character must be posed this frame for the overlay (it started, or it has
        /// faded out and the pose beneath must be shown once exactly).
        [[nodiscard]] bool needs_pose() const { return first || (cleared && presence <= 0.0f && !shown_zero); }
    };
    // Everything else of a character (what a request switch, a fade, an overlay or a pose reads). Phase 1
    // of a character in a steady request reads only its Hot record; the request queue (read only when a
    // request starts) lives apart in queues_.
    struct Character {
        Channel cur;
        float fade_left = 0.0f, fade_total = 0.0f;
        uint8_t fade_snapshot = 0;   // fade from the snapshot pose (else from the live prev channel)
        uint8_t has_walk_method = 0;
        WalkMethod walk_method = WalkMethod::ClipPlayback;
        uint8_t head = 0, count = 0;
        int32_t active_index = -1;
        uint8_t slots_in_use = 0;    // bit per MethodSlot used by the current request
        Overlay overlay;             // reach / look-at layered over the current request
        int32_t inertial_slot = -1;  // InertialOffsets slot while a level change is inertialized
        float inertial_elapsed = 0.0f, inertial_total = 0.0f;  // seconds into / of the transition
        uint8_t inertial_pending = 0;  // the offset is taken at the next pose (the change happened this frame)
        uint8_t inertial_done = 0;     // posed with the offset gone: the slot is released at the next update
        uint8_t inertial_wrap = 0;     // the transition is a looping clip's wrap: the root's travel is not faded
        uint8_t shown = 0;             // 1 once a pose has been evaluated (before: the pool holds the stance)
        Channel prev;                  // the request faded from (while fade_left > 0 and !fade_snapshot)
    };
    // What a steady step can be (Hot::steady): a looping clip, one whose root motion moves the character, a straight
    // walk played from a clip that already faces its way, a reach or look-at; None = the full step (step_active).
    enum class Steady : uint8_t { None = 0, Clip = 1, WalkClip = 2, Hold = 3, RootClip = 4 };
    // Phase 1's record of a character (80 bytes; Character is ~460): the counters every step reads and
    // writes, and, while `steady` is set, all a step of the current request needs (step_steady), whose
    // clocks then live here: Character::cur's copies are written back when it is posed and before any
    // full step or change (leave_steady).
    struct alignas(16) Hot {
        float time = 0.0f, request_time = 0.0f;  // steady: cur's clip clock and seconds since the start
        float rate = 0.0f;                       // steady: clip seconds per second (clock_rate(cur))
        float phase = 0.0f;                      // steady: cur.walk.phase (a clip walk leaves it)
        glm::vec3 velocity{0.0f};                // WalkClip: direction * speed, as advance() computes it
        float faced_max_turn = -1.0f;            // WalkClip: cur.faced_max_turn
        glm::quat faced{1.0f, 0.0f, 0.0f, 0.0f}; // WalkClip: cur.faced (turn() returns it unchanged)
        int64_t last_anim = -1;        // anim_signature of the AnimLod at the last update (-1 before the first)
        float since_posed = 0.0f;      // seconds since the last pose
        float since_locked = 0.0f;     // seconds since the foot lock last saw this character
        float keys_span = 0.0f;        // seconds from the start to the end key pose
        int32_t keys_slot = -1;        // ThrottleKeys slot while interpolating between throttled updates
        Steady steady = Steady::None;
        RequestKind kind = RequestKind::Rest;  // steady: cur.req.kind
        uint8_t stale = 0;             // posing skipped while unseen: the pool's pose (and keys) are old
        uint8_t keys_stale = 0;        // posed without its interpolation keys (read at updates only)
        uint16_t clip = 0;             // RootClip: cur.req.clip
        uint8_t travelling = 0;        // RootClip: cur.travelling
    };
    struct Due {
        uint32_t character;
        uint32_t element;
        float posed_dt;
        bool started;  // the request started this frame
    };
    void activate(uint32_t c);
    void start_next(uint32_t c, Character& ch);
    void begin_fade(uint32_t c, Character& ch, float seconds, bool live_prev);
    void advance(Channel& ch, const AnimLod& lod, float dt, Transform* placement, Velocity* velocity);
    WalkMethod walk_method(const AnimLod& lod) const;
    // turn_towards (controller.cpp) unless `ch` already faces `dir` with exactly this rotation and step.
    static glm::quat turn(Channel& ch, const glm::quat& rotation, const glm::vec3& dir, float max_angle);
    void evaluate(uint32_t c, Channel& ch, const AnimLod& lod, const PoseView& out, Transform& placement,
                  Velocity& velocity, float posed_dt, bool primary, bool first);
    void pose_one(const Due& d, size_t worker);
    // Runs the foot lock on the pose `d`'s character shows this frame (last, after keys and offsets).
    void lock_feet(const Due& d);
    // Leaves character `c`'s pose stale (nobody reads it; posed at once when it is seen again) and forgets its foot
    // lock: the walk goes on unshown, so when it is seen again its feet are elsewhere (FootLock::reset).
    void leave_stale(uint32_t c, Hot& h);
    void update_slots(uint32_t c, Character& ch);
    // Phase 1's output of one block of walk_ (blocks run concurrently, merged in order afterwards).
    struct StepBlock {
        std::vector<Due> due, between;
        std::vector<uint32_t> resting;  // characters to take out of active_
        size_t steady = 0;              // characters stepped by step_steady
    };
    // An active character and its element (phase 1 walks these in element order: the rows stream).
    struct Walker {
        uint32_t character, element;
    };
    // Rebuilds walk_ (active_ in element order) when active_ or the element map changed since it was built.
    void refresh_walk(std::span<const uint32_t> element_of_character, size_t elements);
    size_t begin_update_blocks(float dt, std::span<const AnimLod> lods, std::span<MotionState> states,
                               std::span<Transform> transforms, std::span<Velocity> velocities,
                               std::span<const uint32_t> element_of_character, const ChunkRunner* run_chunks);
    void step_active(const Walker& w, float dt, std::span<MotionState> states, StepBlock& out);
    // The step of a character in a steady request from its Hot record alone (controller_steady.cpp), the same
    // bits as step_active; false (nothing done) when it is not steady or its level or rotation changed.
    bool step_steady(const Walker& w, float dt, std::span<MotionState> states, StepBlock& out);
    // Where a step of `c` (element `e`) stands in its update schedule this frame.
    struct Schedule {
        uint64_t interval;  // AnimLod::update_interval, at least 1
        bool on_phase;      // its turn in the interval
        PoseUse use;        // what reads its pose (pose_use_)
    };
    // Advances the counters of every step (since posed, since locked, frames since update) and says where
    // the character stands in its schedule.
    Schedule tick(uint32_t c, uint32_t e, Hot& h, MotionState& st, const AnimLod& lod, float dt);
    // Lists `c` due this frame (`started`: its request started) and resets its counters, takes or gives back
    // its interpolation keys (`interpolate`) and sets their span to its next scheduled update.
    void mark_due(uint32_t c, uint32_t e, Hot& h, MotionState& st, const Schedule& s, bool interpolate, bool started,
                  float dt, StepBlock& out);
    // After a full step: marks `c` steady (and fills its Hot record) when its next step can be step_steady's.
    void enter_steady(uint32_t c, const Character& ch, const Transform& placement);
    // Writes a steady character's clocks back to its Character and clears `steady` (before a full step or a change).
    void leave_steady(uint32_t c);
    // leave_steady for every character (a setter changed what the steps compute).
    void leave_steady_all();
    static int64_t anim_signature(const AnimLod& l) { return motion_detail::anim_signature(l); }
    // Walk positions phase 1 prefetches ahead of the one it steps (their Hot records).
    static constexpr size_t kStepPrefetch = 8;
    // Prefetches the Hot record of walk_[k]'s character.
    void prefetch_step(size_t k) const;
    void sample_walk_clip(Channel& ch, const PoseView& out) const;
    bool clip_driven(const Character& ch, const AnimLod& lod) const;
    // Whether `ch` plays a looping clip whose ends do not meet (AnimationClip::ends_meet) and its clock crossed the
    // clip's end this step, from `before` (either way): the pose jumps there unless inertialized.
    bool jumped_at_wrap(const Channel& ch, float before) const;
    // `ahead`, a copy of a channel advanced from `from` for a throttled character's next key, stopped short of a
    // jumping wrap (jumped_at_wrap): the keys carry the pose to the clip's end, and the update that crosses the wrap
    // inertializes it from there (interpolating across it would show the jump spread over the interval).
    void stop_before_wrap(Channel& ahead, float from) const;
    // True when `ch` walks by the kinematic walk at `lod` (its pose predictable one interval ahead
    // from the phase and the placement moving at its velocity).
    bool kinematic_walking(const Character& ch, const AnimLod& lod) const;
    void advance_clock(Channel& ch, float seconds) const;
    // The clip `ch` plays when it is a PlayClip whose root motion is given to the transform (the request asks for it
    // and the clip's root moves: root_motion.hpp); nullptr otherwise.
    const AnimationClip* root_moving_clip(const Channel& ch) const;
    // Moves `placement` by `clip`'s root motion from clip time `before` to `after` (root_motion.hpp), sets `velocity`
    // (when given) to the step over `dt`, and runs `walk`'s phase at the rig's stride for that speed while it is
    // travelling (`travelling` set; cleared otherwise). The one place advance() and the steady step do it.
    void move_by_root(const AnimationClip& clip, float before, float after, bool loop, float dt, Transform& placement,
                      Velocity* velocity, KinematicWalkState& walk, uint8_t& travelling) const;
    // Clip seconds per second of `ch`'s clock (PlayClip: its speed; a clip walk: speed over the clip's natural speed).
    static float clock_rate(const Channel& ch);
    // Horizontal unit direction a Walk without a path heads in (its target, else facing `rotation`).
    static glm::vec3 straight_direction(const MotionRequest& r, const glm::quat& rotation);
    static constexpr float kTurnRate = 6.0f;  // rad/s: how fast a walker turns to face its direction of travel
    // Carries a walk's place in its cycle across a change between clip playback and the procedural
    // walks (their clocks run only while used): clip time <-> phase * the clip's duration (the gait
    // cycle starts at the left touchdown, as the kinematic walk's phase 0), and a kinematic walk
    // re-entered plants its feet afresh.
    void sync_walk_clock(Channel& ch, WalkMethod from, WalkMethod to) const;
    void advance_overlay(Overlay& o, const AnimLod& lod, float dt) const;
    void apply_overlay(uint32_t c, Character& ch, const AnimLod& lod, const PoseView& pose, Transform& placement,
                       Velocity& velocity, float posed_dt, bool primary);

    const Skeleton* skeleton_;
    const ClipLibrary* clips_;
    std::optional<WalkRig> rig_;
    std::optional<FootLock> foot_lock_;  // with the walk rig
    FootLockParams foot_lock_params_;
    bool foot_lock_on_ = true;
    GaitParams gait_;
    std::vector<ClipId> walk_clips_;       // gait cycles, any order
    std::vector<float> walk_clip_speeds_;  // their natural speeds (m/s)
    std::array<MethodHook, 3> hooks_{};
    std::array<void*, 3> hook_users_{};
    std::array<MethodRelease, 3> releases_{};
    struct WalkPath {
        std::vector<glm::vec3> points;
        bool loop = false;
    };
    std::vector<WalkPath> paths_;
    std::vector<Character> chars_;
    std::vector<Hot> hot_;  // per character, phase 1's record
    std::vector<std::array<MotionRequest, kQueueCapacity>> queues_;  // per character: queued requests (ring at head)
    std::vector<uint32_t> active_;
    std::vector<Walker> walk_;          // active_ in element order, rebuilt by refresh_walk
    std::vector<uint32_t> walk_map_;    // the element map walk_ was built with (empty: identity)
    std::vector<uint32_t> by_element_;  // refresh_walk's scratch: the character at each element
    std::vector<uint32_t> walk_moved_, walk_from_, walk_to_;  // refresh_walk's scratch: who moved, from, to
    bool walk_dirty_ = true;            // active_ changed since walk_ was built
    PosePool pool_;      // slot i = character i
    PosePool snapshot_;  // slot i = pose character i fades from
    PosePool scratch_;   // slot w = worker w's pose of the request faded from
    size_t workers_ = 1;
    uint64_t frame_ = 0;  // updates so far (phase of throttled characters)
    std::vector<Due> due_;
    std::vector<Due> between_;  // throttled characters shown interpolated this frame
    std::vector<StepBlock> blocks_;  // phase 1 scratch per block of active_
    size_t step_block_ = 2048;       // active characters per block of phase 1
    bool steady_steps_ = true;       // set_steady_steps
    size_t steady_count_ = 0;        // steady_count
    std::mutex slots_mutex_;         // keys_, inertia_ and method releases while phase 1 runs in blocks
    ThrottleKeys keys_;
    InertialOffsets inertia_;
    void settle_inertia(Character& ch, const PoseView& pose, float elapsed);
    // Spans of the update in progress (set by begin_update, read by evaluate_due).
    std::span<const AnimLod> lods_;
    std::span<Transform> transforms_;
    std::span<Velocity> velocities_;
    std::span<uint64_t> level_ns_;  // per AnimLod level: ns of work items (empty = not timed)
    std::span<const uint8_t> pose_use_;  // per element: PoseUse (empty = EveryFrame for all)
};

/// Job form of MotionController::update over spans of characters (index = character id, or
/// element_of_character[id] when given).
struct MotionUpdateJob {
    MotionController* controller = nullptr;  ///< required
    float dt = 0.0f;                         ///< seconds since the last frame (>= 0, finite)
    std::span<const AnimLod> lods;           ///< per character, controller->capacity() elements
    std::span<MotionState> states;           ///< per character, written for active characters only
    std::span<Transform> transforms;         ///< per character; walking moves them (root motion)
    std::span<Velocity> velocities;          ///< per character; walking sets them
    std::span<const uint32_t> element_of_character{};  ///< optional: element of character c (distinct, in range)
    size_t grain = 0;                        ///< 0 = serial; else parallel chunks of this many characters
    MotionController::ChunkRunner run_chunks{};  ///< optional: who runs the chunks (default: TBB)
    std::span<const uint8_t> pose_use{};     ///< optional, per element: PoseUse (empty = every pose read every frame)

    /// True when the job can run; appends one message per failure to `errors` when given.
    bool Validate(std::vector<std::string>* errors = nullptr) const;
    /// Runs the update; returns the number of characters posed. Requires Validate().
    size_t Run() const;
};

}  // namespace aloha
