// Cross-fades between an impostor and the same character drawn as a mesh or as proxy boxes
// (DeformableMesh::dither, ProxyFade, ImpostorInstance::forward_phase.w = impostor_fade(share)), and between
// two meshes (one at dither share, the other at -share): with both drawn, every pixel comes from exactly one of
// them, chosen by the 4x4 Bayer pattern the shaders share.
#include "render_scene.hpp"

#include "engine/gpu/lit_pipeline.hpp"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <array>
#include <cstdlib>
#include <string>
#include <vector>

namespace aloha {
namespace {

constexpr uint32_t kSize = 96;  // ortho 3 x 3 units: 32 pixels per unit
constexpr std::array<uint32_t, 16> kBayer = {0, 8, 2, 10, 12, 4, 14, 6, 3, 11, 1, 9, 15, 7, 13, 5};  // shaders' table

// An atlas of one direction x (1 phase + standing): every cell an opaque grey rectangle whose normals face
// the camera, on a quad of 1 x 2 model units standing on the origin.
TextureImage flat_atlas(ImpostorAtlasLayout& layout) {
    layout.directions = 1;
    layout.rows = 2;
    layout.width = 1.0f;
    layout.bottom = 0.0f;
    layout.height = 2.0f;
    TextureImage image;
    image.name = "flat";
    image.width = 32;
    image.height = 2 * 2 * 64;
    image.rgba.resize(size_t{image.width} * image.height * 4);
    for (uint32_t y = 0; y < image.height; ++y)
        for (uint32_t x = 0; x < image.width; ++x) {
            uint8_t* p = &image.rgba[(size_t{y} * image.width + x) * 4];
            const bool normal_half = y >= image.height / 2;
            p[0] = normal_half ? 128 : 180;
            p[1] = normal_half ? 128 : 180;
            p[2] = normal_half ? 255 : 180;
            p[3] = 255;
        }
    return image;
}

struct Pixels {
    gpu::Rgba8Image image;
    [[nodiscard]] const uint8_t* at(uint32_t x, uint32_t y) const { return &image.pixels[(size_t{y} * image.width + x) * 4]; }
    [[nodiscard]] bool covered(uint32_t x, uint32_t y) const { return at(x, y)[0] != 0 || at(x, y)[1] != 0 || at(x, y)[2] != 0; }
};

bool same(const uint8_t* a, const uint8_t* b) { return a[0] == b[0] && a[1] == b[1] && a[2] == b[2]; }

class CrossFadeRender : public ::testing::Test {
protected:
    void SetUp() override {
        ctx_ = test::lavapipe_context();
        ASSERT_TRUE(ctx_);
        auto r = CrowdRenderer::create(*ctx_);
        ASSERT_TRUE(r.ok()) << r.error().to_string();
        renderer_ = std::move(r).value();
        ImpostorAtlasLayout layout;
        const TextureImage image = flat_atlas(layout);
        auto atlas = renderer_->register_impostor_atlas(image, layout);
        ASSERT_TRUE(atlas.ok()) << atlas.error().to_string();
        // The "mesh": a 1 x 2 quad (counter-clockwise towards the camera) offset by a quarter unit right and
        // up from the impostor's, so the two silhouettes overlap and each has pixels of its own.
        quad_ = {{-0.25f, 0.25f, 0.0f}, {0.75f, 0.25f, 0.0f}, {0.75f, 2.25f, 0.0f}, {-0.25f, 2.25f, 0.0f}};
        normals_.assign(4, {0.0f, 0.0f, 1.0f});
        const std::vector<uint32_t> indices = {0, 1, 2, 0, 2, 3};
        for (const bool vertex_lit : {false, true}) {
            auto t = renderer_->register_topology(indices, 4, /*cull_back_faces=*/vertex_lit, {}, "meshes", vertex_lit);
            ASSERT_TRUE(t.ok()) << t.error().to_string();
            topologies_.push_back(t.value());
        }
        impostor_.position_scale = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
        impostor_.forward_phase = glm::vec4(0.0f, 1.0f, -1.0f, 1.0f);  // facing the camera, standing row
        impostor_.colour = glm::vec4(0.3f, 1.0f, 0.3f, 1.0f);
        impostor_.atlas = atlas.value();
        frame_.camera.view = glm::lookAt(glm::vec3(0.0f, 1.0f, 5.0f), glm::vec3(0.0f, 1.0f, 0.0f), glm::vec3(0.0f, 1.0f, 0.0f));
        frame_.camera.proj = glm::ortho(-1.5f, 1.5f, -1.5f, 1.5f, 0.1f, 20.0f);
        frame_.clear_colour = {0.0f, 0.0f, 0.0f, 1.0f};
    }

