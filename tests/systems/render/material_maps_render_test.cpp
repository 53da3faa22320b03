// Material maps in the CrowdRenderer on lavapipe under validation. A quad facing the camera (normal +z), lit by
// the key light alone (ambient 0, white key, white albedo), shows 255 x max(dot(N', L), 0), where N' is its normal
// map's texel decoded (n = texel / 255 * 2 - 1, normalised) in the glTF tangent frame: x along +u, y towards
// v = 0, z along the surface normal. The frame is derived per pixel from screen-space derivatives, so UVs laid
// along other axes or mirrored must give the same world normal as the frame they define. Occlusion maps scale
// the ambient light; emissive textures add their colour, one-texel ones also on meshes without UVs; vertex colours
// multiply the albedo, encoded as base colour factors are and interpolated across the triangles. Tolerance:
// 1 LSB: the output's rounding to 8 bits (half a level) plus float error (in the derivatives of an affine quad,
// the interpolation), rounded to whole levels. The map texels themselves decode exactly (k / 255).
#include "material_square.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace aloha {
namespace {

using namespace material_test;

using MaterialMapsRender = MaterialRenderFixture;

TEST_F(MaterialMapsRender, NormalMapTurnsTheNormalInTheFrameOfTheUvs) {
    CrowdRenderer& r = *renderer;
    // Texel -> tangent-space normal, as glTF defines it.
    auto decoded = [](std::array<uint8_t, 4> t) { return glm::normalize(glm::vec3(t[0], t[1], t[2]) / 255.0f * 2.0f - 1.0f); };
    struct Case {
        const char* what;
        std::vector<glm::vec2> uvs;  // at (-1,-1), (1,-1), (-1,1), (1,1)
        glm::vec3 tangent, up;       // world directions of +u and of "towards v = 0"
    };
    const Case cases[] = {
        {"u along +x, v down", {{0, 1}, {1, 1}, {0, 0}, {1, 0}}, {1, 0, 0}, {0, 1, 0}},
        {"u mirrored", {{1, 1}, {0, 1}, {1, 0}, {0, 0}}, {-1, 0, 0}, {0, 1, 0}},
        {"u along +y, v along +x", {{0, 0}, {0, 1}, {1, 0}, {1, 1}}, {0, 1, 0}, {-1, 0, 0}},
        {"v up (mirrored in v)", {{0, 0}, {1, 0}, {0, 1}, {1, 1}}, {1, 0, 0}, {0, -1, 0}},
    };
    const std::array<uint8_t, 4> texels[] = {{204, 128, 230, 255}, {128, 204, 230, 255}, {60, 90, 240, 255}};
    for (const Case& c : cases)
        for (const std::array<uint8_t, 4>& texel : texels) {
            const uint32_t ids[1] = {r.register_texture(one_texel(texel, "normal")).value()};
            SurfaceMaterial m;
            m.normal_texture = 0;
            Square sq;
            sq.uvs = c.uvs;
            const glm::vec3 n = decoded(texel);
            const glm::vec3 world = n.x * c.tangent + n.y * c.up + n.z * glm::vec3(0, 0, 1);
            for (const glm::vec3 light : {glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(-1, 0, 0), glm::normalize(glm::vec3(0.3f, -0.5f, 0.8f))}) {
                Result<gpu::Rgba8Image> img = draw_square(r, *ctx, m, ids, sq, false, key_only(light));
                ASSERT_TRUE(img.ok()) << img.error().to_string();
                const float want = std::max(glm::dot(world, light), 0.0f);
                EXPECT_LE(worst(img.value(), glm::vec3(want)), 1) << c.what << ", texel " << int(texel[0]) << " " << int(texel[1]) << ", light "
                                                                   << light.x << " " << light.y << " " << light.z << ": want " << want * 255.0f;
            }
            // Lit per vertex, the map is not read: the surface normal alone.
            Result<gpu::Rgba8Image> flat = draw_square(r, *ctx, m, ids, sq, true, key_only({0.3f, -0.5f, 0.8f}));
            ASSERT_TRUE(flat.ok());
            EXPECT_LE(worst(flat.value(), glm::vec3(glm::normalize(glm::vec3(0.3f, -0.5f, 0.8f)).z)), 1) << c.what;
        }
}

TEST_F(MaterialMapsRender, OcclusionScalesTheAmbientAndEmissiveAddsItsColour) {
    CrowdRenderer& r = *renderer;
    Square sq;
    sq.uvs = {{0, 1}, {1, 1}, {0, 0}, {1, 0}};
    const uint32_t occlusion[1] = {r.register_texture(one_texel({100, 100, 100, 255}, "occlusion")).value()};
    SurfaceMaterial occluded;
    occluded.occlusion_texture = 0;
    // Ambient 1 under a white sky: the albedo (white) times the occlusion per pixel; per vertex it is not read.
    for (const bool vertex_lit : {false, true}) {
        Result<gpu::Rgba8Image> img = draw_square(r, *ctx, occluded, occlusion, sq, vertex_lit, ambient_only());
        ASSERT_TRUE(img.ok()) << img.error().to_string();
        EXPECT_LE(worst(img.value(), glm::vec3(vertex_lit ? 1.0f : 100.0f / 255.0f)), 1) << (vertex_lit ? "per vertex" : "per pixel");
    }
    // A black albedo and an emissive texture: the emissive colour alone, per pixel and per vertex, with UVs and,
    // for a one-texel texture, without.
    const uint32_t emissive[1] = {r.register_texture(one_texel({40, 80, 120, 255}, "emissive")).value()};
    SurfaceMaterial glowing;
    glowing.base_colour = {0, 0, 0, 1};
    glowing.emissive_texture = 0;
    Square bare = sq;
    bare.uvs.clear();
    for (const Square* s : {&sq, &bare})
        for (const bool vertex_lit : {false, true}) {
            Result<gpu::Rgba8Image> img = draw_square(r, *ctx, glowing, emissive, *s, vertex_lit, ambient_only());
            ASSERT_TRUE(img.ok()) << img.error().to_string();
            EXPECT_LE(worst(img.value(), glm::vec3(40, 80, 120) / 255.0f), 1) << (s->uvs.empty() ? "no UVs" : "UVs") << (vertex_lit ? ", per vertex" : ", per pixel");
        }
}

// Vertex colours (linear) red-orange on the left edge, blue-green on the right, under a white ambient light: each
// pixel column is the mix of their display encodings, pow(c, 1 / 2.2), at its centre's share of the width (the
// green channel 0.5 everywhere: 186), per pixel and per vertex alike.
TEST_F(MaterialMapsRender, VertexColoursMultiplyTheAlbedo) {
    CrowdRenderer& r = *renderer;
    Square sq;
    const glm::vec4 left(1.0f, 0.5f, 0.0f, 1.0f), right(0.0f, 0.5f, 1.0f, 1.0f);
    sq.colours = {left, right, left, right};
    auto encoded = [](glm::vec4 c) { return glm::pow(glm::vec3(c), glm::vec3(1.0f / 2.2f)); };
    for (const bool vertex_lit : {false, true}) {
        Result<gpu::Rgba8Image> img = draw_square(r, *ctx, SurfaceMaterial{}, {}, sq, vertex_lit, ambient_only());
        ASSERT_TRUE(img.ok()) << img.error().to_string();
        int worst_level = 0;
        for (uint32_t y = 0; y < kSize; ++y)
            for (uint32_t x = 0; x < kSize; ++x) {
                const glm::vec3 want = glm::mix(encoded(left), encoded(right), (float(x) + 0.5f) / float(kSize)) * 255.0f;
                for (int c = 0; c < 3; ++c)
                    worst_level = std::max(worst_level, static_cast<int>(std::lround(std::abs(img.value().pixels[(size_t{y} * kSize + x) * 4 + size_t(c)] - want[c]))));
            }
        EXPECT_LE(worst_level, 1) << (vertex_lit ? "per vertex" : "per pixel");
    }
    Square mismatched = sq;
    mismatched.colours.pop_back();
    EXPECT_FALSE(draw_square(r, *ctx, SurfaceMaterial{}, {}, mismatched, false, ambient_only()).ok()) << "a colour per vertex, or none";
}

}  // namespace
}  // namespace aloha
