// Impostor atlases in the bake cache (see impostor_atlas_cache.hpp).
#include "systems/render/impostor_atlas_cache.hpp"

#include "engine/core/byte_io.hpp"

namespace aloha {
namespace {

constexpr uint32_t kImpostorAtlasKind = 0x494d5003;  // "IMP" v3 (bands of elevations): a new payload layout gets a new number

static_assert(sizeof(glm::vec3) == 12 && sizeof(glm::vec2) == 8 && sizeof(glm::vec4) == 16, "written as raw bytes");

// A texture's size, texels and sampling (not its name, which only labels messages).
void write_texture(ByteWriter& w, const TextureImage& t) {
    w.put(t.width);
    w.put(t.height);
    w.put_vector(t.rgba);
    w.put<uint32_t>(static_cast<uint32_t>(t.wrap_u));
    w.put<uint32_t>(static_cast<uint32_t>(t.wrap_v));
    w.put<uint8_t>(t.nearest ? 1 : 0);
}

// Everything the bake reads, field by field (no struct padding reaches the bytes).
void write_input(ByteWriter& w, const VkPhysicalDeviceProperties& device, const ImpostorBakeInput& in) {
    w.put(device.vendorID);
    w.put(device.deviceID);
    w.put(device.driverVersion);
    w.put(device.apiVersion);
    w.put_bytes(device.pipelineCacheUUID, VK_UUID_SIZE);
    w.put_string(device.deviceName);
    w.put_vector(in.indices);
    w.put<uint64_t>(in.rows.size());
    for (const ImpostorPose& row : in.rows) {
        w.put_vector(row.positions);
        w.put_vector(row.normals);
    }
    w.put_vector(in.uvs);
    w.put_vector(in.vertex_material);
    w.put_vector(in.colours);
    w.put<uint64_t>(in.materials.size());
    for (const SurfaceMaterial& m : in.materials) {
        w.put(m.base_colour);
        w.put<int32_t>(m.texture);
        w.put<int32_t>(m.normal_texture);
        w.put<int32_t>(m.occlusion_texture);
        w.put<int32_t>(m.emissive_texture);
        w.put<uint8_t>(m.double_sided ? 1 : 0);
        w.put(m.alpha_cutoff);
        w.put<uint8_t>(m.unlit ? 1 : 0);
        w.put<uint8_t>(m.metallic_roughness ? 1 : 0);
        w.put(m.metallic);
        w.put(m.roughness);
        w.put<int32_t>(m.metallic_roughness_texture);
    }
    w.put<uint64_t>(in.textures.size());
    for (const TextureImage& t : in.textures) write_texture(w, t);
    w.put<uint8_t>(in.cull_back_faces ? 1 : 0);
    w.put(in.directions);
    w.put(in.elevations);
    w.put(in.cell_height_px);
}

// The payload's fixed-size fields after the image, in order, handed to `io` one by one (writing and reading alike).
template <class Atlas, class Io>
void layout_fields(Atlas& a, Io&& io) {
    io(a.layout.directions);
    io(a.layout.rows);
    io(a.layout.width);
    io(a.layout.bottom);
    io(a.layout.height);
    io(a.layout.elevations);
    io(a.layout.elevated_height);
    io(a.layout.depth_ratio);
    io(a.texture_bytes);
}

}  // namespace

std::vector<uint8_t> impostor_atlas_key(const VkPhysicalDeviceProperties& device, const ImpostorBakeInput& in) {
    ByteWriter inputs;
    write_input(inputs, device, in);
    return digest_key(kImpostorAtlasKind, inputs.bytes());
}

std::vector<uint8_t> write_impostor_atlas(const ImpostorAtlas& atlas) {
    ByteWriter w;
    w.put_string(atlas.image.name);
    write_texture(w, atlas.image);
    layout_fields(atlas, [&w](const auto& field) { w.put(field); });
    return w.take();
}

std::optional<ImpostorAtlas> read_impostor_atlas(std::span<const uint8_t> bytes) {
    ByteReader r(bytes);
    ImpostorAtlas atlas;
    TextureImage& image = atlas.image;
    uint32_t wrap_u = 0, wrap_v = 0;
    uint8_t nearest = 0;
    r.get_string(image.name);
    r.get(image.width);
    r.get(image.height);
    r.get_vector(image.rgba);
    r.get(wrap_u);
    r.get(wrap_v);
    r.get(nearest);
    layout_fields(atlas, [&r](auto& field) { r.get(field); });
    const auto wrap_ok = [](uint32_t w) { return w <= static_cast<uint32_t>(TextureWrap::MirroredRepeat); };
    if (!r.done() || uint64_t{image.width} * image.height * 4 != image.rgba.size() || image.width == 0 || !wrap_ok(wrap_u) ||
        !wrap_ok(wrap_v) || nearest > 1 || atlas.layout.directions == 0 || atlas.layout.rows < 2 ||
        atlas.layout.elevations < 1 || atlas.layout.elevations > kMaxImpostorElevations)
        return std::nullopt;
    image.wrap_u = static_cast<TextureWrap>(wrap_u);
    image.wrap_v = static_cast<TextureWrap>(wrap_v);
    image.nearest = nearest != 0;
    return atlas;
}

}  // namespace aloha
