// CrowdRenderer end to end on lavapipe under validation: pixel coverage and exact palette colours of
// deformable meshes (two topologies, interleaved), instanced proxies and lines; draw batching; GPU timing;
// the golden image; the warm-up; and validation reporting nothing.
#include "engine/gpu/context.hpp"
#include "engine/gpu/png.hpp"
#include "render_scene.hpp"
#include "engine/gpu/lit_pipeline.hpp"
#include "systems/render/image_compare.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <map>

namespace aloha {
namespace {

using test::kPixelsPerUnit;
using test::kSceneSize;

struct Rendered {
    gpu::Rgba8Image image;
    uint32_t draws = 0;
    double gpu_ms = -1.0;
    uint64_t upload_bytes = 0;
};

// Every mesh at full resolution (the scene's meshes are small: on lavapipe the far layer would take them; its own
// test is FarLayerMeshes.* in impostor_atlas_test.cpp).
Rendered render_scene(gpu::Context& ctx, float ambient, bool oblique = false, bool warm = false) {
    Rendered out;
    RendererOptions options;
    options.far_layer_meshes_below_px = 0.0f;
    Result<std::unique_ptr<CrowdRenderer>> r = CrowdRenderer::create(ctx, options);
    EXPECT_TRUE(r.ok()) << r.error().to_string();
    if (!r.ok()) return out;
    CrowdRenderer& renderer = *r.value();
    test::RenderScene scene;
    const std::vector<uint32_t> grid = {0, 1, 4, 0, 4, 3, 1, 2, 5, 1, 5, 4, 3, 4, 7, 3, 7, 6, 4, 5, 8, 4, 8, 7};
    const std::vector<uint32_t> tri = {0, 1, 2};
    const uint32_t tri_id = renderer.register_topology(tri).value();  // registered first: ids are not order
    const uint32_t grid_id = renderer.register_topology(grid).value();
    scene.build(grid_id, tri_id, ambient);
    if (warm) {
        const Status w = renderer.warm_up();
        EXPECT_TRUE(w.ok()) << w.error().to_string();
    }
    if (oblique) {  // perspective from above-right: box sides visible, each face lit differently
        scene.frame.camera.view = glm::lookAt(glm::vec3(2.5f, 2.0f, 5.0f), glm::vec3(0), glm::vec3(0, 1, 0));
        scene.frame.camera.proj = glm::perspective(glm::radians(50.0f), 1.0f, 0.1f, 20.0f);
    }
    Result<gpu::OffscreenTarget> target = gpu::OffscreenTarget::create(ctx, kSceneSize, kSceneSize);
    EXPECT_TRUE(target.ok());
    Status s = renderer.render(scene.frame, target.value());
    EXPECT_TRUE(s.ok()) << s.error().to_string();
    EXPECT_TRUE(renderer.finish().ok());
    Result<gpu::Rgba8Image> img = target.value().read_back(ctx);
    EXPECT_TRUE(img.ok());
    if (img.ok()) out.image = std::move(img).value();
    out.draws = renderer.last_draw_count();
    out.gpu_ms = renderer.last_gpu_ms();
    out.upload_bytes = renderer.last_upload_bytes();
    return out;
}

uint32_t key(glm::u8vec4 c) { return uint32_t(c.r) << 16 | uint32_t(c.g) << 8 | c.b; }

TEST(CrowdRenderer, UnlitSceneCoverageAndPaletteColours) {
    std::unique_ptr<gpu::Context> ctx = test::lavapipe_context();
    ASSERT_TRUE(ctx);
    const Rendered r = render_scene(*ctx, /*ambient=*/1.0f);
    ASSERT_EQ(r.image.pixels.size(), size_t(kSceneSize) * kSceneSize * 4);
    // ambient = 1 makes the shader write the albedo: palette colours are exact multiples of 1/255, so the
    // UNORM8 result is exact (0 LSB); pixels are counted by exact colour.
    std::map<uint32_t, int> counts;
    for (size_t i = 0; i < r.image.pixels.size(); i += 4)
        ++counts[uint32_t(r.image.pixels[i]) << 16 | uint32_t(r.image.pixels[i + 1]) << 8 | r.image.pixels[i + 2]];
    const double p = kPixelsPerUnit;
    // Rectangle w x h pixels covers w*h +- (w + h + 1) pixel centres; a right triangle with legs L covers
    // L*L/2 +- (2L + 1) (its hypotenuse row ends add up to one pixel per row on top).
    struct Expect {
        glm::vec4 colour;
        double area, tol;
        const char* what;
    };
    const Expect expects[] = {
        {colour_for_level(0), p * p, 2 * p + 1, "grid mesh, full size"},
        {colour_for_level(1), (p / 2) * (p / 2), p + 1, "grid mesh, half-size vertices (same topology)"},
        {colour_for_level(4), p * p / 2, 2 * p + 1, "triangle mesh"},
        {colour_for_level(2), p * p, 2 * p + 1, "unit proxy box (ortho: silhouette = one face)"},
        {colour_for_level(3), (p / 2) * (1.5 * p), 2 * p + 1, "scaled proxy box 0.5 x 1.5"},
        // A horizontal 1-pixel line covers one pixel per column it spans (+-1 at each end).
        {colour_for_rule(5), 3.8 * p, 2.0, "line"},
    };
    int accounted = counts[key(to_rgba8({0, 0, 0, 1}))];
    for (const Expect& e : expects) {
        const int n = counts[key(to_rgba8(e.colour))];
        EXPECT_NEAR(n, e.area, e.tol) << e.what;
        accounted += n;
    }
    EXPECT_EQ(accounted, int(kSceneSize * kSceneSize)) << "no pixel has a colour outside palette + clear";
    // One draw per topology (2), one instanced draw for all proxies, one for all lines.
    EXPECT_EQ(r.draws, 4u);
    // Uploaded: grid 9 + grid 9 + triangle 3 vertices (position + normal, 12 bytes each; proxy boxes need
    // no vertices), 5 instances of 80 bytes, 2 line vertices of 32 bytes.
    EXPECT_EQ(r.upload_bytes, uint64_t((9 + 9 + 3) * 24 + 5 * 80 + 2 * 32));
    if (ctx->timestamps_supported()) {
        EXPECT_GT(r.gpu_ms, 0.0);
    }
    EXPECT_EQ(ctx->validation_message_count(), 0u)
        << (ctx->validation_messages().empty() ? "" : ctx->validation_messages().front());
}

TEST(CrowdRenderer, LitSceneMatchesGoldenImage) {
    std::unique_ptr<gpu::Context> ctx = test::lavapipe_context();
    ASSERT_TRUE(ctx);
    const Rendered r = render_scene(*ctx, /*ambient=*/0.3f, /*oblique=*/true);
    ASSERT_EQ(r.image.width, kSceneSize);
    // Tolerance: another rasteriser may move edge pixels (<= 0.5% of pixels here) and round lit values
    // differently (a few LSB); 8 LSB and 0.5% accept both and still catch any changed shading or geometry.
    GoldenOptions opt;
    opt.per_pixel_threshold = 8;
    opt.max_fraction = 0.005;
    opt.actual_dump_path = ::testing::TempDir() + "aloha_crowd_scene_actual.png";
    Status s = check_golden(r.image, std::string(ALOHA_SOURCE_DIR) + "/tests/systems/render/golden/crowd_scene.png",
                            opt);
    EXPECT_TRUE(s.ok()) << s.error().to_string();
    EXPECT_EQ(ctx->validation_message_count(), 0u)
        << (ctx->validation_messages().empty() ? "" : ctx->validation_messages().front());
}

// CrowdRenderer::warm_up draws every registered pipeline once into its own small target: valid under validation, and
// the frame drawn after it is the same, pixel for pixel, as without it (it writes nothing the frame keeps).
TEST(CrowdRenderer, WarmUpLeavesTheNextFrameAsItWas) {
    std::unique_ptr<gpu::Context> ctx = test::lavapipe_context();
    ASSERT_TRUE(ctx);
    const Rendered cold = render_scene(*ctx, /*ambient=*/0.3f, /*oblique=*/true);
    const Rendered warm = render_scene(*ctx, /*ambient=*/0.3f, /*oblique=*/true, /*warm=*/true);
    ASSERT_EQ(cold.image.width, kSceneSize);
    ASSERT_EQ(warm.image.width, kSceneSize);
    EXPECT_EQ(cold.image.pixels, warm.image.pixels);
    EXPECT_EQ(cold.draws, warm.draws);
    EXPECT_EQ(ctx->validation_message_count(), 0u)
        << (ctx->validation_messages().empty() ? "" : ctx->validation_messages().front());
}

// A topology registered with cull_back_faces hides triangles wound clockwise on screen (seen from behind);
// one registered without it shows them (two-sided).
TEST(CrowdRenderer, CulledTopologiesHideBackFaces) {
    std::unique_ptr<gpu::Context> ctx = test::lavapipe_context();
    ASSERT_TRUE(ctx);
    {
        Result<std::unique_ptr<CrowdRenderer>> r = CrowdRenderer::create(*ctx);
        ASSERT_TRUE(r.ok());
        const std::vector<uint32_t> tri = {0, 1, 2};
        const uint32_t two_sided = r.value()->register_topology(tri).value();
        const uint32_t culled = r.value()->register_topology(tri, 0, /*cull_back_faces=*/true).value();
        const std::vector<glm::vec3> pos = {{-0.5f, -0.5f, 0}, {0.5f, -0.5f, 0}, {-0.5f, 0.5f, 0}};
        const std::vector<glm::vec3> nrm(3, glm::vec3(0, 0, 1));
        // Turned half a turn about y: the counter-clockwise triangle now faces away from the camera.
        const glm::mat4 away = glm::rotate(glm::mat4(1.0f), glm::radians(180.0f), glm::vec3(0, 1, 0));
        Result<gpu::OffscreenTarget> target = gpu::OffscreenTarget::create(*ctx, 64, 64);
        ASSERT_TRUE(target.ok());
        auto count_lit = [&](uint32_t topo, const glm::mat4& model) {
            const std::vector<DeformableMesh> meshes = {{topo, pos, nrm, model, glm::vec4(1.0f)}};
            FrameInput frame;
            frame.camera.view = glm::lookAt(glm::vec3(0, 0, 3), glm::vec3(0), glm::vec3(0, 1, 0));
            frame.camera.proj = glm::ortho(-1.0f, 1.0f, -1.0f, 1.0f, 0.1f, 10.0f);
            frame.meshes = meshes;
            frame.clear_colour = {0, 0, 0, 1};
            frame.ambient = 1.0f;
            EXPECT_TRUE(r.value()->render(frame, target.value()).ok());
            Result<gpu::Rgba8Image> img = target.value().read_back(*ctx);
            int n = 0;
            for (size_t i = 0; i < img.value().pixels.size(); i += 4) n += img.value().pixels[i] == 255;
            return n;
        };
        // Triangle with legs of 0.5 * 64 = 32 px: 512 px +- (2 * 32 + 1).
        EXPECT_NEAR(count_lit(culled, glm::mat4(1.0f)), 512, 65);
        EXPECT_EQ(count_lit(culled, away), 0);
        EXPECT_NEAR(count_lit(two_sided, away), 512, 65);
    }
    EXPECT_EQ(ctx->validation_message_count(), 0u);
}

// Proxy boxes are drawn with back faces culled: seen from (3, 4, 5) only the +x, +y, +z faces may show.
// With the light straight up (+y) and ambient 0.2, the top face is lit 100 % and the side faces 20 %;
// the top-face pixels must cover the projected top quad (shoelace area +- perimeter + 1) around its
// projected centroid (within 1 px), which a wrongly culled (bottom) face would not.
TEST(CrowdRenderer, ProxyBoxShowsItsFrontFacesLitByTheFormula) {
    std::unique_ptr<gpu::Context> ctx = test::lavapipe_context();
    ASSERT_TRUE(ctx);
    {
        Result<std::unique_ptr<CrowdRenderer>> r = CrowdRenderer::create(*ctx);
        ASSERT_TRUE(r.ok());
        Result<gpu::OffscreenTarget> target = gpu::OffscreenTarget::create(*ctx, kSceneSize, kSceneSize);
        ASSERT_TRUE(target.ok());
        const glm::vec4 albedo = colour_for_level(5);
        const std::vector<ProxyInstance> proxies = {{glm::mat4(1.0f), albedo}};
        FrameInput frame;
        frame.camera.view = glm::lookAt(glm::vec3(3, 4, 5), glm::vec3(0), glm::vec3(0, 1, 0));
        frame.camera.proj = glm::perspective(glm::radians(30.0f), 1.0f, 0.1f, 20.0f);
        frame.proxies = proxies;
        frame.light_direction = {0, 1, 0};
        frame.ambient = 0.2f;
        frame.clear_colour = {0, 0, 0, 1};
        ASSERT_TRUE(r.value()->render(frame, target.value()).ok());
        Result<gpu::Rgba8Image> img = target.value().read_back(*ctx);
        ASSERT_TRUE(img.ok());
        const glm::u8vec4 top = to_rgba8(albedo);                         // 0.2 + 0.8 * 1
        const glm::u8vec4 side = to_rgba8(glm::vec4(glm::vec3(albedo) * 0.2f, 1.0f));  // 0.2 + 0.8 * 0
        // Projected top face corners in pixels (y down).
        const glm::mat4 vp = gpu::vulkan_clip_from_gl() * frame.camera.proj * frame.camera.view;
        glm::vec2 q[4];
        const glm::vec3 corners[4] = {{-0.5f, 0.5f, -0.5f}, {0.5f, 0.5f, -0.5f}, {0.5f, 0.5f, 0.5f}, {-0.5f, 0.5f, 0.5f}};
        for (int i = 0; i < 4; ++i) {
            const glm::vec4 c = vp * glm::vec4(corners[i], 1.0f);
            q[i] = (glm::vec2(c) / c.w * 0.5f + 0.5f) * float(kSceneSize);
        }
        double area = 0, perimeter = 0;
        for (int i = 0; i < 4; ++i) {
            area += 0.5 * (double(q[i].x) * q[(i + 1) % 4].y - double(q[(i + 1) % 4].x) * q[i].y);
            perimeter += glm::distance(q[i], q[(i + 1) % 4]);
        }
        const glm::vec2 centre = 0.25f * (q[0] + q[1] + q[2] + q[3]);  // parallelogram-like: close to centroid
        int n_top = 0, n_side = 0;
        glm::dvec2 sum(0.0);
        for (uint32_t y = 0; y < kSceneSize; ++y)
            for (uint32_t x = 0; x < kSceneSize; ++x) {
                const uint8_t* p = &img.value().pixels[(y * kSceneSize + x) * 4];
                // 1 LSB: the derivative-based face normal is exact to float rounding.
                auto is = [p](glm::u8vec4 c) {
                    return std::abs(p[0] - c.r) <= 1 && std::abs(p[1] - c.g) <= 1 && std::abs(p[2] - c.b) <= 1;
                };
                if (is(top)) {
                    ++n_top;
                    sum += glm::dvec2(x + 0.5, y + 0.5);
                } else if (is(side)) {
                    ++n_side;
                }
            }
        EXPECT_NEAR(n_top, std::abs(area), perimeter + 1);
        ASSERT_GT(n_top, 0);
        // Mean of a perspective quad's corners differs from its area centroid by well under a pixel here.
        EXPECT_NEAR(sum.x / n_top, centre.x, 1.0);
        EXPECT_NEAR(sum.y / n_top, centre.y, 1.0);
        EXPECT_GT(n_side, 0);
    }
    EXPECT_EQ(ctx->validation_message_count(), 0u);
}

}  // namespace
}  // namespace aloha
