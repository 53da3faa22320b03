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
// nearest its rest centre, and each skin vertex the region of its dominant muscle; the hems between regions are
// drawn along smooth lines across the triangles (hem_columns).
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

/// Width (m) of the band over which a region's column fades into its neighbour's in the skin's u (hem_columns).
inline constexpr float kHemBand = 0.05f;
/// Most smoothing rounds hem_columns makes (a mesh far finer than the band).
inline constexpr int kMaxHemRounds = 64;

/// Texture coordinates of the generated body skin (rest pose, model space): every vertex takes the region of its
/// dominant muscle (the region of the bone nearest that muscle's rest centre) and u by hem_columns over the skin's
/// triangles `indices`; v = (top - y) / height over the skin's own heights (v = 0 at the top row, 1 at the soles).
/// All zero when there are no muscles or dominant_muscle.size() differs.
[[nodiscard]] std::vector<glm::vec2> body_skin_uvs(const Skeleton& skeleton, std::span<const glm::mat4> rest_model,
                                                   const MuscleSet& muscles, std::span<const glm::vec3> positions,
                                                   std::span<const uint16_t> dominant_muscle, std::span<const uint32_t> indices);

/// The u of each vertex of a triangle mesh whose vertices have body regions `region` (BodyRegion values): the
/// regions' one-hot shares smoothed over the mesh (rounds of averaging with the one-ring, as many as spread them
/// about `band` metres at the mesh's mean edge length, at most kMaxHemRounds), then u between the centres of the two
/// largest shares' columns when those are side by side, by the share of the two, so the column border (the hem) is
/// a smooth line where the shares are equal, not the zigzag of triangle edges between vertices of two regions.
/// A vertex `band` or more away (in rounds) from any other region keeps its column's centre. Without triangles, or
/// with `band` 0, every vertex is at its column's centre (the hem then follows the edges between regions).
[[nodiscard]] std::vector<float> hem_columns(std::span<const uint8_t> region, std::span<const glm::vec3> positions,
                                             std::span<const uint32_t> indices, float band = kHemBand);

/// The generated body texture (256 x 256, four 64-pixel columns: skin; shirt with horizontal stripes;
/// trousers in a woven dark blue; shoes, dark brown with a black sole in the last 2.5 rows), colours
/// given in display (sRGB-encoded) values.
[[nodiscard]] TextureImage make_body_texture();

/// The material drawing the body texture: white base colour, texture index 0.
[[nodiscard]] SurfaceMaterial body_material();

}  // namespace aloha
