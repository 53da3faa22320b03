// The material render tests' set-up: a 64 x 64 target, the square [-1, 1]^2 in z = 0 seen by an orthographic
// camera at (0, 0, 3) looking down -z, drawn with one material; lights and the worst pixel error. Shared by
// material_maps_render_test.cpp and metallic_roughness_render_test.cpp.
#pragma once

#include "engine/gpu/context.hpp"
#include "engine/gpu/png.hpp"
#include "render_scene.hpp"
#include "systems/render/crowd_renderer.hpp"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <cmath>

namespace aloha::material_test {

inline constexpr uint32_t kSize = 64;

// The square [-1, 1]^2 in z = 0 (two triangles) with UVs given at its corners (-1,-1), (1,-1), (-1,1), (1,1).
struct Square {
    std::vector<glm::vec3> positions = {{-1, -1, 0}, {1, -1, 0}, {-1, 1, 0}, {1, 1, 0}};
    std::vector<glm::vec3> normals = std::vector<glm::vec3>(4, glm::vec3(0, 0, 1));
    std::vector<glm::vec2> uvs;
    std::vector<glm::vec4> colours;  // linear vertex colours, or none
    std::vector<uint32_t> indices = {0, 1, 3, 0, 3, 2};
};

inline TextureImage one_texel(std::array<uint8_t, 4> rgba, const char* name) {
    TextureImage t;
    t.name = name;
    t.width = t.height = 1;
    t.rgba.assign(rgba.begin(), rgba.end());
    return t;
}

// The camera of every test: at (0, 0, 3) looking at the origin, orthographic over [-1, 1]^2.
inline constexpr float kCameraZ = 3.0f;

// Draws the square with material `m` whose textures index `ids`, lit per vertex or per pixel; `frame` gives the light.
inline Result<gpu::Rgba8Image> draw_square(CrowdRenderer& r, gpu::Context& ctx, const SurfaceMaterial& m, std::span<const uint32_t> ids,
                                    const Square& sq, bool vertex_lit, FrameInput frame) {
    Result<uint32_t> mat = r.register_material(m, ids);
    if (!mat.ok()) return mat.error();
    const std::vector<uint32_t> materials = {mat.value()};
    Result<uint32_t> topo = r.register_topology(sq.indices, 4, false, {sq.uvs, {}, materials, sq.colours}, "meshes", vertex_lit);
    if (!topo.ok()) return topo.error();
    const std::vector<DeformableMesh> meshes = {{topo.value(), sq.positions, sq.normals, glm::mat4(1.0f), glm::vec4(1.0f)}};
    frame.camera.view = glm::lookAt(glm::vec3(0, 0, kCameraZ), glm::vec3(0), glm::vec3(0, 1, 0));
    frame.camera.proj = glm::ortho(-1.0f, 1.0f, -1.0f, 1.0f, 0.1f, 10.0f);
    frame.meshes = meshes;
    frame.clear_colour = {0, 0, 0, 1};
    Result<gpu::Rgba8Image> img = test::draw_square(r, ctx, frame, kSize);
    if (img.ok()) (void)gpu::write_png(::testing::TempDir() + "aloha_material_maps.png", kSize, kSize, img.value().pixels);
    return img;
}

// Largest |pixel - want| over the whole target, every colour channel.
inline int worst(const gpu::Rgba8Image& img, glm::vec3 want) {
    int out = 0;
    for (size_t i = 0; i < size_t{kSize} * kSize; ++i)
        for (int c = 0; c < 3; ++c)
            out = std::max(out, static_cast<int>(std::lround(std::abs(img.pixels[i * 4 + static_cast<size_t>(c)] - want[c] * 255.0f))));
    return out;
}

inline FrameInput key_only(glm::vec3 light) {
    FrameInput f;
    f.light_direction = light;
    f.ambient = 0.0f;
    f.key_colour = glm::vec3(1.0f);
    return f;
}

inline FrameInput ambient_only() {
    FrameInput f;
    f.ambient = 1.0f;  // white sky and ground (the defaults)
    return f;
}

// A lavapipe context under validation and a renderer on it; the test fails on any validation message.
class MaterialRenderFixture : public ::testing::Test {
protected:
    void SetUp() override {
        ctx = test::lavapipe_context();
        ASSERT_TRUE(ctx);
        Result<std::unique_ptr<CrowdRenderer>> made = CrowdRenderer::create(*ctx);
        ASSERT_TRUE(made.ok()) << made.error().to_string();
        renderer = std::move(made).value();
    }
    void TearDown() override {
        renderer.reset();
        if (ctx) {
            EXPECT_EQ(ctx->validation_message_count(), 0u);
        }
    }
    std::unique_ptr<gpu::Context> ctx;
    std::unique_ptr<CrowdRenderer> renderer;
};

}  // namespace aloha::material_test
