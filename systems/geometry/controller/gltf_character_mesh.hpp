// Conversion of a loaded glTF character's skinned primitives into one CharacterMesh (header-only
// use of the asset types: nothing from aloha::assets is linked).
#pragma once

#include "engine/anim/skeleton.hpp"
#include "engine/assets/gltf_loader.hpp"
#include "systems/geometry/controller/character_geometry.hpp"

#include <glm/glm.hpp>

#include <span>
#include <vector>

namespace aloha {

/// Concatenates every primitive of `character` (indices offset per primitive) and reorders the
/// inverse bind matrices from raw (skin) order to the runtime order of `skeleton`, which must be
/// build_skeleton(character.skeleton).
[[nodiscard]] CharacterMesh character_mesh_from_gltf(const GltfCharacter& character, const Skeleton& skeleton);

/// Joint indices widened for fit_muscles_per_bone.
[[nodiscard]] std::vector<glm::ivec4> widen_joints(std::span<const glm::u16vec4> joints);

}  // namespace aloha