    // Draws the drawn side (`kind` 0, 1: the mesh lit per pixel or per vertex, 2: a proxy box of the same
    // rectangle) at `drawn` share (0: left out), the impostor at impostor_fade(share) when `with_impostor`.
    Pixels draw(int kind, float share, bool with_impostor) {
        std::vector<DeformableMesh> meshes;
        std::vector<ProxyInstance> proxies;
        std::vector<ProxyFade> fades;
        const glm::vec4 red(1.0f, 0.3f, 0.3f, 1.0f);
        if (share > 0.0f && kind < 2) meshes.push_back({topologies_[size_t(kind)], quad_, normals_, glm::mat4(1.0f), red, share});
        if (share > 0.0f && kind == 2) {
            proxies.push_back({glm::scale(glm::translate(glm::mat4(1.0f), {0.25f, 1.25f, -0.05f}), {1.0f, 2.0f, 0.1f}), red});
            if (share < 1.0f) fades.push_back({0, 1, share});
        }
        ImpostorInstance im = impostor_;
        im.forward_phase.w = impostor_fade(share);
        FrameInput frame = frame_;
        frame.meshes = meshes;
        frame.proxies = proxies;
        frame.proxy_fades = fades;
        if (with_impostor) frame.impostors = std::span<const ImpostorInstance>(&im, 1);
        Result<gpu::Rgba8Image> out = test::draw_square(*renderer_, *ctx_, frame, kSize);
        EXPECT_TRUE(out.ok()) << out.error().to_string();
        return {out.ok() ? std::move(out).value() : gpu::Rgba8Image{}};
    }

