// Character picking for the viewer: which character a click lands on (its standing bounds projected
// to the screen), finding a character again after the World regroups, and the marker drawn around it.
#pragma once

#include "components/character.hpp"
#include "components/transform.hpp"
#include "systems/render/crowd_renderer.hpp"

#include <glm/glm.hpp>

#include <span>
#include <vector>

namespace aloha::tool {

/// Pixel position (origin top-left, y down, like mouse coordinates) of world point `p` seen by `camera`
/// in a `viewport` of pixels; false when p is behind the eye (clip w <= 0).
bool project_to_pixels(const RenderCamera& camera, glm::vec2 viewport, glm::vec3 p, glm::vec2* out);

/// Index of the character whose vertical axis (Transform::position up to Bounds::height, scaled)
/// passes nearest on screen to `mouse_px`, if within `max_px`; among equally near ones the one nearer
/// the eye. -1 when none. Requires transforms.size() == bounds.size().
[[nodiscard]] int pick_character(std::span<const Transform> transforms, std::span<const Bounds> bounds,
                                 const RenderCamera& camera, glm::vec2 viewport, glm::vec2 mouse_px, float max_px);

/// Index of the character `ref` in `refs` (group order changes as levels change), or -1.
[[nodiscard]] int find_character(std::span<const CharacterRef> refs, CharacterRef ref);

/// Appends the 12 edges of the box around a standing character (radius and height from `bounds`,
/// scaled by the transform) to `out`, in `colour`.
void marker_lines(const Transform& t, const Bounds& bounds, glm::vec4 colour, std::vector<LineSegment>& out);

}  // namespace aloha::tool
