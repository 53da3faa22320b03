// Writes trace events in the Chrome Trace Event JSON format (opens in Perfetto / chrome://tracing).
#pragma once

#include <span>
#include <string>

#include "engine/core/result.hpp"
#include "engine/scheduler/timing.hpp"

namespace aloha {

/// Track (tid) of system `system`'s whole runs; worker threads use their arena slot as tid.
inline constexpr uint32_t kSystemTrackBase = 1000;
/// Track (tid) of GPU passes (TraceKind::Gpu), named "GPU passes", listed last.
inline constexpr uint32_t kGpuTrack = 3000;

/// The Chrome Trace Event JSON for `events`: one "X" (complete) event per entry, named
/// names[event.system] ("system N" when out of range), microsecond times. One track per system
/// (TraceKind::System events, tid kSystemTrackBase + system, named "system: NAME", listed first)
/// and one per arena thread (TraceKind::Work events, tid = thread, named "worker N"), declared by
/// thread-name and sort-index metadata events; TraceKind::Gpu events go on track kGpuTrack.
[[nodiscard]] std::string chrome_trace_json(std::span<const TraceEvent> events,
                                            std::span<const std::string> names);

/// Writes chrome_trace_json(events, names) to `path`; the error names the file and the reason.
Status write_chrome_trace(const std::string& path, std::span<const TraceEvent> events,
                          std::span<const std::string> names);

}  // namespace aloha
