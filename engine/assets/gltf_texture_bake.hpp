// The factors glTF applies to a material's normal, occlusion, emissive and metallic-roughness textures, baked into a copy of the
// texture's image at load, so the renderer samples each input as it is drawn (no per-material constants).
#pragma once

#include "engine/assets/surface_material.hpp"

#include <glm/glm.hpp>

#include <cstdint>
#include <string>

namespace aloha::gltf_detail {

/// What a material texture is for (which SurfaceMaterial field holds it).
enum class TextureRole : uint8_t { BaseColour, Normal, Occlusion, Emissive, MetallicRoughness };

/// A material's texture factors (glTF defaults: scale 1, strength 1, no emission, metallic 1, roughness 1).
struct TextureBake {
    float normal_scale = 1.0f;        ///< normalTexture.scale: multiplies the tangent-space normal's x and y
    float occlusion_strength = 1.0f;  ///< occlusionTexture.strength in [0, 1]
    glm::vec3 emissive{0.0f};         ///< emissiveFactor x KHR_materials_emissive_strength (linear, >= 0)
    float metallic = 1.0f;            ///< pbrMetallicRoughness.metallicFactor in [0, 1]
    float roughness = 1.0f;           ///< pbrMetallicRoughness.roughnessFactor in [0, 1]
};

/// Bakes `bake`'s factor for `role` into `image` (RGBA8, decoded as stored):
/// - Normal: each texel's n = normalize((rgb / 255 * 2 - 1) * (scale, scale, 1)) encoded back as 0.5 + 0.5 n
///   (glTF's scaledNormal); the image is left as it is when the scale is 1.
/// - Occlusion: 1 + strength * (r / 255 - 1) in r, g and b (glTF reads the red channel).
/// - Emissive: each colour channel times the display encoding of the factor, pow(factor, 1 / 2.2) (the
///   renderer's encoding of linear base colour factors), clipped to 255.
/// - MetallicRoughness: green (roughness) times the roughness factor, blue (metalness) times the metallic
///   factor; red (unused by glTF's model) as stored.
/// Alpha becomes 255 for these four; BaseColour leaves the image unchanged.
void bake_texture(TextureRole role, const TextureBake& bake, TextureImage* image);

/// A one-texel emissive texture of `emissive` (linear, each channel >= 0), encoded and clipped as bake_texture
/// does, for a material with an emissive factor and no emissive texture; `name` names it in notes.
[[nodiscard]] TextureImage constant_emissive(glm::vec3 emissive, std::string name);

}  // namespace aloha::gltf_detail
