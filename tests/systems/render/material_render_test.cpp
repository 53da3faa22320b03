// Materials in the CrowdRenderer on lavapipe under validation: a textured quad shows its texels where
// its UVs put them, a base colour factor is drawn in display space, several materials in one topology
// draw as one range each, the debug (materials off) path shows the instance colour alone, and the
// hemisphere light matches lit_colour().
#include "engine/gpu/context.hpp"
#include "engine/gpu/lit_pipeline.hpp"
#include "engine/gpu/png.hpp"
#include "render_scene.hpp"
#include "systems/render/crowd_renderer.hpp"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>

namespace aloha {
namespace {

constexpr uint32_t kSize = 64;

// 2 x 2 texture, rows top to bottom: (red, green), (blue, grey).
TextureImage quad_texture() {
    TextureImage t;
    t.name = "test";
    t.width = t.height = 2;
    t.rgba = {200, 30, 40, 255, 20, 180, 60, 255, 30, 50, 210, 255, 128, 128, 128, 255};
    t.wrap_u = t.wrap_v = TextureWrap::ClampToEdge;
    t.nearest = true;
    return t;
}

// Registers `m` with texture `tex` (an id from register_texture) as its base colour texture.
Result<uint32_t> with_texture(CrowdRenderer& r, SurfaceMaterial m, uint32_t tex) {
    m.texture = 0;
    const uint32_t ids[1] = {tex};
    return r.register_material(m, ids);
}

// quad_texture()'s texels as drawn opaque: top left, top right, bottom left, bottom right.
const glm::u8vec4 kTexel[4] = {{200, 30, 40, 255}, {20, 180, 60, 255}, {30, 50, 210, 255}, {128, 128, 128, 255}};

glm::u8vec4 pixel(const gpu::Rgba8Image& img, uint32_t x, uint32_t y) {
    const uint8_t* p = &img.pixels[(y * kSize + x) * 4];
    return {p[0], p[1], p[2], p[3]};
}

bool near(glm::u8vec4 a, glm::u8vec4 b, int lsb) {
    return std::abs(a.r - b.r) <= lsb && std::abs(a.g - b.g) <= lsb && std::abs(a.b - b.b) <= lsb;
}

// Pixels of the 32 x 32 block k (0 top left, 1 top right, 2 bottom left, 3 bottom right) within 1 LSB of `want`.
int block_matches(const gpu::Rgba8Image& img, uint32_t k, glm::u8vec4 want) {
    int n = 0;
    for (uint32_t y = (k / 2) * 32; y < (k / 2) * 32 + 32; ++y)
        for (uint32_t x = (k % 2) * 32; x < (k % 2) * 32 + 32; ++x) n += near(pixel(img, x, y), want, 1);
    return n;
}

// A square [-1, 1]^2 in z = 0 filling an orthographic 64 x 64 view, split into a left and a right half
// (6 vertices: x = -1, 0, 1 at y = -1 and 1), UVs spanning the texture (v = 0 at the top).
struct Quad {
    std::vector<glm::vec3> positions = {{-1, -1, 0}, {0, -1, 0}, {1, -1, 0}, {-1, 1, 0}, {0, 1, 0}, {1, 1, 0}};
    std::vector<glm::vec3> normals = std::vector<glm::vec3>(6, glm::vec3(0, 0, 1));
    std::vector<glm::vec2> uvs = {{0, 1}, {0.5f, 1}, {1, 1}, {0, 0}, {0.5f, 0}, {1, 0}};
    std::vector<uint32_t> indices = {0, 1, 4, 0, 4, 3, 1, 2, 5, 1, 5, 4};
};

// The quad (the whole texture over it) with one material on a topology of its own, per-vertex lit or not.
std::vector<DeformableMesh> quad_meshes(CrowdRenderer& r, uint32_t material, bool vertex_lit) {
    static const Quad q;
    const std::vector<uint32_t> ids = {material};
    const uint32_t topo = r.register_topology(q.indices, 6, false, {q.uvs, {}, ids, {}}, "meshes", vertex_lit).value();
    return {{topo, q.positions, q.normals, glm::mat4(1.0f), glm::vec4(1.0f)}};
}

FrameInput unlit_frame(const std::vector<DeformableMesh>& meshes) {
    FrameInput f;
    f.camera.view = glm::lookAt(glm::vec3(0, 0, 3), glm::vec3(0), glm::vec3(0, 1, 0));
    f.camera.proj = glm::ortho(-1.0f, 1.0f, -1.0f, 1.0f, 0.1f, 10.0f);
    f.meshes = meshes;
    f.clear_colour = {0, 0, 0, 1};
    f.ambient = 1.0f;  // white sky and ground: the albedo unlit
    return f;
}

Result<gpu::Rgba8Image> draw(CrowdRenderer& r, gpu::Context& ctx, const FrameInput& frame, const char* png) {
    Result<gpu::OffscreenTarget> target = gpu::OffscreenTarget::create(ctx, kSize, kSize);
    if (!target.ok()) return target.error();
    if (Status s = r.render(frame, target.value()); !s.ok()) return s.error();
    if (Status s = r.finish(); !s.ok()) return s.error();
    Result<gpu::Rgba8Image> img = target.value().read_back(ctx);
    if (img.ok()) (void)gpu::write_png(::testing::TempDir() + png, kSize, kSize, img.value().pixels);
    return img;
}

// Left half: the texture (nearest, white base colour); right half: an untextured material with linear
// factor (0.5, 0.25, 1), drawn as pow(f, 1/2.2) = (0.7297, 0.5325, 1) -> (186, 136, 255).
TEST(MaterialRender, TexturedQuadShowsTextureColoursAndFactor) {
    std::unique_ptr<gpu::Context> ctx = test::lavapipe_context();
    ASSERT_TRUE(ctx);
    {
        Result<std::unique_ptr<CrowdRenderer>> made = CrowdRenderer::create(*ctx);
        ASSERT_TRUE(made.ok()) << made.error().to_string();
        CrowdRenderer& r = *made.value();
        Result<uint32_t> tex = r.register_texture(quad_texture());
        ASSERT_TRUE(tex.ok()) << tex.error().to_string();
        SurfaceMaterial textured;
        Result<uint32_t> a = with_texture(r, textured, tex.value());
        SurfaceMaterial tinted;
        tinted.base_colour = {0.5f, 0.25f, 1.0f, 1.0f};
        Result<uint32_t> b = r.register_material(tinted);
        ASSERT_TRUE(a.ok() && b.ok());
        const Quad q;
        const std::vector<uint16_t> vertex_material = {0, 1, 1, 0, 1, 1};  // triangles take their first vertex's
        const std::vector<uint32_t> ids = {a.value(), b.value()};
        Result<uint32_t> topo = r.register_topology(q.indices, 6, false, {q.uvs, vertex_material, ids, {}});
        ASSERT_TRUE(topo.ok()) << topo.error().to_string();
        const std::vector<DeformableMesh> meshes = {{topo.value(), q.positions, q.normals, glm::mat4(1.0f), glm::vec4(1.0f)}};
        FrameInput frame = unlit_frame(meshes);
        Result<gpu::Rgba8Image> img = draw(r, *ctx, frame, "aloha_material_render.png");
        ASSERT_TRUE(img.ok()) << img.error().to_string();
        EXPECT_EQ(r.last_draw_count(), 2u) << "one draw per material range";
        // Left half spans u in [0, 0.5]: texel column 0 (red on top, blue below); the texel row boundary
        // is at the pixel boundary y = 32, so whole 32 x 32 blocks are exact.
        int red = 0, blue = 0, tint = 0, other = 0;
        for (uint32_t y = 0; y < kSize; ++y)
            for (uint32_t x = 0; x < kSize; ++x) {
                const glm::u8vec4 p = pixel(img.value(), x, y);
                if (near(p, {200, 30, 40, 255}, 1)) ++red;
                else if (near(p, {30, 50, 210, 255}, 1)) ++blue;
                else if (near(p, {186, 136, 255, 255}, 1)) ++tint;
                else ++other;
            }
        EXPECT_EQ(red, 32 * 32);
        EXPECT_EQ(blue, 32 * 32);
        EXPECT_EQ(tint, 32 * 64);
        EXPECT_EQ(other, 0);
        EXPECT_TRUE(near(pixel(img.value(), 8, 8), {200, 30, 40, 255}, 1));
        EXPECT_TRUE(near(pixel(img.value(), 8, 56), {30, 50, 210, 255}, 1));

        // Debug colourings draw the instance colour alone.
        const std::vector<DeformableMesh> green = {{topo.value(), q.positions, q.normals, glm::mat4(1.0f), glm::vec4(0, 1, 0, 1)}};
        FrameInput plain = unlit_frame(green);
        plain.materials = false;
        Result<gpu::Rgba8Image> flat = draw(r, *ctx, plain, "aloha_material_render_plain.png");
        ASSERT_TRUE(flat.ok());
        for (uint32_t y = 0; y < kSize; y += 7)
            for (uint32_t x = 0; x < kSize; x += 7) EXPECT_TRUE(near(pixel(flat.value(), x, y), {0, 255, 0, 255}, 0));
    }
    EXPECT_EQ(ctx->validation_message_count(), 0u);
}

// The whole texture over the quad (u 0..1): four 32 x 32 blocks of its four texels; and the character
// lighting (key light + hemisphere) gives lit_colour()'s prediction, within 1 LSB of rounding.
TEST(MaterialRender, FullTextureAndCharacterLighting) {
    std::unique_ptr<gpu::Context> ctx = test::lavapipe_context();
    ASSERT_TRUE(ctx);
    {
        Result<std::unique_ptr<CrowdRenderer>> made = CrowdRenderer::create(*ctx);
        ASSERT_TRUE(made.ok());
        CrowdRenderer& r = *made.value();
        const uint32_t tex = r.register_texture(quad_texture()).value();
        const uint32_t mat = with_texture(r, SurfaceMaterial{}, tex).value();
        const std::vector<DeformableMesh> meshes = quad_meshes(r, mat, false);  // the frame keeps a span of them
        FrameInput frame = unlit_frame(meshes);
        Result<gpu::Rgba8Image> img = draw(r, *ctx, frame, "aloha_material_full.png");
        ASSERT_TRUE(img.ok());
        for (uint32_t k = 0; k < 4; ++k) EXPECT_EQ(block_matches(img.value(), k, kTexel[k]), 32 * 32) << "texel " << k;
        set_character_lighting(frame);
        Result<gpu::Rgba8Image> lit = draw(r, *ctx, frame, "aloha_material_lit.png");
        ASSERT_TRUE(lit.ok());
        gpu::LitLighting lighting;
        lighting.sky = glm::vec4(frame.sky_colour, 1);
        lighting.ground = glm::vec4(frame.ground_colour, 1);
        lighting.key = glm::vec4(frame.key_colour, 1);
        const glm::vec3 want = gpu::lit_colour(glm::vec3(kTexel[0]) / 255.0f, {0, 0, 1},
                                               glm::vec4(glm::normalize(frame.light_direction), frame.ambient), lighting);
        const glm::u8vec4 got = pixel(lit.value(), 8, 8);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], want[c] * 255.0f, 1.0f) << "channel " << c;
    }
    EXPECT_EQ(ctx->validation_message_count(), 0u);
}

