// What a system declares to the scheduler (phase, reads, writes, body) and what it gets when run.
#pragma once

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>
#include <tbb/task_arena.h>

#include "engine/ecs/command_buffer.hpp"
#include "engine/ecs/type_id.hpp"
#include "engine/scheduler/phase.hpp"
#include "engine/scheduler/timing.hpp"

namespace aloha {

class SystemContext;

/// A system as the scheduler sees it. `reads`/`writes` name component types or resources
/// (component_type_id<T>(), resource_type_id<Tag>(), named_type_id("camera")); writing implies
/// reading. `run` must be callable.
struct SystemDesc {
    std::string name;                      ///< unique, used in messages, timings and traces
    Phase phase;                           ///< phase the system runs in (position in the host's PhaseList)
    std::vector<ComponentTypeId> reads;    ///< types only read
    std::vector<ComponentTypeId> writes;   ///< types written (and possibly read)
    std::function<void(SystemContext&)> run;  ///< the system body
};

/// The ids of Ts, for SystemDesc::reads.
template <class... Ts>
std::vector<ComponentTypeId> reads() {
    return {component_type_id<Ts>()...};
}

/// The ids of Ts, for SystemDesc::writes.
template <class... Ts>
std::vector<ComponentTypeId> writes() {
    return {component_type_id<Ts>()...};
}

/// What a running system gets: frame data, its deferred command buffer and a deterministic
/// parallel_for inside the scheduler's thread arena.
class SystemContext {
public:
    /// Built by the scheduler for each run. `work` (nullptr when not tracing) receives each
    /// thread's span of every parallel_for, in nanoseconds since `epoch` (the scheduler's).
    SystemContext(uint64_t frame, float dt, unsigned threads, uint32_t system, std::string_view name,
                  CommandBuffer* commands, WorkSpans* work = nullptr, std::chrono::steady_clock::time_point epoch = {})
        : frame_(frame), dt_(dt), threads_(threads), system_(system), name_(name), commands_(commands), work_(work),
          epoch_(epoch) {}

    /// Index of the current frame (0 for the first run_frame()).
    [[nodiscard]] uint64_t frame() const { return frame_; }
    /// Seconds this frame advances.
    [[nodiscard]] float dt() const { return dt_; }
    /// Threads of the scheduler's arena.
    [[nodiscard]] unsigned threads() const { return threads_; }
    /// Index of the running system (add() order).
    [[nodiscard]] uint32_t system_index() const { return system_; }
    /// Name of the running system.
    [[nodiscard]] std::string_view system_name() const { return name_; }
    /// This system's own command buffer (thread-safe because it is per system); the scheduler's
    /// apply_commands() applies all of them in system order.
    [[nodiscard]] CommandBuffer& commands() const { return *commands_; }

    /// Number of chunks parallel_for(count, grain, ...) makes: ceil(count / max(grain, 1)).
    [[nodiscard]] static size_t chunk_count(size_t count, size_t grain) {
        grain = std::max<size_t>(grain, 1);
        return (count + grain - 1) / grain;
    }
    /// Calls fn(begin, end) for the chunks [k*grain, min((k+1)*grain, count)), possibly in
    /// parallel. Chunk boundaries depend only on count and grain (never on the thread count), so
    /// per-chunk results combined in chunk order are identical with 1 or N threads.
    /// When tracing, each thread's share is recorded (see WorkSpans).
    template <class Fn>
    void parallel_for(size_t count, size_t grain, Fn&& fn) const {
        grain = std::max<size_t>(grain, 1);
        const size_t chunks = chunk_count(count, grain);
        if (chunks == 0) return;
        auto run_chunks = [&](size_t first, size_t last) {
            const uint64_t begin = work_ ? now_ns() : 0;
            for (size_t k = first; k < last; ++k) fn(k * grain, std::min(count, (k + 1) * grain));
            if (work_) note_work(begin, now_ns());
        };
        if (threads_ <= 1 || chunks <= 1) {
            run_chunks(0, chunks);
        } else {
            tbb::parallel_for(
                tbb::blocked_range<size_t>(0, chunks, 1),
                [&](const tbb::blocked_range<size_t>& r) { run_chunks(r.begin(), r.end()); },
                tbb::simple_partitioner());
        }
        if (work_) close_work();
    }

private:
    [[nodiscard]] uint64_t now_ns() const {
        return static_cast<uint64_t>(
            std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - epoch_).count());
    }
    // Widens the calling thread's span to [begin, end].
    void note_work(uint64_t begin, uint64_t end) const {
        const int t = tbb::this_task_arena::current_thread_index();
        if (t < 0 || static_cast<size_t>(t) >= work_->per_thread.size()) return;
        WorkSpans::Span& span = work_->per_thread[static_cast<size_t>(t)];
        span.begin_ns = span.end_ns == 0 ? begin : std::min(span.begin_ns, begin);
        span.end_ns = std::max(span.end_ns, end);
    }
    // Turns the threads' spans of the parallel_for just finished into events and clears them.
    void close_work() const {
        for (size_t t = 0; t < work_->per_thread.size(); ++t) {
            WorkSpans::Span& span = work_->per_thread[t];
            if (span.end_ns == 0) continue;
            work_->events.push_back({system_, static_cast<uint32_t>(t), span.begin_ns, span.end_ns, frame_, TraceKind::Work});
            span = {};
        }
    }

    uint64_t frame_;
    float dt_;
    unsigned threads_;
    uint32_t system_;
    std::string_view name_;
    CommandBuffer* commands_;
    WorkSpans* work_;
    std::chrono::steady_clock::time_point epoch_;
};

}  // namespace aloha
