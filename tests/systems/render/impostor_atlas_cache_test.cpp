// Impostor atlases in the bake cache (systems/render/impostor_atlas_cache.hpp): the payload reads back what was
// written, a damaged payload is refused, and the key changes with every input the bake reads and with the device.
#include "systems/render/impostor_atlas_cache.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <functional>
#include <string>
#include <vector>

namespace aloha {
namespace {

struct Inputs {  // what an ImpostorBakeInput points at
    std::vector<uint32_t> indices = {0, 1, 2, 0, 2, 3};
    std::vector<glm::vec2> uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    std::vector<uint16_t> vertex_material = {0, 0, 0, 0};
    std::vector<SurfaceMaterial> materials = {SurfaceMaterial{"skin", glm::vec4(0.8f, 0.6f, 0.5f, 1.0f), 0, false}};
    std::vector<TextureImage> textures = {TextureImage{"skin.png", 2, 1, {10, 20, 30, 255, 40, 50, 60, 255}}};
    ImpostorBakeInput input() const {
        ImpostorBakeInput in;
        in.name = "quad";
        in.indices = indices;
        in.rows.assign(2, ImpostorPose{{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}}});
        in.uvs = uvs;
        in.vertex_material = vertex_material;
        in.materials = materials;
        in.textures = textures;
        return in;
    }
};

VkPhysicalDeviceProperties device() {
    VkPhysicalDeviceProperties p{};
    p.vendorID = 0x10005;
    p.deviceID = 1;
    p.driverVersion = 42;
    std::strcpy(p.deviceName, "llvmpipe (test)");
    p.pipelineCacheUUID[0] = 7;
    return p;
}

TEST(ImpostorAtlasCache, ThePayloadReadsBackWhatWasWritten) {
    ImpostorAtlas atlas;
    atlas.image = TextureImage{"impostor atlas 'quad'", 3, 2, {}, TextureWrap::ClampToEdge, TextureWrap::ClampToEdge, false};
    for (uint8_t i = 0; i < 3 * 2 * 4; ++i) atlas.image.rgba.push_back(static_cast<uint8_t>(i * 7));
    atlas.layout = ImpostorAtlasLayout{16, 9, 0.7f, -0.01f, 1.85f, 3, 2.03f, 0.27f};
    atlas.texture_bytes = 1234;
    const std::vector<uint8_t> bytes = write_impostor_atlas(atlas);
    const std::optional<ImpostorAtlas> read = read_impostor_atlas(bytes);
    ASSERT_TRUE(read.has_value());
    EXPECT_EQ(read->image.name, atlas.image.name);
    EXPECT_EQ(read->image.width, 3u);
    EXPECT_EQ(read->image.height, 2u);
    EXPECT_EQ(read->image.rgba, atlas.image.rgba);
    EXPECT_EQ(read->image.wrap_u, TextureWrap::ClampToEdge);
    EXPECT_EQ(read->layout.directions, 16u);
    EXPECT_EQ(read->layout.rows, 9u);
    EXPECT_EQ(read->layout.width, 0.7f);
    EXPECT_EQ(read->layout.bottom, -0.01f);
    EXPECT_EQ(read->layout.height, 1.85f);
    EXPECT_EQ(read->layout.elevations, 3u);
    EXPECT_EQ(read->layout.elevated_height, 2.03f);
    EXPECT_EQ(read->layout.depth_ratio, 0.27f);
    EXPECT_EQ(read->texture_bytes, 1234u);
    // Damaged payloads: cut short, one byte too many, texels that disagree with the size.
    EXPECT_FALSE(read_impostor_atlas(std::span(bytes).first(bytes.size() - 1)).has_value());
    std::vector<uint8_t> longer = bytes;
    longer.push_back(0);
    EXPECT_FALSE(read_impostor_atlas(longer).has_value());
    ImpostorAtlas wrong = atlas;
    wrong.image.width = 4;
    EXPECT_FALSE(read_impostor_atlas(write_impostor_atlas(wrong)).has_value());
    ImpostorAtlas no_band = atlas;
    no_band.layout.elevations = 0;
    EXPECT_FALSE(read_impostor_atlas(write_impostor_atlas(no_band)).has_value());
}

TEST(ImpostorAtlasCache, TheKeyFollowsEveryInputAndTheDevice) {
    const Inputs base;
    const std::vector<uint8_t> key = impostor_atlas_key(device(), base.input());
    EXPECT_EQ(impostor_atlas_key(device(), base.input()), key) << "the same inputs give the same key";
    // The type's name only labels messages: the same mesh under another name is the same atlas.
    ImpostorBakeInput renamed = base.input();
    renamed.name = "other";
    EXPECT_EQ(impostor_atlas_key(device(), renamed), key);
    const std::vector<std::pair<std::string, std::function<void(Inputs&, ImpostorBakeInput&, VkPhysicalDeviceProperties&)>>> changes = {
        {"a row's vertex", [](Inputs&, ImpostorBakeInput& in, VkPhysicalDeviceProperties&) { in.rows[1].positions[2].y += 1e-6f; }},
        {"a normal", [](Inputs&, ImpostorBakeInput& in, VkPhysicalDeviceProperties&) { in.rows[0].normals[0].x = 0.01f; }},
        {"a row more", [](Inputs&, ImpostorBakeInput& in, VkPhysicalDeviceProperties&) { in.rows.push_back(in.rows[0]); }},
        {"the triangles", [](Inputs& i, ImpostorBakeInput& in, VkPhysicalDeviceProperties&) { std::swap(i.indices[1], i.indices[2]); in.indices = i.indices; }},
        {"a UV", [](Inputs& i, ImpostorBakeInput& in, VkPhysicalDeviceProperties&) { i.uvs[3].x = 0.5f; in.uvs = i.uvs; }},
        {"a vertex's material", [](Inputs& i, ImpostorBakeInput& in, VkPhysicalDeviceProperties&) { i.vertex_material[1] = 1; in.vertex_material = i.vertex_material; }},
        {"a material's colour", [](Inputs& i, ImpostorBakeInput& in, VkPhysicalDeviceProperties&) { i.materials[0].base_colour.g = 0.61f; in.materials = i.materials; }},
        {"double-sided", [](Inputs& i, ImpostorBakeInput& in, VkPhysicalDeviceProperties&) { i.materials[0].double_sided = true; in.materials = i.materials; }},
        {"a texel", [](Inputs& i, ImpostorBakeInput& in, VkPhysicalDeviceProperties&) { i.textures[0].rgba[5] = 51; in.textures = i.textures; }},
        {"the texture's wrap", [](Inputs& i, ImpostorBakeInput& in, VkPhysicalDeviceProperties&) { i.textures[0].wrap_v = TextureWrap::MirroredRepeat; in.textures = i.textures; }},
        {"filtering", [](Inputs& i, ImpostorBakeInput& in, VkPhysicalDeviceProperties&) { i.textures[0].nearest = true; in.textures = i.textures; }},
        {"back-face culling", [](Inputs&, ImpostorBakeInput& in, VkPhysicalDeviceProperties&) { in.cull_back_faces = true; }},
        {"directions", [](Inputs&, ImpostorBakeInput& in, VkPhysicalDeviceProperties&) { in.directions = 8; }},
        {"elevations", [](Inputs&, ImpostorBakeInput& in, VkPhysicalDeviceProperties&) { in.elevations = 3; }},
        {"cell height", [](Inputs&, ImpostorBakeInput& in, VkPhysicalDeviceProperties&) { in.cell_height_px = 64; }},
        {"the driver version", [](Inputs&, ImpostorBakeInput&, VkPhysicalDeviceProperties& d) { d.driverVersion = 43; }},
        {"the pipeline cache UUID", [](Inputs&, ImpostorBakeInput&, VkPhysicalDeviceProperties& d) { d.pipelineCacheUUID[15] = 1; }},
        {"the device", [](Inputs&, ImpostorBakeInput&, VkPhysicalDeviceProperties& d) { d.deviceID = 2; }},
    };
    for (const auto& [what, change] : changes) {
        Inputs inputs;
        ImpostorBakeInput in = inputs.input();
        VkPhysicalDeviceProperties d = device();
        change(inputs, in, d);
        EXPECT_NE(impostor_atlas_key(d, in), key) << what;
    }
}

}  // namespace
}  // namespace aloha