// Alpha masks (glTF MASK): the texture's four texels carry alpha 255, 0, 100 and 200; a material drawn with
// cutoff c shows exactly the texels whose alpha / 255 >= c and the clear colour elsewhere (each texel a
// whole 32 x 32 block, nearest sampling: no partial coverage). Opaque (no cutoff) shows all four; the
// per-vertex-lit pipelines test the same way.
TEST(MaterialRender, AlphaMaskDrawsTexelsAtOrAboveTheCutoff) {
    std::unique_ptr<gpu::Context> ctx = test::lavapipe_context();
    ASSERT_TRUE(ctx);
    {
        Result<std::unique_ptr<CrowdRenderer>> made = CrowdRenderer::create(*ctx);
        ASSERT_TRUE(made.ok());
        CrowdRenderer& r = *made.value();
        TextureImage t = quad_texture();
        const uint8_t alpha[4] = {255, 0, 100, 200};
        for (int k = 0; k < 4; ++k) t.rgba[static_cast<size_t>(4 * k + 3)] = alpha[k];
        const uint32_t tex = r.register_texture(t).value();
        struct Case {
            float cutoff;
            bool vertex_lit;
        };
        for (const Case c : {Case{-1.0f, false}, Case{0.5f, false}, Case{0.3f, false}, Case{0.79f, false}, Case{0.5f, true}}) {
            SurfaceMaterial m;
            m.alpha_cutoff = c.cutoff;
            const uint32_t mat = with_texture(r, m, tex).value();
            const std::vector<DeformableMesh> meshes = quad_meshes(r, mat, c.vertex_lit);  // the frame keeps a span of them
            Result<gpu::Rgba8Image> img = draw(r, *ctx, unlit_frame(meshes), "aloha_material_alpha.png");
            ASSERT_TRUE(img.ok()) << img.error().to_string();
            for (uint32_t k = 0; k < 4; ++k) {
                const bool shown = c.cutoff < 0.0f || static_cast<float>(alpha[k]) / 255.0f >= c.cutoff;
                EXPECT_EQ(block_matches(img.value(), k, shown ? kTexel[k] : glm::u8vec4(0, 0, 0, 255)), 32 * 32) << "cutoff " << c.cutoff << (c.vertex_lit ? " vertex-lit" : "") << ", texel " << k
                                      << (shown ? " shown" : " discarded");
            }
        }
        SurfaceMaterial above;
        above.alpha_cutoff = 1.5f;
        EXPECT_FALSE(r.register_material(above).ok());
    }
    EXPECT_EQ(ctx->validation_message_count(), 0u);
}

