// Renders known quads with the lit-mesh pipeline on lavapipe under validation, reads the image back and
// checks coverage against the projected area, the lit colour against the shader formula, depth ordering,
// image orientation, and that the validation layer reported nothing.
#include "engine/gpu/buffer.hpp"
#include "engine/gpu/context.hpp"
#include "engine/gpu/lit_pipeline.hpp"
#include "engine/gpu/texture.hpp"
#include "engine/gpu/offscreen_target.hpp"
#include "engine/gpu/png.hpp"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace aloha::gpu {
namespace {

constexpr uint32_t kSize = 128;

// Float-to-UNORM8 conversion is exact to within rounding (<= 1 LSB); the interpolated normals are the same
// at every vertex, so normalize() adds < 1e-6. Two LSB covers both with margin.
constexpr int kColourTolLsb = 2;

struct Rgb8 {
    int r, g, b;
};

Rgb8 to_rgb8(glm::vec3 c) {
    return {int(std::lround(c.r * 255.0f)), int(std::lround(c.g * 255.0f)), int(std::lround(c.b * 255.0f))};
}

bool near(const uint8_t* px, Rgb8 want, int tol) {
    return std::abs(px[0] - want.r) <= tol && std::abs(px[1] - want.g) <= tol && std::abs(px[2] - want.b) <= tol;
}

template <class T>
Buffer make_buffer(const Context& ctx, const std::vector<T>& data, VkBufferUsageFlags usage) {
    Result<Buffer> b = Buffer::create(ctx, sizeof(T) * data.size(), usage);
    EXPECT_TRUE(b.ok()) << b.error().to_string();
    b.value().write(std::as_bytes(std::span(data)));
    return std::move(b).value();
}

// Pixel x-extent (half width) of a quad of half-size `half` centred on the view axis at world depth z.
double projected_half_px(const glm::mat4& view_proj, float half, float z) {
    const glm::vec4 c = view_proj * glm::vec4(half, 0.0f, z, 1.0f);
    return (c.x / c.w) * 0.5 * kSize;
}

TEST(LitMesh, QuadCoverageColourDepthAndOrientation) {
    ContextOptions opt;
    opt.validation = true;
    opt.device = "lavapipe";
    Result<std::unique_ptr<Context>> made = Context::create(opt);
    ASSERT_TRUE(made.ok()) << made.error().to_string();
    Context& ctx = *made.value();
    {
        Result<OffscreenTarget> target = OffscreenTarget::create(ctx, kSize, kSize);
        ASSERT_TRUE(target.ok()) << target.error().to_string();
        Result<LitPipelines> pipes = LitPipelines::create(ctx, target.value().view().render_pass, 1);
        ASSERT_TRUE(pipes.ok()) << pipes.error().to_string();

        // Unit quad in the z = 0 plane, normal +z.
        const std::vector<float> pos = {-0.5f, -0.5f, 0, 0.5f, -0.5f, 0, 0.5f, 0.5f, 0, -0.5f, 0.5f, 0};
        const std::vector<float> nrm = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
        const std::vector<uint32_t> idx = {0, 1, 2, 0, 2, 3};
        const glm::vec3 red(0.8f, 0.5f, 0.2f), blue(0.1f, 0.2f, 0.9f), green(0.2f, 0.9f, 0.3f);
        std::vector<LitInstance> inst(3);
        inst[0] = {glm::mat4(1.0f), glm::vec4(red, 1.0f)};  // front, centred
        inst[1] = {glm::scale(glm::translate(glm::mat4(1.0f), {0, 0, -1}), {2, 2, 1}), glm::vec4(blue, 1.0f)};
        inst[2] = {glm::scale(glm::translate(glm::mat4(1.0f), {0, 0.75f, 0.5f}), {0.2f, 0.2f, 1}),
                   glm::vec4(green, 1.0f)};  // small, above centre, nearest
        const std::vector<LineVertex> lines(1);

        Buffer pb = make_buffer(ctx, pos, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
        Buffer nb = make_buffer(ctx, nrm, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
        Buffer ib = make_buffer(ctx, inst, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
        Buffer lb = make_buffer(ctx, lines, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
        Buffer xb = make_buffer(ctx, idx, VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
        Buffer lightb = make_buffer(ctx, std::vector<LitLighting>(1), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
        Buffer uvb = make_buffer(ctx, std::vector<glm::vec2>(1), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
        const std::vector<uint8_t> white_texel = {255, 255, 255, 255};
        Result<Texture> white = Texture::create(ctx, 1, 1, white_texel);
        ASSERT_TRUE(white.ok()) << white.error().to_string();
        Result<VkDescriptorSet> set = pipes.value().allocate_set();
        ASSERT_TRUE(set.ok()) << set.error().to_string();
        pipes.value().write_set(set.value(), pb, nb, ib, lb, lightb);
        // The untextured mode still binds a material set (the shader declares it): UVs unused, white texel.
        Result<VkDescriptorSet> material = pipes.value().material_set(uvb, white.value().view(), white.value().sampler());
        ASSERT_TRUE(material.ok()) << material.error().to_string();
        const VkDescriptorSet sets[2] = {set.value(), material.value()};

        const glm::vec3 eye(0, 0, 3);
        LitPush push;
        push.view_proj = vulkan_clip_from_gl() * glm::perspective(glm::radians(60.0f), 1.0f, 0.1f, 10.0f) *
                         glm::lookAt(eye, glm::vec3(0), glm::vec3(0, 1, 0));
        push.light = glm::vec4(glm::normalize(glm::vec3(1, 1, 1)), 0.25f);
        push.camera = glm::vec4(eye, 1.0f);
        push.offsets = glm::uvec4(0, 0, 0, 0);  // shared mesh: stride 0

        const TargetView view = target.value().view();
        const LitPipelines& lp = pipes.value();
        Status drawn = ctx.submit_once([&](VkCommandBuffer cmd) {
            begin_render_pass(cmd, view, VkClearColorValue{{0.0f, 0.0f, 0.0f, 1.0f}});
            VkViewport vp{0, 0, float(kSize), float(kSize), 0, 1};
            VkRect2D sc{{0, 0}, view.extent};
            vkCmdSetViewport(cmd, 0, 1, &vp);
            vkCmdSetScissor(cmd, 0, 1, &sc);
            vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, lp.mesh());
            vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, lp.layout(), 0, 2, sets, 0, nullptr);
            vkCmdPushConstants(cmd, lp.layout(), VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                               sizeof(LitPush), &push);
            vkCmdBindIndexBuffer(cmd, xb.handle(), 0, VK_INDEX_TYPE_UINT32);
            vkCmdDrawIndexed(cmd, 6, 3, 0, 0, 0);
            vkCmdEndRenderPass(cmd);
        });
        ASSERT_TRUE(drawn.ok()) << drawn.error().to_string();
        Result<Rgba8Image> img = target.value().read_back(ctx);
        ASSERT_TRUE(img.ok()) << img.error().to_string();
        (void)write_png(::testing::TempDir() + "aloha_lit_mesh_test.png", kSize, kSize, img.value().pixels);

        // Expected colours from the shader formula (normal +z faces the camera at +z).
        const Rgb8 want_red = to_rgb8(lit_colour(red, {0, 0, 1}, push.light));
        const Rgb8 want_blue = to_rgb8(lit_colour(blue, {0, 0, 1}, push.light));
        const Rgb8 want_green = to_rgb8(lit_colour(green, {0, 0, 1}, push.light));
        int n_red = 0, n_blue = 0, n_green = 0, n_clear = 0, n_other = 0;
        double green_row_sum = 0;
        const double half_blue = projected_half_px(push.view_proj, 1.0f, -1.0f);
        int clear_inside_blue = 0;
        for (uint32_t y = 0; y < kSize; ++y) {
            for (uint32_t x = 0; x < kSize; ++x) {
                const uint8_t* px = &img.value().pixels[(y * kSize + x) * 4];
                EXPECT_EQ(px[3], 255);
                if (near(px, want_red, kColourTolLsb)) {
                    ++n_red;
                } else if (near(px, want_blue, kColourTolLsb)) {
                    ++n_blue;
                } else if (near(px, want_green, kColourTolLsb)) {
                    ++n_green;
                    green_row_sum += y;
                } else if (px[0] == 0 && px[1] == 0 && px[2] == 0) {
                    ++n_clear;
                    // Pixels whose centre lies well inside the blue quad must not be clear.
                    const double cx = x + 0.5 - kSize / 2.0, cy = y + 0.5 - kSize / 2.0;
                    if (std::abs(cx) < half_blue - 1 && std::abs(cy) < half_blue - 1) ++clear_inside_blue;
                } else {
                    ++n_other;
                }
            }
        }
        // Coverage: an axis-aligned W x H rectangle covers W*H +- (W + H + 1) pixel centres (each row and
        // column can gain or lose at most one partially covered pixel).
        const double half_red = projected_half_px(push.view_proj, 0.5f, 0.0f);
        const double red_area = 4 * half_red * half_red;
        const double red_tol = 4 * half_red + 1;
        // The green quad occludes part of the red one only if it overlaps it; it is placed at y = 0.75 in
        // front, so its projection (centre ~0.75 * 1.2 = 0.9 in NDC units of the z=0 plane) lies above red.
        EXPECT_NEAR(n_red, red_area, red_tol);
        const double blue_area = 4 * half_blue * half_blue;
        const double green_area = n_green;  // counted; checked separately below
        EXPECT_NEAR(n_blue + n_red + green_area, blue_area, 4 * half_blue + 1 + red_tol);
        EXPECT_GT(n_green, 20);
        EXPECT_EQ(n_other, 0) << "every pixel is clear, or one quad's lit colour within " << kColourTolLsb
                              << " LSB";
        EXPECT_EQ(clear_inside_blue, 0);
        EXPECT_EQ(n_red + n_blue + n_green + n_clear, int(kSize * kSize));
        // Orientation: world +y appears at the top (small row indices).
        EXPECT_LT(green_row_sum / n_green, kSize / 2.0 - 10);
    }
    EXPECT_EQ(ctx.validation_message_count(), 0u)
        << (ctx.validation_messages().empty() ? "" : ctx.validation_messages().front());
}

TEST(LitPipelines, MaterialsDrawWithTheTwinsOfTheirVariantThePlainOnesWithThePlainPipelines) {
    EXPECT_EQ(lit_variant(kLitMesh | kLitTexturedMesh | kLitUnlit | kLitAlphaTest), LitVariant::Plain);
    EXPECT_EQ(lit_variant(kLitMetallicRoughness | kLitTexturedMesh | kLitNormals), LitVariant::MetallicRoughness);
    for (const uint32_t bit : {kLitNormalMap, kLitOcclusion, kLitEmissive, kLitVertexColour}) {
        EXPECT_EQ(lit_variant(bit), LitVariant::Maps);
        EXPECT_EQ(lit_variant(bit | kLitMetallicRoughness), LitVariant::Maps);
    }
    ContextOptions opt;
    opt.validation = true;
    opt.device = "lavapipe";
    Result<std::unique_ptr<Context>> made = Context::create(opt);
    ASSERT_TRUE(made.ok()) << made.error().to_string();
    {
        Result<OffscreenTarget> target = OffscreenTarget::create(*made.value(), 8, 8);
        ASSERT_TRUE(target.ok()) << target.error().to_string();
        Result<LitPipelines> made_pipes = LitPipelines::create(*made.value(), target.value().view().render_pass, 1);
        ASSERT_TRUE(made_pipes.ok()) << made_pipes.error().to_string();
        LitPipelines& pipes = made_pipes.value();
        const VkPipeline plain[8] = {pipes.mesh(), pipes.mesh_culled(), pipes.vertex_lit(), pipes.vertex_lit_culled(),
                                     pipes.dithered(false, false), pipes.dithered(false, true), pipes.dithered(true, false),
                                     pipes.dithered(true, true)};
        // Without a map bit (textured, unlit, alpha-tested, dithered, normal output) a pipeline is its own choice.
        for (const VkPipeline p : plain)
            for (const uint32_t mode : {uint32_t{kLitMesh}, uint32_t{kLitTexturedMesh}, uint32_t{kLitNormals} | kLitTexturedMesh,
                                        kLitUnlit | kLitAlphaTest | lit_dither_bits(0.5f)})
                EXPECT_EQ(pipes.for_mode(p, mode), p);
        ASSERT_TRUE(pipes.ensure_variant(kLitMesh).ok());  // plain: nothing to build
        for (const uint32_t mode : {uint32_t{kLitMetallicRoughness}, uint32_t{kLitNormalMap}}) {
            ASSERT_TRUE(pipes.ensure_variant(mode).ok());
            ASSERT_TRUE(pipes.ensure_variant(mode).ok());  // once: the second call keeps the first twins
        }
        std::vector<VkPipeline> twins;
        for (const VkPipeline p : plain) {
            const VkPipeline pbr = pipes.for_mode(p, kLitMetallicRoughness | kLitTexturedMesh);
            const VkPipeline maps = pipes.for_mode(p, kLitNormalMap);
            EXPECT_NE(pbr, VK_NULL_HANDLE);
            EXPECT_NE(maps, VK_NULL_HANDLE);
            for (const uint32_t bit : {kLitOcclusion, kLitEmissive, kLitVertexColour})
                EXPECT_EQ(pipes.for_mode(p, bit | kLitMetallicRoughness | kLitTexturedMesh), maps);
            twins.push_back(pbr);
            twins.push_back(maps);
            twins.push_back(p);
        }
        std::sort(twins.begin(), twins.end());
        EXPECT_EQ(std::unique(twins.begin(), twins.end()), twins.end()) << "each pipeline has a twin of its own per variant";
    }
    EXPECT_EQ(made.value()->validation_message_count(), 0u);
}

TEST(Buffers, RejectZeroSizes) {
    ContextOptions opt;
    opt.device = "lavapipe";
    Result<std::unique_ptr<Context>> made = Context::create(opt);
    ASSERT_TRUE(made.ok()) << made.error().to_string();
    EXPECT_FALSE(Buffer::create(*made.value(), 0, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT).ok());
    EXPECT_FALSE(OffscreenTarget::create(*made.value(), 0, 16).ok());
}

TEST(OffscreenTarget, ReadBackBeforeDrawingIsCleared) {
    ContextOptions opt;
    opt.validation = true;
    opt.device = "lavapipe";
    Result<std::unique_ptr<Context>> made = Context::create(opt);
    ASSERT_TRUE(made.ok()) << made.error().to_string();
    {
        Result<OffscreenTarget> t = OffscreenTarget::create(*made.value(), 8, 4, /*srgb=*/true);
        ASSERT_TRUE(t.ok()) << t.error().to_string();
        Result<Rgba8Image> img = t.value().read_back(*made.value());
        ASSERT_TRUE(img.ok()) << img.error().to_string();
        EXPECT_EQ(img.value().pixels, std::vector<uint8_t>(8 * 4 * 4, 0));
    }
    EXPECT_EQ(made.value()->validation_message_count(), 0u);
}

}  // namespace
}  // namespace aloha::gpu
