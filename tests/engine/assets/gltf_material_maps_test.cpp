// Material maps: a material's normal, occlusion, emissive and metallic-roughness textures are read with glTF's
// factors baked into their texels (normal scale, occlusion strength, emissive factor and
// KHR_materials_emissive_strength, metallic and roughness factors); every lit material is metallic-roughness; an
// emissive factor alone becomes a one-texel texture that needs no UVs; a map on another UV set than the
// material's first texture is left out with a note; malformed factors are errors naming their JSON path.
// Expected texels are computed here from the glTF specification's formulas on the stored 8-bit values; the
// tolerance of 1 is the rounding of the baked result to 8 bits.
#include "engine/assets/gltf_loader.hpp"
#include "tests/common/gltf_builder.hpp"
#include "tests/common/png_bytes.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace aloha {
namespace {

using nlohmann::json;
using test::GltfBuilder;

// A triangle on one joint with material 0 (the caller's materials and textures in b.doc), with TEXCOORD_0 and
// TEXCOORD_1 or without UVs.
Result<GltfCharacter> load_triangle(GltfBuilder& b, bool uvs = true) {
    json attributes = {{"POSITION", b.vec3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}})}, {"NORMAL", b.vec3({{0, 0, 1}, {0, 0, 1}, {0, 0, 1}})}};
    if (uvs) {
        attributes["TEXCOORD_0"] = b.vec2({{0, 0}, {1, 0}, {0, 1}});
        attributes["TEXCOORD_1"] = b.vec2({{0, 0}, {0.5f, 0}, {0, 0.5f}});
    }
    const int j = b.node({{"name", "j"}, {"mesh", b.mesh(json::array({{{"attributes", attributes}, {"material", 0}}}))}});
    b.root(j);
    b.skin({j}, {});
    return parse_gltf_character(b.dump(), "maps.gltf");
}

// One texture per image: textures[k] draws images[k].
void one_texture_per_image(GltfBuilder& b, const std::vector<std::vector<uint8_t>>& texels) {
    b.doc["textures"] = json::array();
    for (const std::vector<uint8_t>& t : texels) b.doc["textures"].push_back({{"source", b.image(test::png_bytes(t, 1, 1))}});
}

bool has_note(const GltfCharacter& c, const std::string& part) {
    for (const std::string& n : c.notes)
        if (n.find(part) != std::string::npos) return true;
    return false;
}

uint8_t unorm8(double v) { return static_cast<uint8_t>(std::lround(std::clamp(v, 0.0, 1.0) * 255.0)); }

void expect_texel(const TextureImage& t, std::array<int, 4> want) {
    ASSERT_EQ(t.rgba.size(), 4u) << t.name;
    for (size_t c = 0; c < 4; ++c) EXPECT_NEAR(t.rgba[c], want[c], 1) << t.name << " channel " << c;
}

