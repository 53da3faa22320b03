// Vertex colours (glTF COLOR_0): VEC3 and VEC4, float and normalised unsigned byte and short, read as linear
// RGBA (alpha 1 for VEC3) in [0, 1]; carried with their vertices when flat normals duplicate them; a wrong type
// or count is an error naming the attribute. Byte and short values are exact fractions (v / 255, v / 65535).
#include "engine/assets/gltf_loader.hpp"
#include "tests/common/gltf_builder.hpp"

#include <gtest/gtest.h>

namespace aloha {
namespace {

using nlohmann::json;
using test::GltfBuilder;

// A triangle on one joint with COLOR_0 = `colour` (an accessor index), with or without normals.
Result<GltfCharacter> load_coloured(GltfBuilder& b, int colour, bool normals = true) {
    json attributes = {{"POSITION", b.vec3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}})}, {"COLOR_0", colour}};
    if (normals) attributes["NORMAL"] = b.vec3({{0, 0, 1}, {0, 0, 1}, {0, 0, 1}});
    const int j = b.node({{"name", "j"}, {"mesh", b.mesh(json::array({{{"attributes", attributes}}}))}});
    b.root(j);
    b.skin({j}, {});
    return parse_gltf_character(b.dump(), "colours.gltf");
}

TEST(GltfVertexColours, FloatAndNormalisedColoursReadAsLinearRgba) {
    {
        GltfBuilder b;
        Result<GltfCharacter> r = load_coloured(b, b.vec4({{1, 0, 0, 1}, {0, 0.5f, 0, 0.25f}, {0, 0, 1, 1}}));
        ASSERT_TRUE(r.ok()) << r.error().to_string();
        ASSERT_EQ(r.value().meshes[0].colours.size(), 3u);
        EXPECT_EQ(r.value().meshes[0].colours[1], glm::vec4(0, 0.5f, 0, 0.25f));
        bool noted = false;
        for (const std::string& n : r.value().notes) noted |= n.find("1 primitive with COLOR_0") != std::string::npos;
        EXPECT_TRUE(noted);
    }
    {
        GltfBuilder b;
        const std::vector<uint8_t> bytes = {255, 0, 0, 0, 51, 0, 0, 0, 255};
        Result<GltfCharacter> r = load_coloured(b, b.accessor(bytes, "VEC3", 5121, true));
        ASSERT_TRUE(r.ok()) << r.error().to_string();
        EXPECT_EQ(r.value().meshes[0].colours[1], glm::vec4(0, 0.2f, 0, 1)) << "51 / 255, alpha 1 for VEC3";
    }
    {
        GltfBuilder b;
        const std::vector<uint16_t> shorts = {65535, 0, 0, 65535, 0, 65535, 0, 65535, 0, 0, 65535, 0};
        Result<GltfCharacter> r = load_coloured(b, b.accessor(shorts, "VEC4", 5123, true));
        ASSERT_TRUE(r.ok()) << r.error().to_string();
        EXPECT_EQ(r.value().meshes[0].colours[2], glm::vec4(0, 0, 1, 0));
    }
}

TEST(GltfVertexColours, FlatNormalsKeepEachCornersColour) {
    GltfBuilder b;
    json attributes = {{"POSITION", b.vec3({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}})},
                       {"COLOR_0", b.vec4({{1, 0, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 1}, {1, 1, 1, 1}})}};
    // Two triangles sharing vertices 1 and 2: without NORMAL every triangle gets its own three corners.
    const int j = b.node({{"name", "j"}, {"mesh", b.mesh(json::array({{{"attributes", attributes}, {"indices", b.indices({0, 1, 2, 1, 3, 2})}}}))}});
    b.root(j);
    b.skin({j}, {});
    Result<GltfCharacter> r = parse_gltf_character(b.dump(), "flat.gltf");
    ASSERT_TRUE(r.ok()) << r.error().to_string();
    const GltfSkinnedMesh& m = r.value().meshes[0];
    ASSERT_EQ(m.positions.size(), 6u);
    ASSERT_EQ(m.colours.size(), 6u);
    const glm::vec4 want[6] = {{1, 0, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 1}, {0, 1, 0, 1}, {1, 1, 1, 1}, {0, 0, 1, 1}};
    for (size_t v = 0; v < 6; ++v) EXPECT_EQ(m.colours[m.indices[v]], want[v]) << "corner " << v;
}

TEST(GltfVertexColours, WrongTypeOrCountIsAnErrorNamingTheAttribute) {
    {
        GltfBuilder b;
        Result<GltfCharacter> r = load_coloured(b, b.vec2({{1, 0}, {0, 1}, {1, 1}}));
        ASSERT_FALSE(r.ok());
        EXPECT_NE(r.error().to_string().find("meshes[0].primitives[0].attributes.COLOR_0"), std::string::npos) << r.error().to_string();
        EXPECT_NE(r.error().to_string().find("VEC3 or VEC4"), std::string::npos) << r.error().to_string();
    }
    {
        GltfBuilder b;
        Result<GltfCharacter> r = load_coloured(b, b.vec4({{1, 0, 0, 1}, {0, 1, 0, 1}}));
        ASSERT_FALSE(r.ok());
        EXPECT_NE(r.error().to_string().find("COLOR_0"), std::string::npos) << r.error().to_string();
    }
}

}  // namespace
}  // namespace aloha
