// Impostor atlases: one character type rendered once, at load, into a texture of views x poses that the
// impostor level draws as camera-facing quads (CrowdRenderer::register_impostor_atlas, ImpostorInstance).
// The bake draws the type's mesh with the renderer's own pipelines into an offscreen target through an
// orthographic camera: every cell at once in one frame for the colour (the albedo: ambient light 1 from a
// white sky and ground) and one for the normals (FrameInput::write_normals).
#pragma once

#include "engine/assets/surface_material.hpp"
#include "engine/core/result.hpp"
#include "systems/render/crowd_renderer.hpp"

#include <glm/glm.hpp>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace aloha {

namespace gpu {
class Context;
}

/// One pose of the baked mesh (model space, local +Z forward, +Y up).
struct ImpostorPose {
    std::vector<glm::vec3> positions;  ///< the topology's vertices
    std::vector<glm::vec3> normals;    ///< one per vertex (need not be unit length)
};

/// What an atlas is baked from: one character type's mesh in its walk phases and standing pose.
struct ImpostorBakeInput {
    std::string name;                             ///< the type (messages, the texture's name)
    std::span<const uint32_t> indices;            ///< triangle list shared by every pose
    std::vector<ImpostorPose> rows;               ///< walk phases 0, 1/(n-1), ..., then the standing pose (n >= 2)
    std::span<const glm::vec2> uvs;               ///< per vertex, or empty
    std::span<const uint16_t> vertex_material;    ///< per vertex (indices into materials), or empty
    std::span<const glm::vec4> colours;           ///< LINEAR colour per vertex (COLOR_0), or empty (white); with materials
    std::span<const SurfaceMaterial> materials;   ///< the type's materials (may be empty: white)
    std::span<const TextureImage> textures;       ///< their textures
    bool cull_back_faces = false;                 ///< closed mesh wound counter-clockwise from outside
    uint32_t directions = 16;                     ///< camera azimuths around the vertical axis (>= 1)
    uint32_t elevations = 1;                      ///< bands of views, level then from above (impostor_elevation; 1..8)
    uint32_t cell_height_px = 96;                 ///< pixels per cell vertically (its width follows the bounds)
};

/// A baked atlas: the image and its layout, ready for CrowdRenderer::register_impostor_atlas.
struct ImpostorAtlas {
    TextureImage image;            ///< colour half on top, normal half below (see ImpostorAtlasLayout)
    ImpostorAtlasLayout layout;    ///< cells and the quad they cover
    double build_ms = 0.0;         ///< wall time of the bake (renderer set-up, two frames, read-backs)
    uint64_t texture_bytes = 0;    ///< GPU memory of the mipmapped texture (packed R32G32_UINT, full chain)
};

/// Model units per atlas pixel of `in`'s bake: its cells' height (the rows' vertical extent with a margin) over
/// in.cell_height_px. Requires at least one row with a position.
[[nodiscard]] float impostor_texel_size(const ImpostorBakeInput& in);

/// The name a bake gives its atlas image (messages): "impostor atlas '<type>'".
[[nodiscard]] std::string impostor_atlas_image_name(const std::string& type);

/// Bakes `in` on `ctx` (a renderer and target of its own, released before returning). Errors: fewer than
/// two rows, poses whose sizes differ from the first's, an empty mesh, elevations outside 1..8, an atlas wider or
/// taller than 8192 pixels, Vulkan failures.
[[nodiscard]] Result<ImpostorAtlas> bake_impostor_atlas(gpu::Context& ctx, const ImpostorBakeInput& in);

/// The world from model matrix the bake gives direction `d` (of `directions`) in its cell: the camera,
/// looking along -Z, sees the character from azimuth 2 pi d / directions in the character's own frame
/// (0 = in front of it, along its +Z). Without the cell offset; for tests that render the same view.
[[nodiscard]] glm::mat4 impostor_view_rotation(uint32_t d, uint32_t directions);

/// The same from `elevation` radians above the horizon, about the pivot `pivot_y` above the origin: the character
/// turned to azimuth d, its pivot moved to the origin, then leant towards the camera (+Z) by the elevation, so a
/// camera looking along -Z sees it as one looking down at that angle does. Equals impostor_view_rotation() moved
/// down by pivot_y at elevation 0.
[[nodiscard]] glm::mat4 impostor_view_transform(uint32_t d, uint32_t directions, float elevation, float pivot_y);

}  // namespace aloha