// An unlit material (KHR_materials_unlit) under the characters' key light and hemisphere: every pixel is its
// texel as it is (1 LSB of rounding), per-pixel and per-vertex lit alike, where the same material lit differs.
TEST(MaterialRender, UnlitMaterialShowsItsAlbedo) {
    std::unique_ptr<gpu::Context> ctx = test::lavapipe_context();
    ASSERT_TRUE(ctx);
    {
        Result<std::unique_ptr<CrowdRenderer>> made = CrowdRenderer::create(*ctx);
        ASSERT_TRUE(made.ok());
        CrowdRenderer& r = *made.value();
        const uint32_t tex = r.register_texture(quad_texture()).value();
        for (const bool vertex_lit : {false, true})
            for (const bool unlit : {true, false}) {
                SurfaceMaterial m;
                m.unlit = unlit;
                const uint32_t mat = with_texture(r, m, tex).value();
                const std::vector<DeformableMesh> meshes = quad_meshes(r, mat, vertex_lit);  // the frame keeps a span of them
                FrameInput frame = unlit_frame(meshes);
                set_character_lighting(frame);
                Result<gpu::Rgba8Image> img = draw(r, *ctx, frame, "aloha_material_unlit.png");
                ASSERT_TRUE(img.ok()) << img.error().to_string();
                int exact = 0;
                for (uint32_t k = 0; k < 4; ++k) exact += block_matches(img.value(), k, kTexel[k]);
                if (unlit) EXPECT_EQ(exact, 64 * 64) << (vertex_lit ? "vertex-lit" : "per-pixel");
                else EXPECT_LT(exact, 64 * 64 / 4) << "the lit material is shaded" << (vertex_lit ? " (vertex-lit)" : "");
            }
    }
    EXPECT_EQ(ctx->validation_message_count(), 0u);
}