TEST(GltfMaterialMaps, NormalOcclusionAndEmissiveTexturesCarryTheirFactors) {
    GltfBuilder b;
    const std::vector<uint8_t> normal = {204, 128, 230, 255}, occlusion = {100, 50, 50, 255}, emissive = {200, 100, 50, 255};
    one_texture_per_image(b, {normal, occlusion, emissive});
    b.doc["materials"] = json::array({{{"normalTexture", {{"index", 0}, {"scale", 0.5}}},
                                       {"occlusionTexture", {{"index", 1}, {"strength", 0.5}}},
                                       {"emissiveTexture", {{"index", 2}}},
                                       {"emissiveFactor", {1.0, 0.5, 0.0}}}});
    Result<GltfCharacter> r = load_triangle(b);
    ASSERT_TRUE(r.ok()) << r.error().to_string();
    const GltfCharacter& c = r.value();
    const SurfaceMaterial& m = c.materials[0];
    EXPECT_EQ(m.texture, -1);
    ASSERT_GE(m.normal_texture, 0);
    ASSERT_GE(m.occlusion_texture, 0);
    ASSERT_GE(m.emissive_texture, 0);
    // glTF: scaledNormal = normalize((sampled * 2 - 1) * (scale, scale, 1)), stored again as 0.5 + 0.5 n.
    double n[3];
    for (int k = 0; k < 3; ++k) n[k] = (normal[static_cast<size_t>(k)] / 255.0 * 2.0 - 1.0) * (k < 2 ? 0.5 : 1.0);
    const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    expect_texel(c.textures[static_cast<size_t>(m.normal_texture)],
                 {unorm8(0.5 + 0.5 * n[0] / len), unorm8(0.5 + 0.5 * n[1] / len), unorm8(0.5 + 0.5 * n[2] / len), 255});
    // glTF: occlusion = 1 + strength * (sampled.r - 1), in every colour channel.
    const uint8_t ao = unorm8(1.0 + 0.5 * (100 / 255.0 - 1.0));
    expect_texel(c.textures[static_cast<size_t>(m.occlusion_texture)], {ao, ao, ao, 255});
    // Emissive texels (display-encoded) times the display encoding of the linear factor, pow(f, 1 / 2.2).
    expect_texel(c.textures[static_cast<size_t>(m.emissive_texture)], {200, unorm8(100 / 255.0 * std::pow(0.5, 1 / 2.2)), 0, 255});
    EXPECT_TRUE(has_note(c, "material inputs drawn besides base colour: 1 normal map, 1 occlusion map, 1 emissive input"));
    ASSERT_EQ(c.meshes.size(), 1u);
    EXPECT_EQ(c.meshes[0].uvs.size(), 3u) << "the maps' UV set is read although there is no base colour texture";
}

TEST(GltfMaterialMaps, OneImageIsBakedOncePerFactor) {
    GltfBuilder b;
    one_texture_per_image(b, {{255, 128, 128, 255}});
    b.doc["materials"] = json::array({{{"normalTexture", {{"index", 0}}}}, {{"normalTexture", {{"index", 0}}}},
                                      {{"normalTexture", {{"index", 0}, {"scale", 2.0}}}}});
    Result<GltfCharacter> r = load_triangle(b);
    ASSERT_TRUE(r.ok()) << r.error().to_string();
    const std::vector<SurfaceMaterial>& m = r.value().materials;
    EXPECT_EQ(m[0].normal_texture, m[1].normal_texture) << "same image, same scale: one texture";
    EXPECT_NE(m[0].normal_texture, m[2].normal_texture) << "another scale: its own texture";
    EXPECT_EQ(r.value().textures.size(), 2u);
    expect_texel(r.value().textures[static_cast<size_t>(m[0].normal_texture)], {255, 128, 128, 255});
}

