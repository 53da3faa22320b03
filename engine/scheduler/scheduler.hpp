// Scheduler: derives passes from systems' read/write declarations, runs them phase by phase on a
// oneTBB arena, and records per-system timings and trace events.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include "engine/core/result.hpp"
#include "engine/ecs/command_buffer.hpp"
#include "engine/ecs/registry.hpp"
#include "engine/scheduler/phase.hpp"
#include "engine/scheduler/system.hpp"
#include "engine/scheduler/timing.hpp"

namespace aloha {

/// One pass: systems of one phase that run together (their access sets do not conflict).
struct Pass {
    Phase phase;
    std::vector<uint32_t> systems;  ///< system indices, in add() order
};

/// Orders and runs systems. Typical use: construct with the host's phases, add() systems, build(), then
/// run_frame(dt) every frame.
class Scheduler {
public:
    /// Creates a scheduler running the host's `phases` (in order) with `threads` threads (0 = oneTBB's
    /// default concurrency). build() checks the list (1 to kMaxPhases unique, non-empty names).
    explicit Scheduler(PhaseList phases, unsigned threads = 0);
    ~Scheduler();
    Scheduler(const Scheduler&) = delete;
    Scheduler& operator=(const Scheduler&) = delete;

    /// Adds a system; returns its index. Invalidates the plan (call build() again).
    uint32_t add(SystemDesc desc);
    /// Derives the passes. Fails (listing every problem) on a bad phase list, a system's phase outside it,
    /// empty/duplicate names, missing run
    /// functions, two systems of one phase writing the same type (message names both and the
    /// type), or a read/write cycle inside a phase.
    Status build();
    /// True after a successful build() with no add() since.
    [[nodiscard]] bool built() const { return built_; }

    /// Sets the thread count of the arena (>= 1; 0 = default concurrency). Not during a frame.
    void set_threads(unsigned threads);
    /// Threads of the arena.
    [[nodiscard]] unsigned threads() const { return threads_; }
    /// Hook called after every phase (with that phase), on the calling thread; apply command
    /// buffers there.
    void set_between_phases(std::function<void(Phase)> hook) { between_phases_ = std::move(hook); }
    /// Sink receiving every trace event after each frame (calling thread): each system's run in
    /// system order, then each system's per-thread parallel work (TraceKind::Work). While a sink is
    /// set, parallel_for notes which thread ran what (two clock reads per task).
    void set_trace_sink(std::function<void(const TraceEvent&)> sink) { trace_sink_ = std::move(sink); }

    /// Runs every phase once; requires built(). Frame index advances by one.
    void run_frame(float dt);
    /// Applies every system's command buffer to `registry` in system order; returns commands
    /// skipped for dead targets. Call it from the between-phases hook.
    size_t apply_commands(Registry& registry);

    /// The host's phases, in run order.
    [[nodiscard]] const PhaseList& phases() const { return phases_; }
    /// The derived passes, phases in order.
    [[nodiscard]] const std::vector<Pass>& plan() const { return plan_; }
    /// The derived passes as lists of system names.
    [[nodiscard]] std::vector<std::vector<std::string>> passes() const;
    /// Human-readable plan: phases, passes, each system's reads and writes.
    [[nodiscard]] std::string describe() const;

    /// Number of systems added.
    [[nodiscard]] size_t system_count() const { return systems_.size(); }
    /// Names of the systems, by index (the `names` argument of write_chrome_trace).
    [[nodiscard]] const std::vector<std::string>& names() const { return names_; }
    /// Index of the system called `name`, or -1.
    [[nodiscard]] int find(const std::string& name) const;
    /// Wall time of system `index` for the last frames (ns); requires index < system_count().
    [[nodiscard]] const TimingRing& timings(uint32_t index) const { return timings_[index]; }
    /// Wall time of the system called `name`, or nullptr when there is none.
    [[nodiscard]] const TimingRing* timings(const std::string& name) const;
    /// Sum of the last frame's run times (ns) of the systems in phases before `phase` (e.g.
    /// the host's render phase: every CPU system), systems of one pass each counted; 0 before the first frame.
    [[nodiscard]] uint64_t latest_ns_before(Phase phase) const;
    /// Wall time of whole frames (ns), including between-phase hooks.
    [[nodiscard]] const TimingRing& frame_timings() const { return frame_timings_; }
    /// Trace events of the last frame, one per system, indexed by system.
    [[nodiscard]] std::span<const TraceEvent> last_frame_trace() const { return frame_events_; }
    /// Frames run so far.
    [[nodiscard]] uint64_t frame() const { return frame_; }

private:
    void run_system(uint32_t index, float dt);
    [[nodiscard]] uint64_t now_ns() const;

    PhaseList phases_;
    std::vector<SystemDesc> systems_;
    std::vector<std::string> names_;
    std::vector<Pass> plan_;
    std::vector<TimingRing> timings_;
    std::vector<TraceEvent> frame_events_;
    std::vector<WorkSpans> work_;
    std::vector<std::unique_ptr<CommandBuffer>> commands_;
    TimingRing frame_timings_;
    std::function<void(Phase)> between_phases_;
    std::function<void(const TraceEvent&)> trace_sink_;
    std::unique_ptr<tbb::task_arena> arena_;
    std::unique_ptr<tbb::global_control> control_;
    std::chrono::steady_clock::time_point epoch_;
    unsigned threads_ = 1;
    uint64_t frame_ = 0;
    bool built_ = false;
};

/// Derives passes for `systems` in the host's `phases` (see Scheduler::build); on failure `errors` gets every problem.
[[nodiscard]] std::vector<Pass> derive_passes(std::span<const SystemDesc> systems, const PhaseList& phases,
                                              std::vector<std::string>& errors);

}  // namespace aloha
