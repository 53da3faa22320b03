// WebP textures (EXT_texture_webp): the texture's WebP source is decoded with libwebp and preferred over
// the PNG fallback its `source` names; a file that requires the extension loads; broken WebP data is
// noted (the material drawn untextured) and a malformed extension is an error naming it. Images are
// encoded in the test with libwebp's lossless encoder, so decoded texels must equal the input exactly.
// An image whose bufferView runs outside its buffer (PNG or WebP) is noted and never read.
#include "engine/assets/gltf_loader.hpp"
#include "tests/common/gltf_builder.hpp"
#include "tests/common/png_bytes.hpp"

#include <gtest/gtest.h>
#include <webp/encode.h>

namespace aloha {
namespace {

using nlohmann::json;
using test::GltfBuilder;

// 2 x 2 RGBA texels, rows top to bottom; the alpha channel is part of what must come back (no texel fully
// transparent: the simple lossless encoder drops the colour of those, as WebP allows).
const std::vector<uint8_t> kTexels = {200, 30, 40, 255, 20, 180, 60, 128, 30, 50, 210, 1, 128, 128, 128, 255};

std::vector<unsigned char> webp(const std::vector<uint8_t>& rgba, int w, int h) {
    uint8_t* out = nullptr;
    const size_t size = WebPEncodeLosslessRGBA(rgba.data(), w, h, w * 4, &out);
    std::vector<unsigned char> bytes(out, out + size);
    WebPFree(out);
    return bytes;
}

// A textured triangle on one joint whose material's base colour texture is `texture` (a textures[] entry).
Result<GltfCharacter> load_with(GltfBuilder& b, const json& texture) {
    b.doc["textures"] = json::array({texture});
    b.doc["materials"] = json::array({{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}});
    json prim = {{"attributes", {{"POSITION", b.vec3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}})},
                                 {"NORMAL", b.vec3({{0, 0, 1}, {0, 0, 1}, {0, 0, 1}})},
                                 {"TEXCOORD_0", b.vec2({{0, 0}, {1, 0}, {0, 1}})}}},
                 {"material", 0}};
    const int j = b.node({{"name", "j"}, {"mesh", b.mesh(json::array({prim}))}});
    b.root(j);
    b.skin({j}, {});
    return parse_gltf_character(b.dump(), "webp.gltf");
}

bool has_note(const GltfCharacter& c, const std::string& part) {
    for (const std::string& n : c.notes)
        if (n.find(part) != std::string::npos) return true;
    return false;
}

TEST(GltfWebp, WebpSourceIsPreferredOverThePngFallback) {
    GltfBuilder b;
    std::vector<uint8_t> other(kTexels.size(), 7);  // the fallback PNG differs from the WebP image
    const int fallback = b.image(test::png_bytes(other, 2, 2));
    const int image = b.image(webp(kTexels, 2, 2), "image/webp");
    b.doc["extensionsUsed"] = {"EXT_texture_webp"};
    Result<GltfCharacter> r = load_with(b, {{"source", fallback}, {"extensions", {{"EXT_texture_webp", {{"source", image}}}}}});
    ASSERT_TRUE(r.ok()) << r.error().to_string();
    ASSERT_EQ(r.value().textures.size(), 1u);
    const TextureImage& t = r.value().textures[0];
    EXPECT_EQ(t.width, 2u);
    EXPECT_EQ(t.height, 2u);
    EXPECT_EQ(t.rgba, kTexels) << "lossless WebP decodes to the encoded texels, alpha included";
    EXPECT_EQ(r.value().materials[0].texture, 0);
    EXPECT_TRUE(has_note(r.value(), "EXT_texture_webp: 1 material texture drawn from WebP images"));
}

TEST(GltfWebp, RequiredWebpWithoutFallbackLoads) {
    GltfBuilder b;
    const int image = b.image(webp(kTexels, 2, 2), "image/webp");
    b.doc["extensionsUsed"] = {"EXT_texture_webp"};
    b.doc["extensionsRequired"] = {"EXT_texture_webp"};
    Result<GltfCharacter> r = load_with(b, {{"extensions", {{"EXT_texture_webp", {{"source", image}}}}}});
    ASSERT_TRUE(r.ok()) << r.error().to_string();
    ASSERT_EQ(r.value().textures.size(), 1u);
    EXPECT_EQ(r.value().textures[0].rgba, kTexels);
}