TEST(GltfMaterialMaps, EmissiveFactorAloneIsOneTexelThatNeedsNoUvs) {
    for (const double strength : {2.0, 4.0}) {
        GltfBuilder b;
        b.doc["extensionsUsed"] = {"KHR_materials_emissive_strength"};
        b.doc["extensionsRequired"] = {"KHR_materials_emissive_strength"};  // read, so a file requiring it loads
        b.doc["materials"] = json::array({{{"emissiveFactor", {0.5, 0.25, 0.0}},
                                           {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", strength}}}}}}});
        Result<GltfCharacter> r = load_triangle(b, false);
        ASSERT_TRUE(r.ok()) << r.error().to_string();
        const GltfCharacter& c = r.value();
        ASSERT_EQ(c.materials.size(), 1u) << "no copy without textures: the one texel needs no UVs";
        ASSERT_GE(c.materials[0].emissive_texture, 0);
        const TextureImage& t = c.textures[static_cast<size_t>(c.materials[0].emissive_texture)];
        EXPECT_EQ(t.width * t.height, 1u);
        expect_texel(t, {unorm8(std::pow(0.5 * strength, 1 / 2.2)), unorm8(std::pow(0.25 * strength, 1 / 2.2)), 0, 255});
        EXPECT_EQ(has_note(c, "drawn clipped to the display's white"), strength * 0.5 > 1.0) << strength;
    }
}

TEST(GltfMaterialMaps, PrimitivesWithoutTexcoordsKeepOnlyOneTexelMaps) {
    GltfBuilder b;
    b.doc["textures"] = json::array({{{"source", b.image(test::png_bytes({128, 128, 255, 255, 128, 128, 255, 255}, 2, 1))}},
                                     {{"source", b.image(test::png_bytes({200, 0, 0, 255}, 1, 1))}}});
    b.doc["materials"] = json::array({{{"normalTexture", {{"index", 0}}}, {"emissiveTexture", {{"index", 1}}}, {"emissiveFactor", {1, 1, 1}}}});
    Result<GltfCharacter> r = load_triangle(b, false);
    ASSERT_TRUE(r.ok()) << r.error().to_string();
    const GltfCharacter& c = r.value();
    ASSERT_EQ(c.meshes.size(), 1u);
    const SurfaceMaterial& drawn = c.materials[static_cast<size_t>(c.meshes[0].material)];
    EXPECT_NE(drawn.name.find("(no TEXCOORD)"), std::string::npos);
    EXPECT_EQ(drawn.normal_texture, -1) << "a 2 x 1 map needs UVs";
    EXPECT_EQ(drawn.emissive_texture, c.materials[0].emissive_texture) << "one texel reads the same at every UV";
}

TEST(GltfMaterialMaps, MapOnAnotherUvSetIsLeftOutWithANote) {
    GltfBuilder b;
    one_texture_per_image(b, {{255, 255, 255, 255}, {128, 128, 255, 255}});
    b.doc["materials"] = json::array({{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}, {"normalTexture", {{"index", 1}, {"texCoord", 1}}}}});
    Result<GltfCharacter> r = load_triangle(b);
    ASSERT_TRUE(r.ok()) << r.error().to_string();
    EXPECT_GE(r.value().materials[0].texture, 0);
    EXPECT_EQ(r.value().materials[0].normal_texture, -1);
    EXPECT_TRUE(has_note(r.value(), "materials[0].normalTexture: on TEXCOORD_1 where the material's first texture is on TEXCOORD_0"));
}

TEST(GltfMaterialMaps, MalformedFactorsAreErrorsNamingTheirPath) {
    struct Case {
        json material;
        std::string path;
    };
    const Case cases[] = {
        {{{"occlusionTexture", {{"index", 0}, {"strength", 2.0}}}}, "materials[0].occlusionTexture.strength"},
        {{{"emissiveFactor", {2.0, 0.0, 0.0}}}, "materials[0].emissiveFactor"},
        {{{"normalTexture", {{"index", 5}}}}, "materials[0].normalTexture"},
        {{{"emissiveTexture", {{"index", 0}, {"texCoord", -1}}}}, "materials[0].emissiveTexture"},
        {{{"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", -1}}}}}},
         "materials[0].extensions.KHR_materials_emissive_strength.emissiveStrength"},
        {{{"pbrMetallicRoughness", {{"metallicFactor", 1.5}}}}, "materials[0].pbrMetallicRoughness.metallicFactor"},
        {{{"pbrMetallicRoughness", {{"roughnessFactor", -0.25}}}}, "materials[0].pbrMetallicRoughness.roughnessFactor"},
        {{{"pbrMetallicRoughness", {{"metallicRoughnessTexture", {{"index", 3}}}}}}, "materials[0].pbrMetallicRoughness.metallicRoughnessTexture"},
    };
    for (const Case& c : cases) {
        GltfBuilder b;
        one_texture_per_image(b, {{128, 128, 255, 255}});
        b.doc["materials"] = json::array({c.material});
        Result<GltfCharacter> r = load_triangle(b);
        ASSERT_FALSE(r.ok()) << c.material.dump();
        EXPECT_NE(r.error().to_string().find(c.path), std::string::npos) << r.error().to_string();
        EXPECT_NE(r.error().to_string().find("maps.gltf"), std::string::npos) << r.error().to_string();
    }
}

