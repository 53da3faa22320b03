// Frame pacing against the GPU: fixed or chosen from the smoothed CPU and GPU times (see gpu_overlap_policy.hpp).
#include "systems/frame/gpu_overlap_policy.hpp"

#include <cassert>

namespace aloha {

GpuOverlapPolicy::GpuOverlapPolicy(GpuOverlap mode, GpuOverlapSettings settings) : mode_(mode), settings_(settings) {
    assert(settings.leave_gpu_ms > 0.0 && settings.leave_gpu_ms < settings.enter_gpu_ms);
    assert(settings.min_cpu_ms >= 0.0 && settings.smoothing > 0.0 && settings.smoothing <= 1.0);
}

bool GpuOverlapPolicy::decide(double cpu_ms, double gpu_ms) {
    const auto smooth = [&](double& average, double sample) {
        average = average < 0.0 ? sample : average + settings_.smoothing * (sample - average);
    };
    if (cpu_ms >= 0.0) smooth(cpu_ms_, cpu_ms);
    if (gpu_ms >= 0.0) smooth(gpu_ms_, gpu_ms);
    switch (mode_) {
        case GpuOverlap::Off: overlapping_ = false; break;
        case GpuOverlap::On: overlapping_ = true; break;
        case GpuOverlap::Auto:
            if (gpu_ms_ < 0.0 || cpu_ms_ < 0.0) break;  // nothing measured yet: keep serial
            if (!overlapping_)
                overlapping_ = gpu_ms_ > settings_.enter_gpu_ms && cpu_ms_ >= settings_.min_cpu_ms;
            else
                overlapping_ = gpu_ms_ >= settings_.leave_gpu_ms && cpu_ms_ >= 0.5 * settings_.min_cpu_ms;
            break;
    }
    return overlapping_;
}

}  // namespace aloha
