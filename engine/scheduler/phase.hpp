// Phases as data: the host that owns a frame names its phases (a PhaseList, in run order) and gives them
// to its Scheduler; a system names its phase by position in that list. The scheduler knows no phase
// names of its own.
#pragma once

#include <compare>
#include <cstdint>
#include <string>
#include <vector>

namespace aloha {

/// A phase of the host's frame: its position in the host's PhaseList (0 runs first).
struct Phase {
    uint8_t index = 0;
    constexpr auto operator<=>(const Phase&) const = default;
};

/// The host's phases by name, in run order (1 to 255 of them, names unique and non-empty). Structural
/// changes are applied between phases (Scheduler::set_between_phases).
using PhaseList = std::vector<std::string>;

/// Largest number of phases a PhaseList may hold.
inline constexpr size_t kMaxPhases = 255;

}  // namespace aloha
