// Per-pass GPU timestamps (RendererOptions::pass_timestamps) on lavapipe under validation: the passes are
// listed in recording order (mesh passes by label in the order labels were first registered, then proxies,
// lines, resolve) with their draws, instances and triangles; their times add up to the frame's; the image is
// the same with and without them; and without them no pass is reported.
#include "engine/gpu/context.hpp"
#include "render_scene.hpp"

#include <gtest/gtest.h>

namespace aloha {
namespace {

struct PassRun {
    gpu::Rgba8Image image;
    std::vector<GpuPassTime> passes;
    double gpu_ms = -1.0;
};

PassRun render_with(gpu::Context& ctx, bool pass_timestamps) {
    PassRun out;
    RendererOptions o;
    o.pass_timestamps = pass_timestamps;
    Result<std::unique_ptr<CrowdRenderer>> r = CrowdRenderer::create(ctx, o);
    EXPECT_TRUE(r.ok()) << r.error().to_string();
    if (!r.ok()) return out;
    CrowdRenderer& renderer = *r.value();
    test::RenderScene scene;
    const std::vector<uint32_t> grid = {0, 1, 4, 0, 4, 3, 1, 2, 5, 1, 5, 4, 3, 4, 7, 3, 7, 6, 4, 5, 8, 4, 8, 7};
    const std::vector<uint32_t> tri = {0, 1, 2};
    // Labels first seen in this order: "far" (the triangle), then "near" (the grid).
    const uint32_t tri_id = renderer.register_topology(tri, 0, false, {}, "far").value();
    const uint32_t grid_id = renderer.register_topology(grid, 0, false, {}, "near").value();
    scene.build(grid_id, tri_id, 0.3f);
    Result<gpu::OffscreenTarget> target = gpu::OffscreenTarget::create(ctx, test::kSceneSize, test::kSceneSize);
    EXPECT_TRUE(target.ok());
    if (!target.ok()) return out;
    for (int frame = 0; frame < 3; ++frame) {  // several frames: the slots' query pools are reused
        Status s = renderer.render(scene.frame, target.value());
        EXPECT_TRUE(s.ok()) << s.error().to_string();
    }
    EXPECT_TRUE(renderer.finish().ok());
    Result<gpu::Rgba8Image> img = target.value().read_back(ctx);
    EXPECT_TRUE(img.ok());
    if (img.ok()) out.image = std::move(img).value();
    out.passes.assign(renderer.last_gpu_passes().begin(), renderer.last_gpu_passes().end());
    out.gpu_ms = renderer.last_gpu_ms();
    return out;
}

TEST(PassTiming, PassesInOrderWithTheirWorkAndTimesThatAddUp) {
    gpu::ContextOptions co;
    co.validation = true;
    co.device = "lavapipe";
    Result<std::unique_ptr<gpu::Context>> c = gpu::Context::create(co);
    ASSERT_TRUE(c.ok()) << c.error().to_string();
    gpu::Context& ctx = *c.value();
    if (!ctx.timestamps_supported()) GTEST_SKIP() << "the device has no timestamp queries";
    const PassRun timed = render_with(ctx, true);
    const PassRun plain = render_with(ctx, false);
    EXPECT_TRUE(plain.passes.empty());
    EXPECT_GT(plain.gpu_ms, 0.0);
    // The timestamps only split the work: the picture is the same, byte for byte.
    EXPECT_EQ(timed.image.pixels, plain.image.pixels);
    ASSERT_EQ(timed.passes.size(), 5u);
    struct Expect {
        const char* name;
        uint32_t draws;
        uint64_t instances, triangles;
    };
    // far: 1 triangle mesh; near: 2 grid meshes of 8 triangles; proxies: 2 boxes of 12; lines: 1 segment.
    const Expect expect[] = {{"far", 1, 1, 1}, {"near", 1, 2, 16}, {"proxies", 1, 2, 24}, {"lines", 1, 1, 0}, {"resolve", 0, 0, 0}};
    double end = 0.0;
    for (size_t k = 0; k < 5; ++k) {
        const GpuPassTime& p = timed.passes[k];
        EXPECT_EQ(p.name, expect[k].name);
        EXPECT_EQ(p.draws, expect[k].draws) << p.name;
        EXPECT_EQ(p.instances, expect[k].instances) << p.name;
        EXPECT_EQ(p.triangles, expect[k].triangles) << p.name;
        EXPECT_GE(p.ms, 0.0) << p.name;
        // Each pass starts where the one before ended (consecutive timestamps); 1e-9 ms covers rounding.
        EXPECT_NEAR(p.begin_ms, end, 1e-9) << p.name;
        end = p.begin_ms + p.ms;
    }
    EXPECT_NEAR(end, timed.gpu_ms, 1e-9);
    EXPECT_EQ(ctx.validation_message_count(), 0u)
        << (ctx.validation_messages().empty() ? "" : ctx.validation_messages().front());
}

}  // namespace
}  // namespace aloha