    std::unique_ptr<gpu::Context> ctx_;
    std::unique_ptr<CrowdRenderer> renderer_;
    std::vector<glm::vec3> quad_, normals_;
    std::vector<uint32_t> topologies_;
    ImpostorInstance impostor_;
    FrameInput frame_;
};

TEST_F(CrossFadeRender, EveryPixelComesFromTheMeshOrTheImpostorByTheSharedPattern) {
    if (!ctx_) GTEST_SKIP();
    const Pixels impostor = draw(0, 0.0f, true);  // t = 1: the impostor alone
    for (const int kind : {0, 1, 2}) {
        SCOPED_TRACE("drawn side " + std::string(kind == 0 ? "mesh lit per pixel" : kind == 1 ? "mesh lit per vertex" : "proxy box"));
        const Pixels mesh = draw(kind, 1.0f, false);  // t = 0: the mesh alone
        ASSERT_EQ(mesh.image.width, kSize);
        // The end points: share 1 with the impostor at impostor_fade(1) is the mesh frame, bit for bit; share 0
        // (the mesh left out) with the impostor at impostor_fade(0) = 1 is the impostor frame.
        const Pixels at_mesh = draw(kind, 1.0f, true);
        EXPECT_EQ(at_mesh.image.pixels, mesh.image.pixels);
        EXPECT_EQ(draw(kind, 0.0f, true).image.pixels, impostor.image.pixels);
        // Every share a fade of N = 2..8 frames shows (k / N), and the middle one.
        for (const float share : {0.5f, 1.0f / 6.0f, 5.0f / 6.0f, 0.125f, 0.875f, 0.3f}) {
            SCOPED_TRACE("share " + std::to_string(share));
            const Pixels both = draw(kind, share, true);
            uint32_t kept = 0;  // Bayer values whose threshold the share passes (shaders/impostor.frag's test)
            for (uint32_t b = 0; b < 16; ++b) kept += (float(b) + 0.5f) / 16.0f < share ? 1u : 0u;
            EXPECT_EQ(gpu::lit_dither_bits(share), kept << 8);
            size_t wrong = 0, overlap = 0, from_mesh = 0, union_count = 0;
            std::vector<uint8_t> partial_block((kSize / 4) * (kSize / 4), 0), block_has((kSize / 4) * (kSize / 4), 0);
            for (uint32_t y = 0; y < kSize; ++y)
                for (uint32_t x = 0; x < kSize; ++x) {
                    const bool mesh_side = kBayer[(y & 3) * 4 + (x & 3)] < kept;
                    // Exactly one of the two pure frames' pixel, the pattern's choice: no blend, no double draw.
                    if (!same(both.at(x, y), mesh_side ? mesh.at(x, y) : impostor.at(x, y))) ++wrong;
                    const bool m = mesh.covered(x, y), i = impostor.covered(x, y);
                    union_count += m || i;
                    const size_t block = (y / 4) * (kSize / 4) + x / 4;
                    if (m && i) {
                        ++overlap;
                        from_mesh += mesh_side;
                        block_has[block] = 1;
                    } else {
                        partial_block[block] = 1;
                    }
                    // Covered only inside the union of the two silhouettes.
                    if (both.covered(x, y) && !(m || i)) ++wrong;
                    // Where both silhouettes cover the pixel it is never left empty (no holes).
                    if (m && i && !both.covered(x, y)) ++wrong;
                }
            EXPECT_EQ(wrong, 0u);
            ASSERT_GT(overlap, 500u);
            EXPECT_LT(overlap, union_count);  // the silhouettes differ: each has pixels of its own
            // The mesh's share of the overlap: kept / 16 in every 4x4 block inside it; a block the overlap's edge
            // crosses holds c < 16 overlap pixels of which between max(0, c - (16 - kept)) and min(c, kept) are the
            // mesh's, at most 16 * max(kept, 16 - kept) / 16 <= 16 from c * kept / 16.
            size_t edge_blocks = 0;
            for (size_t b = 0; b < block_has.size(); ++b) edge_blocks += block_has[b] && partial_block[b];
            const double expected = double(overlap) * kept / 16.0;
            EXPECT_LE(std::abs(double(from_mesh) - expected), double(std::max(kept, 16u - kept)) * double(edge_blocks))
                << from_mesh << " mesh pixels of " << overlap << ", " << edge_blocks << " edge blocks";
            if (share == 0.5f) {
                EXPECT_NEAR(double(from_mesh) / double(overlap), 0.5, 8.0 * double(edge_blocks) / double(overlap));
            }
        }
    }
}

// Two meshes of one character cross-faded (a mesh <-> mesh level switch): the entered one at `share`, the left
// one at -share (the complement). The left mesh is offset half a unit left and a little nearer the camera, so
// the silhouettes differ and a pixel drawn by both would show the left mesh whatever the pattern says.
TEST_F(CrossFadeRender, TwoMeshesAtComplementaryDithersCoverEachPixelOnce) {
    if (!ctx_) GTEST_SKIP();
    std::vector<glm::vec3> left_quad = quad_;
    for (glm::vec3& p : left_quad) p += glm::vec3(-0.5f, 0.0f, 0.01f);
    const glm::vec4 red(1.0f, 0.3f, 0.3f, 1.0f), blue(0.3f, 0.3f, 1.0f, 1.0f);
    // entered: topologies_[e] at `share` (0: left out); left: topologies_[l] at `left_dither` (0: left out).
    auto draw_two = [&](size_t e, size_t l, float share, float left_dither) {
        std::vector<DeformableMesh> meshes;
        if (share != 0.0f) meshes.push_back({topologies_[e], quad_, normals_, glm::mat4(1.0f), red, share});
        if (left_dither != 0.0f) meshes.push_back({topologies_[l], left_quad, normals_, glm::mat4(1.0f), blue, left_dither});
        FrameInput frame = frame_;
        frame.meshes = meshes;
        Result<gpu::Rgba8Image> out = test::draw_square(*renderer_, *ctx_, frame, kSize);
        EXPECT_TRUE(out.ok()) << out.error().to_string();
        return Pixels{out.ok() ? std::move(out).value() : gpu::Rgba8Image{}};
    };
    // Both ways between per-pixel and per-vertex lighting (a layered level and the skinned one).
    for (const auto& [e, l] : {std::pair<size_t, size_t>{0, 1}, std::pair<size_t, size_t>{1, 0}}) {
        SCOPED_TRACE("entered lit per " + std::string(e == 0 ? "pixel" : "vertex"));
        const Pixels entered = draw_two(e, l, 1.0f, 0.0f), left = draw_two(e, l, 0.0f, 1.0f);
        ASSERT_EQ(entered.image.width, kSize);
        // The end points: the left mesh at -1 keeps no pixel, so share 1 is the entered frame bit for bit.
        EXPECT_EQ(draw_two(e, l, 1.0f, -1.0f).image.pixels, entered.image.pixels);
        for (const float share : {0.5f, 1.0f / 6.0f, 5.0f / 6.0f, 0.125f, 0.875f, 0.3f}) {
            SCOPED_TRACE("share " + std::to_string(share));
            const Pixels both = draw_two(e, l, share, -share);
            uint32_t kept = 0;
            for (uint32_t b = 0; b < 16; ++b) kept += (float(b) + 0.5f) / 16.0f < share ? 1u : 0u;
            EXPECT_EQ(gpu::lit_dither_bits(-share), kept << 8 | gpu::kLitDitherComplement);
            size_t wrong = 0, overlap = 0, from_entered = 0, holes = 0;
            for (uint32_t y = 0; y < kSize; ++y)
                for (uint32_t x = 0; x < kSize; ++x) {
                    const bool entered_side = kBayer[(y & 3) * 4 + (x & 3)] < kept;
                    // Exactly the pattern's choice of the two pure frames' pixel (background where that mesh is absent).
                    if (!same(both.at(x, y), entered_side ? entered.at(x, y) : left.at(x, y))) ++wrong;
                    const bool a = entered.covered(x, y), b = left.covered(x, y);
                    if (a && b) {
                        ++overlap;
                        from_entered += entered_side;
                        holes += !both.covered(x, y);  // both silhouettes cover it: never empty
                    }
                }
            EXPECT_EQ(wrong, 0u);
            EXPECT_EQ(holes, 0u);
            ASSERT_GT(overlap, 500u);
            // In the overlap each 4x4 block gives the entered mesh `kept` of its 16 pixels; the overlap is a
            // rectangle whose blocks the edge crosses give at most max(kept, 16 - kept) per block off c * kept / 16,
            // and it spans at most 2 * (24 + 24) such blocks in a 96-pixel square (24 blocks a side).
            const double expected = double(overlap) * kept / 16.0;
            EXPECT_LE(std::abs(double(from_entered) - expected), double(std::max(kept, 16u - kept)) * 96.0);
        }
    }
}

TEST_F(CrossFadeRender, RejectsOutOfRangeDithersAndProxyRuns) {
    if (!ctx_) GTEST_SKIP();
    std::vector<DeformableMesh> meshes = {{topologies_[0], quad_, normals_, glm::mat4(1.0f), glm::vec4(1.0f), 1.5f}};
    std::vector<ProxyInstance> proxies(2);
    std::vector<ProxyFade> fades = {{1, 1, 0.5f}, {0, 1, 0.5f}};  // out of order
    FrameInput frame = frame_;
    frame.meshes = meshes;
    frame.proxies = proxies;
    frame.proxy_fades = fades;
    std::vector<std::string> errors;
    EXPECT_FALSE(renderer_->Validate(frame, &errors));
    ASSERT_EQ(errors.size(), 2u);
    EXPECT_NE(errors[0].find("dither 1.5"), std::string::npos) << errors[0];
    EXPECT_NE(errors[1].find("proxy_fades[1]"), std::string::npos) << errors[1];
}

}  // namespace
}  // namespace aloha
