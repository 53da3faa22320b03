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
/// build_skeleton(character.skeleton). UVs are kept when any primitive has them ((0, 0) for the others);
/// vertex_material holds each primitive's material, with -1 (glTF's default material) mapped to
/// character.materials.size() (see gltf_surface_materials).
[[nodiscard]] CharacterMesh character_mesh_from_gltf(const GltfCharacter& character, const Skeleton& skeleton);

/// The materials CharacterMesh::vertex_material indexes: the file's, plus glTF's default material
/// (white, untextured) at the end.
[[nodiscard]] std::vector<SurfaceMaterial> gltf_surface_materials(const GltfCharacter& character);

/// Joint indices widened for fit_muscles_per_bone.
[[nodiscard]] std::vector<glm::ivec4> widen_joints(std::span<const glm::u16vec4> joints);

}  // namespace aloha
