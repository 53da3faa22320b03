// What a character type's impostor atlas is baked from (systems/render/impostor_atlas.hpp): the type's
// mesh at its richest layered level, posed along its walk cycle and standing, with springs at rest.
#pragma once

#include "systems/frame/draw_lists.hpp"
#include "systems/render/impostor_atlas.hpp"

#include <glm/glm.hpp>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace aloha {

/// The level `gc`'s atlas is baked from: its first Layered level as the type draws it, else its first
/// SkinnedMesh, else its first Subdivided level; GeometryController::kNoLevel when it has no mesh level.
[[nodiscard]] uint8_t impostor_source_level(const GeometryController& gc);

/// The bake input of `draw`'s type at `level`: one row per entry of `poses` (each the type's model-space
/// joint matrices: the walk phases, then the standing pose), its surface there by
/// GeometryController::reference_surface and area-weighted normals, the level's UVs and materials.
/// Allocates (load time only).
[[nodiscard]] ImpostorBakeInput impostor_bake_input(const DrawType& draw, uint8_t level,
                                                    std::span<const std::vector<glm::mat4>> poses, std::string name);

}  // namespace aloha
