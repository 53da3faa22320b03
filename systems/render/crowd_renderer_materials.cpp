// CrowdRenderer materials: textures (halved to the size limit), materials (up to five textures each), topologies
// with per-vertex UVs, colours and materials (index lists reordered into one range per material, each with its
// descriptor set), and character lighting.
#include "engine/gpu/context.hpp"
#include "engine/gpu/vk_error.hpp"
#include "systems/render/crowd_renderer.hpp"
#include "systems/render/impostor_packing.hpp"

#include <algorithm>
#include <cmath>

namespace aloha {

void set_character_lighting(FrameInput& frame) {
    frame.light_direction = glm::vec3(0.45f, 0.8f, 0.55f);
    frame.key_colour = glm::vec3(1.0f, 0.96f, 0.9f);
    frame.ambient = 0.45f;
    frame.sky_colour = glm::vec3(0.95f, 1.0f, 1.1f);
    frame.ground_colour = glm::vec3(0.42f, 0.38f, 0.34f);
}

Status CrowdRenderer::init_materials() {
    const uint8_t white[4] = {255, 255, 255, 255};
    Result<gpu::Texture> t = gpu::Texture::create(ctx_, 1, 1, white);
    if (!t) return t.error();
    white_ = std::move(t).value();
    Result<gpu::Buffer> b = gpu::Buffer::create(ctx_, sizeof(glm::vec2), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    if (!b) return b.error();
    no_uvs_ = std::move(b).value();
    const glm::vec2 zero(0.0f);
    no_uvs_.write(std::as_bytes(std::span(&zero, 1)));
    Result<gpu::Buffer> c = gpu::Buffer::create(ctx_, sizeof(glm::vec4), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    if (!c) return c.error();
    no_colours_ = std::move(c).value();
    const glm::vec4 one(1.0f);
    no_colours_.write(std::as_bytes(std::span(&one, 1)));
    gpu::MaterialImages images;
    images.fill(gpu::MaterialImage{white_.view(), white_.sampler()});
    Result<VkDescriptorSet> set = pipes_.material_set(no_uvs_, no_colours_, images);
    if (!set) return set.error();
    plain_set_ = set.value();
    return {};
}

Result<uint32_t> CrowdRenderer::register_texture(const TextureImage& image) {
    if (image.width == 0 || image.height == 0 || image.rgba.size() != size_t{image.width} * image.height * 4)
        return gpu::gpu_error("register_texture: '" + image.name + "' has " + std::to_string(image.rgba.size()) + " bytes for " +
                              std::to_string(image.width) + " x " + std::to_string(image.height) + " RGBA8 pixels");
    auto mode = [](TextureWrap w) {
        switch (w) {
            case TextureWrap::ClampToEdge: return VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
            case TextureWrap::MirroredRepeat: return VK_SAMPLER_ADDRESS_MODE_MIRRORED_REPEAT;
            case TextureWrap::Repeat: break;
        }
        return VK_SAMPLER_ADDRESS_MODE_REPEAT;
    };
    // Halved (each texel the mean of the 2 x 2 it covers, downsample_rgba8) while a side exceeds the limit.
    uint32_t w = image.width, h = image.height;
    std::vector<uint8_t> halved;
    while (max_texture_side_ > 0 && std::max(w, h) > max_texture_side_) {
        halved = downsample_rgba8(halved.empty() ? image.rgba : halved, w, h);
        w = std::max(w / 2, 1u);
        h = std::max(h / 2, 1u);
    }
    Result<gpu::Texture> t = gpu::Texture::create(ctx_, w, h, halved.empty() ? std::span<const uint8_t>(image.rgba) : std::span<const uint8_t>(halved),
                                                  gpu::SamplerDesc{mode(image.wrap_u), mode(image.wrap_v), image.nearest, blend_texture_mips_});
    if (!t) return t.error();
    textures_.push_back(std::move(t).value());
    texel_textures_.push_back(w == 1 && h == 1);
    texture_sizes_.emplace_back(w, h);
    return static_cast<uint32_t>(textures_.size() - 1);
}

Result<uint32_t> CrowdRenderer::register_material(const SurfaceMaterial& material, std::span<const uint32_t> texture_ids) {
    // In gpu::MaterialTexture order.
    const int used[gpu::kMaterialTextures] = {material.texture, material.normal_texture, material.occlusion_texture, material.emissive_texture,
                                              material.metallic_roughness ? material.metallic_roughness_texture : -1};
    const char* what[gpu::kMaterialTextures] = {"texture", "normal texture", "occlusion texture", "emissive texture", "metallic-roughness texture"};
    Material m;
    for (uint32_t k = 0; k < gpu::kMaterialTextures; ++k) {
        if (used[k] < 0) continue;
        if (static_cast<size_t>(used[k]) >= texture_ids.size() || texture_ids[static_cast<size_t>(used[k])] >= textures_.size())
            return gpu::gpu_error("register_material: '" + material.name + "' uses " + what[k] + " " + std::to_string(used[k]) + " of " +
                                  std::to_string(texture_ids.size()) + " (" + std::to_string(textures_.size()) + " registered)");
        m.textures[k] = static_cast<int>(texture_ids[static_cast<size_t>(used[k])]);
    }
    const glm::vec4 f = material.base_colour;
    for (int c = 0; c < 4; ++c)
        if (!(f[c] >= 0.0f && f[c] <= 1.0f))
            return gpu::gpu_error("register_material: '" + material.name + "' base colour values must be in [0, 1]");
    m.colour = glm::vec4(std::pow(f.r, 1.0f / 2.2f), std::pow(f.g, 1.0f / 2.2f), std::pow(f.b, 1.0f / 2.2f), f.a);
    const int emissive = m.textures[gpu::kEmissiveTexture];
    m.texel_emissive = emissive >= 0 && texel_textures_[static_cast<size_t>(emissive)];
    if (!(material.alpha_cutoff <= 1.0f))
        return gpu::gpu_error("register_material: '" + material.name + "' alpha cutoff must be at most 1 (negative: opaque)");
    m.mode_bits = gpu::lit_alpha_bits(material.alpha_cutoff) | (material.unlit ? gpu::kLitUnlit : 0u);
    if (material.metallic_roughness && !material.unlit) {
        if (!(material.metallic >= 0.0f && material.metallic <= 1.0f && material.roughness >= 0.0f && material.roughness <= 1.0f))
            return gpu::gpu_error("register_material: '" + material.name + "' metallic and roughness must be in [0, 1]");
        // The factors as a map stores them: roughness in green, metalness in blue.
        const auto byte = [](float v) { return static_cast<uint8_t>(std::lround(v * 255.0f)); };
        const std::pair<uint8_t, uint8_t> key{byte(material.metallic), byte(material.roughness)};
        auto it = factor_textures_.find(key);
        if (it == factor_textures_.end()) {
            TextureImage texel;
            texel.name = "metallic " + std::to_string(material.metallic) + ", roughness " + std::to_string(material.roughness);
            texel.width = texel.height = 1;
            texel.rgba = {0, key.second, key.first, 255};
            texel.nearest = true;
            Result<uint32_t> id = register_texture(texel);
            if (!id) return id.error();
            it = factor_textures_.emplace(key, id.value()).first;
        }
        m.metallic_roughness_factors = static_cast<int>(it->second);
    }
    materials_.push_back(m);
    return static_cast<uint32_t>(materials_.size() - 1);
}

uint32_t CrowdRenderer::material_mode(const Material& m, bool uvs) {
    uint32_t bits = m.mode_bits;
    if (uvs) {
        // The textured mode passes the UVs on, which every map reads (a base colour texture left out is white).
        const bool any = std::any_of(std::begin(m.textures), std::end(m.textures), [](int t) { return t >= 0; });
        if (any) bits |= gpu::kLitTexturedMesh;
        if (m.textures[gpu::kNormalTexture] >= 0) bits |= gpu::kLitNormalMap;
        if (m.textures[gpu::kOcclusionTexture] >= 0) bits |= gpu::kLitOcclusion;
    }
    if ((uvs || m.texel_emissive) && m.textures[gpu::kEmissiveTexture] >= 0) bits |= gpu::kLitEmissive;
    if (m.metallic_roughness_factors >= 0) bits |= gpu::kLitMetallicRoughness;
    return bits;
}

Result<uint32_t> CrowdRenderer::register_topology(std::span<const uint32_t> indices, uint32_t vertex_count, bool cull_back_faces,
                                                 const TopologySurface& surface, std::string_view pass, bool vertex_lighting) {
    if (indices.empty() || indices.size() % 3 != 0)
        return gpu::gpu_error("register_topology: index count " + std::to_string(indices.size()) + " is not a non-zero multiple of 3");
    const uint32_t max_index = *std::max_element(indices.begin(), indices.end());
    if (vertex_count == 0) vertex_count = max_index + 1;
    if (max_index >= vertex_count)
        return gpu::gpu_error("register_topology: index " + std::to_string(max_index) + " >= vertex_count " + std::to_string(vertex_count));
    if (!surface.uvs.empty() && surface.uvs.size() != vertex_count)
        return gpu::gpu_error("register_topology: " + std::to_string(surface.uvs.size()) + " UVs for " + std::to_string(vertex_count) + " vertices");
    const bool materials = !surface.materials.empty();
    if (!surface.colours.empty() && (!materials || surface.colours.size() != vertex_count))
        return gpu::gpu_error("register_topology: " + std::to_string(surface.colours.size()) + " vertex colours for " + std::to_string(vertex_count) +
                              " vertices" + (materials ? "" : " without materials"));
    if (materials && !surface.vertex_material.empty() && surface.vertex_material.size() != vertex_count)
        return gpu::gpu_error("register_topology: " + std::to_string(surface.vertex_material.size()) + " vertex materials for " +
                              std::to_string(vertex_count) + " vertices");
    for (const uint32_t id : surface.materials)
        if (id >= materials_.size())
            return gpu::gpu_error("register_topology: material " + std::to_string(id) + " is not registered (" + std::to_string(materials_.size()) + ")");
    auto local_of = [&](size_t tri) -> uint32_t {
        return surface.vertex_material.empty() ? 0u : surface.vertex_material[indices[tri * 3]];
    };
    if (materials)
        for (size_t tri = 0; tri < indices.size() / 3; ++tri)
            if (local_of(tri) >= surface.materials.size())
                return gpu::gpu_error("register_topology: triangle " + std::to_string(tri) + " uses material " + std::to_string(local_of(tri)) + " of " +
                                      std::to_string(surface.materials.size()));
    // Triangles grouped by material (stable: the order within a material is kept).
    std::vector<uint32_t> ordered(indices.begin(), indices.end());
    Topology t;
    if (materials) {
        std::vector<uint32_t> tris(indices.size() / 3);
        for (uint32_t k = 0; k < tris.size(); ++k) tris[k] = k;
        std::stable_sort(tris.begin(), tris.end(), [&](uint32_t a, uint32_t b) { return local_of(a) < local_of(b); });
        for (size_t k = 0; k < tris.size(); ++k)
            for (size_t c = 0; c < 3; ++c) ordered[k * 3 + c] = indices[size_t{tris[k]} * 3 + c];
        if (!surface.uvs.empty()) {
            Result<gpu::Buffer> uv = gpu::Buffer::create(ctx_, surface.uvs.size_bytes(), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
            if (!uv) return uv.error();
            uv.value().write(std::as_bytes(surface.uvs));
            t.uvs = std::move(uv).value();
        }
        if (!surface.colours.empty()) {
            std::vector<glm::vec4> encoded(surface.colours.size());
            for (size_t v = 0; v < encoded.size(); ++v) {
                const glm::vec4 raw = surface.colours[v];
                if (!std::isfinite(raw.r + raw.g + raw.b + raw.a)) return gpu::gpu_error("register_topology: vertex " + std::to_string(v) + " colour is not finite");
                const glm::vec4 c = glm::clamp(raw, 0.0f, 1.0f);
                encoded[v] = glm::vec4(std::pow(c.r, 1.0f / 2.2f), std::pow(c.g, 1.0f / 2.2f), std::pow(c.b, 1.0f / 2.2f), c.a);
            }
            Result<gpu::Buffer> cb = gpu::Buffer::create(ctx_, encoded.size() * sizeof(glm::vec4), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
            if (!cb) return cb.error();
            cb.value().write(std::as_bytes(std::span<const glm::vec4>(encoded)));
            t.colours = std::move(cb).value();
        }
        for (size_t k = 0; k < tris.size();) {
            const uint32_t local = local_of(tris[k]);
            size_t end = k;
            while (end < tris.size() && local_of(tris[end]) == local) ++end;
            Range r;
            r.first_index = static_cast<uint32_t>(k * 3);
            r.index_count = static_cast<uint32_t>((end - k) * 3);
            r.material = surface.materials[local];
            const Material& m = materials_[r.material];
            const bool uvs = t.uvs.handle() != VK_NULL_HANDLE;
            r.mode = material_mode(m, uvs) | (t.colours.handle() != VK_NULL_HANDLE ? uint32_t{gpu::kLitVertexColour} : 0u);
            if (Status made = pipes_.ensure_variant(r.mode); !made.ok()) return made.error();
            gpu::MaterialImages images;
            for (uint32_t slot = 0; slot < gpu::kMaterialTextures; ++slot) {
                const bool drawn = m.textures[slot] >= 0 && (uvs || (slot == gpu::kEmissiveTexture && m.texel_emissive));
                int id = drawn ? m.textures[slot] : -1;
                if (slot == gpu::kMetallicRoughnessTexture && !drawn) id = m.metallic_roughness_factors;  // the factors alone
                const gpu::Texture& tex = id >= 0 ? textures_[static_cast<size_t>(id)] : white_;
                images[slot] = {tex.view(), tex.sampler()};
            }
            Result<VkDescriptorSet> set = pipes_.material_set(uvs ? t.uvs : no_uvs_, t.colours.handle() != VK_NULL_HANDLE ? t.colours : no_colours_, images);
            if (!set) return set.error();
            r.set = set.value();
            t.ranges.push_back(r);
            k = end;
        }
    }
    Result<gpu::Buffer> buf = gpu::Buffer::create(ctx_, indices.size_bytes(), VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
    if (!buf) return buf.error();
    buf.value().write(std::as_bytes(std::span<const uint32_t>(ordered)));
    t.indices = std::move(buf).value();
    t.vertex_lighting = vertex_lighting;
    t.index_count = static_cast<uint32_t>(indices.size());
    t.vertex_count = vertex_count;
    t.cull_back_faces = cull_back_faces;
    t.pass = pass_id(pass);
    topologies_.push_back(std::move(t));
    const uint32_t id = static_cast<uint32_t>(topologies_.size() - 1);
    // Recording order: by pass, in the order passes were first named (a stable insertion).
    const auto at = std::find_if(draw_order_.begin(), draw_order_.end(),
                                 [&](uint32_t other) { return topologies_[other].pass > topologies_[id].pass; });
    draw_order_.insert(at, id);
    return id;
}

}  // namespace aloha
