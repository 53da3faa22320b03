// Whether a frame's GPU work is left in flight while the next frame's CPU systems run (two frames in flight)
// or waited for before the frame ends (serial): on, off, or chosen frame by frame from the measured times.
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

namespace aloha {

/// How frames are paced against the GPU.
enum class GpuOverlap : uint8_t {
    Off,   ///< every frame waits for its GPU work: a frame's latency is its CPU plus GPU time
    On,    ///< every frame leaves its GPU work in flight: the GPU draws it while the next frame's CPU systems run
    Auto,  ///< overlapped while the GPU's frame is too long for the frame rate and there is CPU time to hide
};

/// The mode's name as the command line and the report spell it: "off", "on", "auto".
[[nodiscard]] inline std::string_view gpu_overlap_name(GpuOverlap mode) {
    return mode == GpuOverlap::On ? "on" : mode == GpuOverlap::Auto ? "auto" : "off";
}
/// The mode a name spells ("off", "on", "auto"); nullopt for anything else.
[[nodiscard]] inline std::optional<GpuOverlap> parse_gpu_overlap(std::string_view name) {
    if (name == "off") return GpuOverlap::Off;
    if (name == "on") return GpuOverlap::On;
    if (name == "auto") return GpuOverlap::Auto;
    return std::nullopt;
}

/// GpuOverlap::Auto's thresholds. Overlap hides at most the shorter of the CPU systems' and the GPU's time
/// and costs a frame of latency and, on a software rasteriser sharing the CPU's cores, noise in the CPU
/// systems' times (their rasteriser threads run beside them): worth it only while the frame cannot make its
/// rate serially. So it starts once the smoothed GPU time passes `enter_gpu_ms` with at least `min_cpu_ms` of
/// CPU systems to hide behind it, and stops once the GPU time falls under `leave_gpu_ms` or the CPU time
/// under half of `min_cpu_ms` (the gaps keep a frame near a threshold from switching back and forth).
struct GpuOverlapSettings {
    double enter_gpu_ms = 16.7;  ///< a 60 Hz frame: shorter GPU frames already make the rate serially
    double leave_gpu_ms = 12.5;  ///< < enter_gpu_ms
    double min_cpu_ms = 1.0;     ///< less CPU time than this is not worth a frame of latency
    double smoothing = 0.2;      ///< weight of the newest frame in the moving averages, (0, 1]
};

/// Decides frame by frame whether to overlap (GpuOverlap::Auto) or applies a fixed mode. Plain state: one
/// per frame loop, fed each frame with the times measured so far.
class GpuOverlapPolicy {
public:
    /// Requires settings with 0 < leave_gpu_ms < enter_gpu_ms, min_cpu_ms >= 0 and smoothing in (0, 1].
    explicit GpuOverlapPolicy(GpuOverlap mode = GpuOverlap::Off, GpuOverlapSettings settings = {});

    /// Whether the frame about to be submitted should be left in flight. `cpu_ms`: the newest frame's CPU
    /// systems' time; `gpu_ms`: the newest GPU time measured (< 0: none yet, e.g. while the first frames are
    /// in flight; it is then left out of the average).
    bool decide(double cpu_ms, double gpu_ms);

    /// The last decision.
    [[nodiscard]] bool overlapping() const { return overlapping_; }
    /// The smoothed times Auto decides on (-1 before the first measurement).
    [[nodiscard]] double smoothed_cpu_ms() const { return cpu_ms_; }
    [[nodiscard]] double smoothed_gpu_ms() const { return gpu_ms_; }

private:
    GpuOverlap mode_;
    GpuOverlapSettings settings_;
    bool overlapping_ = false;
    double cpu_ms_ = -1.0;
    double gpu_ms_ = -1.0;
};

}  // namespace aloha
