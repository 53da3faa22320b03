// Per-system timing storage: a fixed-capacity ring of frame times and trace events.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace aloha {

/// Fixed-capacity ring of durations in nanoseconds, oldest overwritten first. Allocates only at
/// construction. Written by one thread at a time; read between frames.
class TimingRing {
public:
    /// Default capacity: frames of history kept per system.
    static constexpr size_t kDefaultCapacity = 4096;

    /// Creates an empty ring holding at most `capacity` (>= 1) values.
    explicit TimingRing(size_t capacity = kDefaultCapacity) : values_(capacity == 0 ? 1 : capacity) {}

    /// Appends `ns`, dropping the oldest value when full.
    void push(uint64_t ns) {
        values_[head_] = ns;
        head_ = head_ + 1 == values_.size() ? 0 : head_ + 1;
        if (size_ < values_.size()) ++size_;
        ++total_;
    }
    /// Number of values held (<= capacity()).
    [[nodiscard]] size_t size() const { return size_; }
    /// Maximum number of values held.
    [[nodiscard]] size_t capacity() const { return values_.size(); }
    /// Number of values ever pushed.
    [[nodiscard]] uint64_t total_pushed() const { return total_; }
    /// The i-th held value, 0 = oldest; requires i < size().
    [[nodiscard]] uint64_t at(size_t i) const {
        const size_t start = (head_ + values_.size() - size_) % values_.size();
        return values_[(start + i) % values_.size()];
    }
    /// The newest value; requires size() > 0.
    [[nodiscard]] uint64_t latest() const { return at(size_ - 1); }
    /// Mean of the held values in nanoseconds (0 when empty).
    [[nodiscard]] double mean_ns() const {
        if (size_ == 0) return 0.0;
        double sum = 0.0;
        for (size_t i = 0; i < size_; ++i) sum += static_cast<double>(at(i));
        return sum / static_cast<double>(size_);
    }
    /// Forgets every value.
    void clear() {
        head_ = 0;
        size_ = 0;
        total_ = 0;
    }

private:
    std::vector<uint64_t> values_;
    size_t head_ = 0;
    size_t size_ = 0;
    uint64_t total_ = 0;
};

/// What a trace event spans: a whole system run, one thread's share of a system's parallel_for
/// (from the first chunk it ran to the end of its last), or a GPU pass (timestamps placed on the CPU clock
/// by whoever adds them; `system` then indexes the names after the scheduler's).
enum class TraceKind : uint8_t { System, Work, Gpu };

/// One system run (or one thread's work inside it): which system, on which arena thread, when
/// (ns since the scheduler started).
struct TraceEvent {
    uint32_t system = 0;     ///< index of the system in the scheduler (add() order)
    uint32_t thread = 0;     ///< arena thread slot that ran it (0 .. threads-1)
    uint64_t begin_ns = 0;   ///< start, nanoseconds since the scheduler's epoch
    uint64_t end_ns = 0;     ///< end, nanoseconds since the scheduler's epoch
    uint64_t frame = 0;      ///< frame index the run belongs to
    TraceKind kind = TraceKind::System;  ///< whole run or a thread's parallel work
};

/// Per-system record of the arena threads that ran its parallel_for chunks this frame (tracing
/// only). Each thread writes only its own `per_thread` entry; `events` is appended by the thread
/// running the system, after each parallel_for.
struct WorkSpans {
    struct Span {
        uint64_t begin_ns = 0, end_ns = 0;  ///< 0, 0 = no chunk on this thread yet
    };
    std::vector<Span> per_thread;     ///< indexed by arena thread slot (sized to the thread count)
    std::vector<TraceEvent> events;   ///< closed spans of this frame (TraceKind::Work)
};

}  // namespace aloha
