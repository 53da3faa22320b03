// Baking glTF's normal scale, occlusion strength, emissive factor and metallic and roughness factors into texture images
// (engine/assets/gltf_texture_bake.hpp).
#include "engine/assets/gltf_texture_bake.hpp"

#include <algorithm>
#include <cmath>

namespace aloha::gltf_detail {

namespace {

uint8_t unorm8(float v) { return static_cast<uint8_t>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f)); }

// pow(factor, 1 / 2.2) per channel: how the renderer displays a linear factor.
glm::vec3 display_encoded(glm::vec3 linear) {
    return {std::pow(std::max(linear.r, 0.0f), 1.0f / 2.2f), std::pow(std::max(linear.g, 0.0f), 1.0f / 2.2f),
            std::pow(std::max(linear.b, 0.0f), 1.0f / 2.2f)};
}

}  // namespace

void bake_texture(TextureRole role, const TextureBake& bake, TextureImage* image) {
    std::vector<uint8_t>& px = image->rgba;
    switch (role) {
        case TextureRole::BaseColour: return;
        case TextureRole::Normal:
            if (bake.normal_scale == 1.0f) return;
            for (size_t i = 0; i + 3 < px.size(); i += 4) {
                glm::vec3 n = glm::vec3(px[i], px[i + 1], px[i + 2]) / 255.0f * 2.0f - 1.0f;
                n *= glm::vec3(bake.normal_scale, bake.normal_scale, 1.0f);
                const float len = glm::length(n);
                n = len > 1e-6f ? n / len : glm::vec3(0.0f, 0.0f, 1.0f);  // a zero normal keeps the surface's own
                for (int c = 0; c < 3; ++c) px[i + static_cast<size_t>(c)] = unorm8(0.5f + 0.5f * n[c]);
                px[i + 3] = 255;
            }
            return;
        case TextureRole::Occlusion:
            for (size_t i = 0; i + 3 < px.size(); i += 4) {
                const uint8_t ao = unorm8(1.0f + bake.occlusion_strength * (static_cast<float>(px[i]) / 255.0f - 1.0f));
                px[i] = px[i + 1] = px[i + 2] = ao;
                px[i + 3] = 255;
            }
            return;
        case TextureRole::Emissive: {
            const glm::vec3 e = display_encoded(bake.emissive);
            for (size_t i = 0; i + 3 < px.size(); i += 4) {
                for (int c = 0; c < 3; ++c) px[i + static_cast<size_t>(c)] = unorm8(static_cast<float>(px[i + static_cast<size_t>(c)]) / 255.0f * e[c]);
                px[i + 3] = 255;
            }
            return;
        }
        case TextureRole::MetallicRoughness:
            for (size_t i = 0; i + 3 < px.size(); i += 4) {
                px[i + 1] = unorm8(static_cast<float>(px[i + 1]) / 255.0f * bake.roughness);
                px[i + 2] = unorm8(static_cast<float>(px[i + 2]) / 255.0f * bake.metallic);
                px[i + 3] = 255;
            }
            return;
    }
}

TextureImage constant_emissive(glm::vec3 emissive, std::string name) {
    TextureImage t;
    t.name = std::move(name);
    t.width = t.height = 1;
    const glm::vec3 e = display_encoded(emissive);
    t.rgba = {unorm8(e.r), unorm8(e.g), unorm8(e.b), 255};
    t.nearest = true;
    return t;
}

}  // namespace aloha::gltf_detail
