// The switch-hitch reading of `aloha profile`: the CPU systems' slowest frame against their p95, over all
// measured frames and apart for the frames with a level switch and those without. A switch hitch (a
// level's geometry built on the switch frame) shows on the frames with a switch; a slow frame with no
// switch in it is something else (the machine stalling the thread, the crowd's own work), and the worst
// frame's slowest system against that system's median says which.
#pragma once

#include <nlohmann/json.hpp>

#include <span>
#include <string>
#include <vector>

namespace aloha::tool {

/// One measured frame as the hitch reading sees it.
struct HitchFrame {
    double cpu_ms = 0;              ///< the CPU systems' time of the frame
    uint32_t switches = 0;          ///< geometric + animation level changes in the frame
    std::vector<double> system_ms;  ///< each scheduler system's time (the same systems every frame)
};

/// The reading. `bar` is the largest max / p95 allowed (DESIGN.md: 3). Requires system_names to name each
/// entry of every frame's system_ms. Returns {p95_ms, bar, all, with_switch, without_switch, worst_frame}:
/// all / with_switch / without_switch are {frames, max_ms, max_over_p95, within_bar} against the p95 of
/// all frames (null figures when that side has no frame); worst_frame is {index, cpu_ms, switches, system,
/// system_ms, system_p50_ms} for the slowest frame and its slowest system. An empty input gives null.
[[nodiscard]] nlohmann::json switch_hitch_report(std::span<const HitchFrame> frames, std::span<const std::string> system_names,
                                                 double bar = 3.0);

/// One printed line of the reading (ends in a newline); empty when the report is null.
[[nodiscard]] std::string switch_hitch_line(const nlohmann::json& report);

}  // namespace aloha::tool
