// The impostor level's records and atlas layout, shared by the renderer (systems/render/crowd_renderer.hpp),
// its draw-order and far-layer planning, and the atlas bake.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>

namespace aloha {

/// One impostor (the `impostor` geometric level): a camera-facing quad showing the cell of its type's atlas
/// (register_impostor_atlas) nearest the camera's direction and the walk phase. 64 bytes, copied as is.
struct ImpostorInstance {
    glm::vec4 position_scale{0.0f, 0.0f, 0.0f, 1.0f}; ///< xyz: character origin (world), w: its uniform scale
    glm::vec4 forward_phase{0.0f, 1.0f, 0.0f, 1.0f};  ///< xy: world (x, z) of the character's local +Z (unit);
                                                      ///< z: walk phase in [0, 1), < 0 the standing row;
                                                      ///< w: fade: 1 shown, (0, 1) dithered in, < 0 the complement
                                                      ///< of a mesh dithered at -w (shaders/impostor.frag)
    glm::vec4 colour{1.0f};                           ///< tint, multiplies the atlas albedo
    uint32_t atlas = 0;                               ///< id from CrowdRenderer::register_impostor_atlas
    uint32_t reserved[3] = {0, 0, 0};                 ///< padding (std430 uvec4)
};

/// ImpostorInstance::forward_phase.w of an impostor cross-faded with its mesh (or proxies) drawn at
/// `drawn_share` (DeformableMesh::dither, ProxyFade::share): -drawn_share, so the two cover each pixel once;
/// 1 (the whole impostor) when drawn_share <= 0.
[[nodiscard]] inline float impostor_fade(float drawn_share) { return drawn_share > 0.0f ? -drawn_share : 1.0f; }

/// How an impostor atlas image is laid out (systems/render/impostor_atlas.hpp builds one). The image's top
/// half holds colour cells (RGB premultiplied by coverage in alpha), the bottom half normal cells (0.5 + 0.5 N
/// in the bake camera's frame, premultiplied the same way); each half is `directions` columns x `rows` rows.
struct ImpostorAtlasLayout {
    uint32_t directions = 16;  ///< columns: camera azimuths 2 pi c / directions in the character's frame (local +Z = 0)
    uint32_t rows = 9;         ///< walk phases r / (rows - 1), then one standing row
    float width = 1.0f;        ///< the quad (one cell) in model units: width, centred on the origin
    float bottom = 0.0f;       ///< height of its lower edge above the origin
    float height = 1.8f;       ///< its height
};

}  // namespace aloha
