// A project-generated look for characters without an authored mesh: texture coordinates for the
// generated body skin, and the texture they index (skin, shirt, trousers, shoes), both made
// by code from the skeleton alone, so textured pictures need no third-party content.
//
// Regions come from the skeleton's shape (any humanoid-like rig): the spine is the path from the root
// to the highest joint; a limb branching off it that reaches the lowest 15 % of the height is a leg,
// otherwise an arm. Bones of legs are trousers, those starting
// in the lowest tenth of the height shoes; arm bones starting within the first half of the arm's
// length (collar, upper arm) are shirt, the rest (forearm, hand) skin; spine bones are shirt up to
// the highest arm branch and skin above it (neck, head). Each muscle takes the region of the bone
// nearest its rest centre, and each skin vertex the region of its dominant muscle.
#pragma once

#include "engine/anim/skeleton.hpp"
#include "engine/assets/surface_material.hpp"
#include "systems/geometry/muscle/muscle_set.hpp"

#include <glm/glm.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace aloha {

/// Body regions, in the order of the texture's columns.
enum class BodyRegion : uint8_t { Skin = 0, Shirt = 1, Trousers = 2, Shoes = 3 };

/// Region of every joint's outgoing bone (the bone from the joint to its first child; a joint without
/// children takes its parent's). Requires rest_model.size() == joint count.
[[nodiscard]] std::vector<BodyRegion> bone_regions(const Skeleton& skeleton, std::span<const glm::mat4> rest_model);

/// Texture coordinates of the generated body skin (rest pose, model space): every vertex takes the
/// region of its dominant muscle (the region of the bone nearest that muscle's rest centre), u at the
/// centre of that region's column, and v = (top - y) / height over the rest skeleton's joint heights
/// (v = 0 at the top row). All zero when there are no muscles or dominant_muscle.size() differs.
[[nodiscard]] std::vector<glm::vec2> body_skin_uvs(const Skeleton& skeleton, std::span<const glm::mat4> rest_model,
                                                   const MuscleSet& muscles, std::span<const glm::vec3> positions,
                                                   std::span<const uint16_t> dominant_muscle);

/// The generated body texture (256 x 256, four 64-pixel columns: skin; shirt with horizontal stripes;
/// trousers in a woven dark blue; shoes, dark brown with a black sole at the bottom rows), colours
/// given in display (sRGB-encoded) values.
[[nodiscard]] TextureImage make_body_texture();

/// The material drawing the body texture: white base colour, texture index 0.
[[nodiscard]] SurfaceMaterial body_material();

}  // namespace aloha