TEST(GltfWebp, BrokenWebpIsNotedAndTheMaterialDrawnUntextured) {
    GltfBuilder b;
    std::vector<unsigned char> bytes = webp(kTexels, 2, 2);
    bytes.resize(bytes.size() / 2);  // a WebP header over cut data
    const int image = b.image(bytes, "image/webp");
    Result<GltfCharacter> r = load_with(b, {{"extensions", {{"EXT_texture_webp", {{"source", image}}}}}});
    ASSERT_TRUE(r.ok()) << r.error().to_string();
    EXPECT_EQ(r.value().materials[0].texture, -1);
    EXPECT_TRUE(has_note(r.value(), "images[0]: WebP decoding failed")) << "or a bad header";
}

TEST(GltfWebp, BrokenWebpFallsBackToItsPngSource) {
    GltfBuilder b;
    const int fallback = b.image(test::png_bytes(kTexels, 2, 2));
    std::vector<unsigned char> bytes = webp(kTexels, 2, 2);
    bytes.resize(bytes.size() / 2);
    const int image = b.image(bytes, "image/webp");
    Result<GltfCharacter> r = load_with(b, {{"source", fallback}, {"extensions", {{"EXT_texture_webp", {{"source", image}}}}}});
    ASSERT_TRUE(r.ok()) << r.error().to_string();
    ASSERT_EQ(r.value().textures.size(), 1u);
    EXPECT_EQ(r.value().textures[0].rgba, kTexels);
    EXPECT_EQ(r.value().materials[0].texture, 0);
    EXPECT_TRUE(has_note(r.value(), "textures[0]: its WebP images[1] could not be used; the fallback images[0] is drawn"));
    EXPECT_FALSE(has_note(r.value(), "drawn from WebP images")) << "no texture is drawn from WebP";
}

TEST(GltfWebp, MalformedExtensionIsAnErrorNamingIt) {
    for (const json& ext : {json{{"source", -1}}, json{{"index", 0}}, json{{"source", "a.webp"}}}) {
        GltfBuilder b;
        b.image(webp(kTexels, 2, 2), "image/webp");
        Result<GltfCharacter> r = load_with(b, {{"extensions", {{"EXT_texture_webp", ext}}}});
        ASSERT_FALSE(r.ok()) << ext.dump();
        EXPECT_EQ(r.error().path, "textures[0].extensions.EXT_texture_webp.source") << r.error().to_string();
    }
    // A source past the images: the texture has no usable image, noted, drawn untextured.
    GltfBuilder b;
    b.image(webp(kTexels, 2, 2), "image/webp");
    Result<GltfCharacter> r = load_with(b, {{"extensions", {{"EXT_texture_webp", {{"source", 5}}}}}});
    ASSERT_TRUE(r.ok()) << r.error().to_string();
    EXPECT_TRUE(has_note(r.value(), "textures[0]: no usable image source (5)"));
}

// Regression (found by fuzz_gltf, fixed): tinygltf hands the image callback a bufferView's bytes without checking them
// against the buffer, so a view past the buffer's end was read out of bounds (a heap overflow or a read of freed memory
// under ASan). Views starting past the end and views running over it are both noted; the material drawn untextured.
TEST(GltfWebp, ImageViewOutsideItsBufferIsNotedAndNotRead) {
    for (const char* mime : {"image/webp", "image/png"}) {
        for (const bool starts_outside : {true, false}) {
            GltfBuilder b;
            const std::vector<unsigned char> bytes = std::string(mime) == "image/png" ? test::png_bytes(kTexels, 2, 2) : webp(kTexels, 2, 2);
            const int image = b.image(bytes, mime);
            json& view = b.doc["bufferViews"][static_cast<size_t>(b.doc["images"][static_cast<size_t>(image)]["bufferView"].get<int>())];
            if (starts_outside)
                view["byteOffset"] = 1u << 20;
            else
                view["byteLength"] = (1u << 20) + bytes.size();
            const json texture = std::string(mime) == "image/png" ? json{{"source", image}} : json{{"extensions", {{"EXT_texture_webp", {{"source", image}}}}}};
            Result<GltfCharacter> r = load_with(b, texture);
            ASSERT_TRUE(r.ok()) << mime << ": " << r.error().to_string();
            EXPECT_EQ(r.value().materials[0].texture, -1) << mime;
            EXPECT_TRUE(has_note(r.value(), "images[0]: bufferView 0 (bytes ")) << mime << (starts_outside ? " starting" : " running") << " outside";
            EXPECT_TRUE(has_note(r.value(), ") lies outside buffer 0 of ")) << mime;
        }
    }
}

}  // namespace
}  // namespace aloha
