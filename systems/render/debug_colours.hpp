// Debug palettes: colour a character by its LOD level, the rule that fired, or its motion method.
// Every channel is a multiple of 1/255, so an unlit (ambient = 1) draw writes the palette value exactly.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>

namespace aloha {

/// Number of distinct colours in the LOD-level palette (levels beyond it wrap around).
inline constexpr int kLevelPaletteSize = 10;
/// Number of distinct colours in the rule palette (rule ids wrap around).
inline constexpr int kRulePaletteSize = 12;

/// Colour for geometric or animation LOD `level` (0 = richest: red, then orange, yellow, green, cyan,
/// blue, violet, grey). Negative levels give white. Alpha is 1.
[[nodiscard]] glm::vec4 colour_for_level(int level);

/// Colour for knowledge-base rule `rule_id` (12 well-separated hues, wrapping). Negative ids give white.
[[nodiscard]] glm::vec4 colour_for_rule(int rule_id);

/// Colour for a walk method as numbered by aloha::WalkMethod (0 clip playback: blue, 1 kinematic: green,
/// 2 dynamic: orange); other values give magenta.
[[nodiscard]] glm::vec4 colour_for_motion_method(int method);

/// Converts a palette colour to 8-bit RGBA exactly as a UNORM8 target stores it (round to nearest).
[[nodiscard]] glm::u8vec4 to_rgba8(glm::vec4 colour);

}  // namespace aloha
