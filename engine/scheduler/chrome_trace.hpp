// Writes trace events in the Chrome Trace Event JSON format (opens in Perfetto / chrome://tracing).
#pragma once

#include <span>
#include <string>

#include "engine/core/result.hpp"
#include "engine/scheduler/timing.hpp"

namespace aloha {

/// The Chrome Trace Event JSON for `events`: one "X" (complete) event per entry, named
/// names[event.system] ("system N" when out of range), tid = arena thread, microsecond times,
/// plus thread-name metadata events.
[[nodiscard]] std::string chrome_trace_json(std::span<const TraceEvent> events,
                                            std::span<const std::string> names);

/// Writes chrome_trace_json(events, names) to `path`; the error names the file and the reason.
Status write_chrome_trace(const std::string& path, std::span<const TraceEvent> events,
                          std::span<const std::string> names);

}  // namespace aloha
