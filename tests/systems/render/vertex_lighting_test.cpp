// Vertex lighting (register_topology's vertex_lighting, shaders/lit_vertex.frag) on lavapipe under validation:
// where the normal is the same at every vertex the light per vertex equals the light per pixel, so a flat quad
// drawn both ways gives lit_colour()'s prediction within 1 LSB of rounding, untextured and textured; on a
// curved patch every vertex-lit pixel lies within the range of its corners' light.
#include "engine/gpu/context.hpp"
#include "engine/gpu/lit_pipeline.hpp"
#include "render_scene.hpp"
#include "systems/render/crowd_renderer.hpp"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <cmath>

namespace aloha {
namespace {

constexpr uint32_t kSize = 64;

struct Quad {  // [-1, 1]^2 at z = 0, facing +z, filling the orthographic view; UVs over the texture
    std::vector<glm::vec3> positions = {{-1, -1, 0}, {1, -1, 0}, {-1, 1, 0}, {1, 1, 0}};
    std::vector<glm::vec3> normals = std::vector<glm::vec3>(4, glm::vec3(0, 0, 1));
    std::vector<glm::vec2> uvs = {{0, 1}, {1, 1}, {0, 0}, {1, 0}};
    std::vector<uint32_t> indices = {0, 1, 3, 0, 3, 2};
};

FrameInput lit_frame(const std::vector<DeformableMesh>& meshes) {
    FrameInput f;
    f.camera.view = glm::lookAt(glm::vec3(0, 0, 3), glm::vec3(0), glm::vec3(0, 1, 0));
    f.camera.proj = glm::ortho(-1.0f, 1.0f, -1.0f, 1.0f, 0.1f, 10.0f);
    f.meshes = meshes;
    f.clear_colour = {0, 0, 0, 1};
    set_character_lighting(f);
    return f;
}

Result<gpu::Rgba8Image> draw(CrowdRenderer& r, gpu::Context& ctx, const FrameInput& frame) {
    return test::draw_square(r, ctx, frame, kSize);
}

glm::vec3 pixel(const gpu::Rgba8Image& img, uint32_t x, uint32_t y) {
    const uint8_t* p = &img.pixels[(y * kSize + x) * 4];
    return {p[0], p[1], p[2]};
}

gpu::LitLighting lighting_of(const FrameInput& f) {
    gpu::LitLighting l;
    l.sky = glm::vec4(f.sky_colour, 1);
    l.ground = glm::vec4(f.ground_colour, 1);
    l.key = glm::vec4(f.key_colour, 1);
    return l;
}

TEST(VertexLighting, FlatQuadMatchesPerPixelLight) {
    std::unique_ptr<gpu::Context> ctx = test::lavapipe_context();
    ASSERT_TRUE(ctx);
    {
        Result<std::unique_ptr<CrowdRenderer>> made = CrowdRenderer::create(*ctx);
        ASSERT_TRUE(made.ok());
        CrowdRenderer& r = *made.value();
        TextureImage t;
        t.name = "grey";
        t.width = t.height = 1;
        t.rgba = {128, 200, 64, 255};
        const uint32_t tex = r.register_texture(t).value();
        SurfaceMaterial grey;
        grey.texture = 0;
        const uint32_t texture_ids[1] = {tex};
        const std::vector<uint32_t> textured = {r.register_material(grey, texture_ids).value()};
        const Quad q;
        for (const bool with_texture : {false, true}) {
            const TopologySurface surface = with_texture ? TopologySurface{q.uvs, {}, textured, {}} : TopologySurface{};
            const uint32_t per_pixel = r.register_topology(q.indices, 4, true, surface, "pixel", false).value();
            const uint32_t per_vertex = r.register_topology(q.indices, 4, true, surface, "vertex", true).value();
            const glm::vec4 colour(0.9f, 0.6f, 0.3f, 1.0f);
            std::vector<gpu::Rgba8Image> images;
            for (const uint32_t topo : {per_pixel, per_vertex}) {
                const std::vector<DeformableMesh> meshes = {{topo, q.positions, q.normals, glm::mat4(1.0f), colour}};
                Result<gpu::Rgba8Image> img = draw(r, *ctx, lit_frame(meshes));
                ASSERT_TRUE(img.ok()) << img.error().to_string();
                images.push_back(std::move(img).value());
            }
            const FrameInput f = lit_frame({});
            const glm::vec3 albedo = with_texture ? glm::vec3(colour) * glm::vec3(128, 200, 64) / 255.0f : glm::vec3(colour);
            const glm::vec3 want = 255.0f * gpu::lit_colour(albedo, {0, 0, 1}, glm::vec4(glm::normalize(f.light_direction), f.ambient),
                                                           lighting_of(f));
            for (uint32_t y = 1; y < kSize; y += 9)
                for (uint32_t x = 1; x < kSize; x += 9)
                    for (int c = 0; c < 3; ++c) {
                        EXPECT_NEAR(pixel(images[1], x, y)[c], want[c], 1.0f) << x << "," << y << " texture " << with_texture;
                        EXPECT_NEAR(pixel(images[1], x, y)[c], pixel(images[0], x, y)[c], 1.0f);
                    }
        }
    }
    EXPECT_EQ(ctx->validation_message_count(), 0u)
        << (ctx->validation_messages().empty() ? "" : ctx->validation_messages().front());
}

// A quad whose corner normals differ (a patch of a curved surface): lit per vertex, every pixel is a convex
// combination of the four corners' exact light (Gouraud interpolation), so it lies within their range, +-1
// LSB of rounding.
TEST(VertexLighting, CurvedPatchStaysWithinTheCornerLight) {
    std::unique_ptr<gpu::Context> ctx = test::lavapipe_context();
    ASSERT_TRUE(ctx);
    {
        Result<std::unique_ptr<CrowdRenderer>> made = CrowdRenderer::create(*ctx);
        ASSERT_TRUE(made.ok());
        CrowdRenderer& r = *made.value();
        Quad q;
        q.normals = {glm::normalize(glm::vec3(-0.3f, -0.2f, 1)), glm::normalize(glm::vec3(0.3f, -0.2f, 1)),
                     glm::normalize(glm::vec3(-0.3f, 0.2f, 1)), glm::normalize(glm::vec3(0.3f, 0.2f, 1))};
        const uint32_t topo = r.register_topology(q.indices, 4, true, {}, "vertex", true).value();
        const glm::vec4 colour(0.7f, 0.7f, 0.7f, 1.0f);
        const std::vector<DeformableMesh> meshes = {{topo, q.positions, q.normals, glm::mat4(1.0f), colour}};
        const FrameInput f = lit_frame(meshes);
        Result<gpu::Rgba8Image> img = draw(r, *ctx, f);
        ASSERT_TRUE(img.ok());
        glm::vec3 lo(255.0f), hi(0.0f);
        for (const glm::vec3& n : q.normals) {
            const glm::vec3 c = 255.0f * gpu::lit_colour(glm::vec3(colour), n, glm::vec4(glm::normalize(f.light_direction), f.ambient),
                                                         lighting_of(f));
            lo = glm::min(lo, c);
            hi = glm::max(hi, c);
        }
        for (uint32_t y = 0; y < kSize; y += 3)
            for (uint32_t x = 0; x < kSize; x += 3)
                for (int c = 0; c < 3; ++c) {
                    EXPECT_GE(pixel(img.value(), x, y)[c], lo[c] - 1.0f);
                    EXPECT_LE(pixel(img.value(), x, y)[c], hi[c] + 1.0f);
                }
        EXPECT_GT(hi.r - lo.r, 4.0f) << "the corners must differ for the test to mean something";
    }
    EXPECT_EQ(ctx->validation_message_count(), 0u);
}

}  // namespace
}  // namespace aloha