// A texture of 1-texel black and white columns (128 x 128, bilinear): its mip level 1 averages each pair of columns,
// so it is one grey. Drawn minified by 2^0.7 texels a pixel both ways (lod 0.7), the nearest level (round(0.7) = 1)
// is that grey at every pixel (exactly: equal texels), while blending levels 0 and 1 keeps 30% of level 0's columns: pixels far apart. The
// default on lavapipe (a CPU device) is the nearest level (blend_texture_mips_default).
TEST(MaterialRender, NearestMipReadsOneLevelAndBlendMixesTwo) {
    std::unique_ptr<gpu::Context> ctx = test::lavapipe_context();
    ASSERT_TRUE(ctx);
    ASSERT_TRUE(ctx->is_cpu_device());
    EXPECT_FALSE(blend_texture_mips_default(true));
    EXPECT_TRUE(blend_texture_mips_default(false));
    TextureImage stripes;
    stripes.name = "stripes";
    stripes.width = stripes.height = 128;
    stripes.rgba.resize(128 * 128 * 4);
    for (uint32_t i = 0; i < 128 * 128; ++i) {
        const uint8_t v = (i % 128) % 2 == 0 ? 0 : 255;
        stripes.rgba[4 * i + 0] = stripes.rgba[4 * i + 1] = stripes.rgba[4 * i + 2] = v;
        stripes.rgba[4 * i + 3] = 255;
    }
    stripes.wrap_u = stripes.wrap_v = TextureWrap::ClampToEdge;
    // u and v span s of the texture over the quad's 64 pixels: 128 s / 64 = 2^0.7 texels a pixel.
    const float s = std::exp2(0.7f) * float(kSize) / 128.0f;
    auto spread = [&](std::optional<bool> blend) -> int {
        RendererOptions options;
        options.blend_texture_mips = blend;
        Result<std::unique_ptr<CrowdRenderer>> made = CrowdRenderer::create(*ctx, options);
        if (!made.ok()) return -1;
        CrowdRenderer& r = *made.value();
        const uint32_t tex = r.register_texture(stripes).value();
        const uint32_t mat = with_texture(r, SurfaceMaterial{}, tex).value();
        Quad q;
        q.uvs = {{0, s}, {0.5f * s, s}, {s, s}, {0, 0}, {0.5f * s, 0}, {s, 0}};
        const std::vector<uint32_t> ids = {mat};
        const uint32_t topo = r.register_topology(q.indices, 6, false, {q.uvs, {}, ids, {}}).value();
        const std::vector<DeformableMesh> meshes = {{topo, q.positions, q.normals, glm::mat4(1.0f), glm::vec4(1.0f)}};
        Result<gpu::Rgba8Image> img = draw(r, *ctx, unlit_frame(meshes), "aloha_material_mips.png");
        if (!img.ok()) return -1;
        int lo = 255, hi = 0;
        for (uint32_t y = 0; y < kSize; ++y)
            for (uint32_t x = 0; x < kSize; ++x) {
                const int g = pixel(img.value(), x, y).g;
                lo = std::min(lo, g), hi = std::max(hi, g);
            }
        return hi - lo;
    };
    // Level 1's texels are all the same average, and bilinear weights of equal texels give that value exactly.
    EXPECT_EQ(spread(false), 0) << "the nearest level: one grey";
    EXPECT_EQ(spread(std::nullopt), 0) << "the default on a CPU device: the nearest level";
    EXPECT_GE(spread(true), 30) << "blended: 30% of level 0's black and white columns, bilinearly sampled";
    EXPECT_EQ(ctx->validation_message_count(), 0u);
}