TEST(GltfMaterialMaps, MetallicRoughnessMapCarriesItsFactors) {
    GltfBuilder b;
    const std::vector<uint8_t> texel = {50, 200, 100, 255};  // red unused, green roughness, blue metalness
    one_texture_per_image(b, {texel});
    b.doc["materials"] = json::array(
        {{{"pbrMetallicRoughness", {{"metallicFactor", 0.5}, {"roughnessFactor", 0.25}, {"metallicRoughnessTexture", {{"index", 0}}}}}}});
    Result<GltfCharacter> r = load_triangle(b);
    ASSERT_TRUE(r.ok()) << r.error().to_string();
    const GltfCharacter& c = r.value();
    const SurfaceMaterial& m = c.materials[0];
    EXPECT_TRUE(m.metallic_roughness);
    EXPECT_FLOAT_EQ(m.metallic, 0.5f);
    EXPECT_FLOAT_EQ(m.roughness, 0.25f);
    ASSERT_GE(m.metallic_roughness_texture, 0);
    // glTF: roughness = factor x green, metalness = factor x blue.
    expect_texel(c.textures[static_cast<size_t>(m.metallic_roughness_texture)], {50, unorm8(200 / 255.0 * 0.25), unorm8(100 / 255.0 * 0.5), 255});
    EXPECT_TRUE(has_note(c, "1 metallic-roughness map"));
    EXPECT_TRUE(has_note(c, "1 material with a metalness factor above 0"));
    EXPECT_EQ(c.meshes[0].uvs.size(), 3u) << "the map's UV set is read";
}

TEST(GltfMaterialMaps, EveryLitMaterialIsMetallicRoughnessWithTheSpecificationsDefaults) {
    GltfBuilder b;
    one_texture_per_image(b, {{0, 128, 255, 255}});
    b.doc["textures"].push_back({{"source", b.image(test::png_bytes({0, 128, 255, 255, 0, 64, 0, 255}, 2, 1))}});
    b.doc["materials"] = json::array({json::object(),
                                      {{"extensions", {{"KHR_materials_unlit", json::object()}}},
                                       {"pbrMetallicRoughness", {{"metallicRoughnessTexture", {{"index", 0}}}}}},
                                      {{"pbrMetallicRoughness", {{"metallicFactor", 0.0}, {"metallicRoughnessTexture", {{"index", 1}}}}}}});
    Result<GltfCharacter> r = load_triangle(b);
    ASSERT_TRUE(r.ok()) << r.error().to_string();
    const std::vector<SurfaceMaterial>& m = r.value().materials;
    EXPECT_TRUE(m[0].metallic_roughness) << "a material without pbrMetallicRoughness has glTF's defaults";
    EXPECT_EQ(m[0].metallic, 1.0f);
    EXPECT_EQ(m[0].roughness, 1.0f);
    EXPECT_EQ(m[0].metallic_roughness_texture, -1);
    EXPECT_FALSE(m[1].metallic_roughness) << "KHR_materials_unlit: no lighting at all";
    EXPECT_EQ(m[1].metallic_roughness_texture, -1);
    EXPECT_TRUE(m[2].metallic_roughness);
    EXPECT_GE(m[2].metallic_roughness_texture, 0);
    EXPECT_TRUE(has_note(r.value(), "1 material with a metalness factor above 0")) << "material 0; material 2's factor is 0";

    // A primitive without UVs: the map is left out, the factors stay.
    GltfBuilder nb;
    nb.doc["textures"] = json::array({{{"source", nb.image(test::png_bytes({0, 128, 255, 255, 0, 64, 0, 255}, 2, 1))}}});
    nb.doc["materials"] = json::array({{{"pbrMetallicRoughness", {{"metallicFactor", 0.75}, {"metallicRoughnessTexture", {{"index", 0}}}}}}});
    Result<GltfCharacter> plain = load_triangle(nb, false);
    ASSERT_TRUE(plain.ok()) << plain.error().to_string();
    const SurfaceMaterial& drawn = plain.value().materials[static_cast<size_t>(plain.value().meshes[0].material)];
    EXPECT_NE(drawn.name.find("(no TEXCOORD)"), std::string::npos);
    EXPECT_EQ(drawn.metallic_roughness_texture, -1);
    EXPECT_TRUE(drawn.metallic_roughness);
    EXPECT_FLOAT_EQ(drawn.metallic, 0.75f);
}

}  // namespace
}  // namespace aloha
