// The phases of an ALOHA frame, run in declaration order, and helpers to use them generically.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>

namespace aloha {

/// A frame is these phases in this order; structural changes are applied between them.
enum class Phase : uint8_t { Attributes, Rules, Resolve, Motion, Tessellate, Skin, Render };

/// Number of phases.
inline constexpr size_t kPhaseCount = 7;

/// Every phase, in run order.
inline constexpr std::array<Phase, kPhaseCount> kAllPhases{
    Phase::Attributes, Phase::Rules, Phase::Resolve, Phase::Motion,
    Phase::Tessellate, Phase::Skin,  Phase::Render};

/// Position of `p` in the run order (0 = Attributes).
constexpr size_t phase_index(Phase p) { return static_cast<size_t>(p); }

/// The phase's name as written in docs and traces ("Attributes", ...); "?" when out of range.
constexpr std::string_view phase_name(Phase p) {
    constexpr std::array<std::string_view, kPhaseCount> names{
        "Attributes", "Rules", "Resolve", "Motion", "Tessellate", "Skin", "Render"};
    return phase_index(p) < kPhaseCount ? names[phase_index(p)] : std::string_view("?");
}

}  // namespace aloha