// A texture wider or taller than RendererOptions::max_texture_side is halved until it fits (64 x 32 under a limit of
// 16: 16 x 8), each texel the mean of the 2 x 2 it covers; quad_texture()'s four texels scaled up to 32 x 16 blocks
// stay four uniform blocks through the means, so the quad shows the same four colours exactly. Smaller textures
// are uploaded as they are.
TEST(MaterialRender, TexturesOverTheSideLimitAreHalved) {
    EXPECT_EQ(RendererOptions{}.max_texture_side, 2048u);
    std::unique_ptr<gpu::Context> ctx = test::lavapipe_context();
    ASSERT_TRUE(ctx);
    {
        RendererOptions options;
        options.max_texture_side = 16;
        Result<std::unique_ptr<CrowdRenderer>> made = CrowdRenderer::create(*ctx, options);
        ASSERT_TRUE(made.ok());
        CrowdRenderer& r = *made.value();
        TextureImage big = quad_texture();
        big.width = 64;
        big.height = 32;
        big.rgba.resize(size_t{64} * 32 * 4);
        for (uint32_t y = 0; y < 32; ++y)
            for (uint32_t x = 0; x < 64; ++x)
                for (uint32_t c = 0; c < 4; ++c) big.rgba[(size_t{y} * 64 + x) * 4 + c] = kTexel[(y / 16) * 2 + x / 32][static_cast<int>(c)];
        const uint32_t tex = r.register_texture(big).value();
        EXPECT_EQ(r.texture_size(tex), glm::uvec2(16, 8));
        EXPECT_EQ(r.texture_size(r.register_texture(quad_texture()).value()), glm::uvec2(2, 2)) << "within the limit: as it is";
        const uint32_t mat = with_texture(r, SurfaceMaterial{}, tex).value();
        const std::vector<DeformableMesh> meshes = quad_meshes(r, mat, false);  // the frame keeps a span of them
        Result<gpu::Rgba8Image> img = draw(r, *ctx, unlit_frame(meshes), "aloha_material_halved.png");
        ASSERT_TRUE(img.ok()) << img.error().to_string();
        for (uint32_t k = 0; k < 4; ++k) EXPECT_EQ(block_matches(img.value(), k, kTexel[k]), 32 * 32) << "texel " << k;
    }
    EXPECT_EQ(ctx->validation_message_count(), 0u);
}

// Bad inputs are refused with messages, never drawn.
TEST(MaterialRender, RegistrationErrors) {
    std::unique_ptr<gpu::Context> ctx = test::lavapipe_context();
    ASSERT_TRUE(ctx);
    {
        Result<std::unique_ptr<CrowdRenderer>> made = CrowdRenderer::create(*ctx);
        ASSERT_TRUE(made.ok());
        CrowdRenderer& r = *made.value();
        TextureImage bad = quad_texture();
        bad.rgba.pop_back();
        EXPECT_FALSE(r.register_texture(bad).ok());
        SurfaceMaterial beyond;  // texture 3 of none given, then an id never registered
        beyond.normal_texture = 3;
        EXPECT_FALSE(r.register_material(beyond).ok());
        EXPECT_FALSE(with_texture(r, SurfaceMaterial{}, 7).ok());
        SurfaceMaterial over;
        over.base_colour = {2, 0, 0, 1};
        EXPECT_FALSE(r.register_material(over).ok());
        const Quad q;
        const std::vector<uint32_t> ids = {7};
        EXPECT_FALSE(r.register_topology(q.indices, 6, false, {q.uvs, {}, ids, {}}).ok());
        const std::vector<glm::vec2> short_uvs(3);
        EXPECT_FALSE(r.register_topology(q.indices, 6, false, {short_uvs, {}, {}, {}}).ok());
    }
    EXPECT_EQ(ctx->validation_message_count(), 0u);
}

}  // namespace
}  // namespace aloha
