// CrowdRenderer bookkeeping: per-frame buffers grow only when exceeded (then never again for the same
// load), invalid frame input is rejected with every problem listed, bad topologies are rejected.
#include "engine/gpu/context.hpp"
#include "render_scene.hpp"

#include <gtest/gtest.h>

namespace aloha {
namespace {

const std::vector<uint32_t> kGrid = {0, 1, 4, 0, 4, 3, 1, 2, 5, 1, 5, 4, 3, 4, 7, 3, 7, 6, 4, 5, 8, 4, 8, 7};
const std::vector<uint32_t> kTri = {0, 1, 2};

TEST(CrowdRendererBuffers, GrowOnlyWhenExceeded) {
    std::unique_ptr<gpu::Context> ctx = test::lavapipe_context();
    ASSERT_TRUE(ctx);
    {
        RendererOptions opt;
        opt.frames_in_flight = 2;
        opt.initial_vertices = 8;  // smaller than the scene: every buffer kind must grow once per slot
        opt.initial_instances = 1;
        opt.initial_line_segments = 1;
        Result<std::unique_ptr<CrowdRenderer>> r = CrowdRenderer::create(*ctx, opt);
        ASSERT_TRUE(r.ok()) << r.error().to_string();
        CrowdRenderer& renderer = *r.value();
        EXPECT_EQ(renderer.growth_events(), 0u) << "initial allocation is not growth";
        test::RenderScene scene;
        const uint32_t grid = renderer.register_topology(kGrid).value();
        const uint32_t tri = renderer.register_topology(kTri).value();
        scene.build(grid, tri, 0.5f);
        Result<gpu::OffscreenTarget> target = gpu::OffscreenTarget::create(*ctx, 64, 64);
        ASSERT_TRUE(target.ok());
        ASSERT_TRUE(renderer.render(scene.frame, target.value()).ok());
        // Slot 0: positions, normals (21 > 8 vertices), instances (5 > 1) and the proxy index batch
        // (2 boxes > 1) grow; lines (1 segment) fit in the initial single segment.
        EXPECT_EQ(renderer.growth_events(), 4u);
        ASSERT_TRUE(renderer.render(scene.frame, target.value()).ok());
        EXPECT_EQ(renderer.growth_events(), 8u);  // slot 1 grows the same way
        for (int i = 0; i < 6; ++i) ASSERT_TRUE(renderer.render(scene.frame, target.value()).ok());
        EXPECT_EQ(renderer.growth_events(), 8u) << "same load: no more growth";
        // A smaller frame never shrinks or regrows.
        scene.frame.meshes = std::span(scene.meshes).first(1);
        ASSERT_TRUE(renderer.render(scene.frame, target.value()).ok());
        EXPECT_EQ(renderer.growth_events(), 8u);
        EXPECT_EQ(renderer.frame_count(), 9u);
        ASSERT_TRUE(renderer.finish().ok());
    }
    EXPECT_EQ(ctx->validation_message_count(), 0u)
        << (ctx->validation_messages().empty() ? "" : ctx->validation_messages().front());
}

TEST(CrowdRendererBuffers, InvalidInputListsEveryProblem) {
    std::unique_ptr<gpu::Context> ctx = test::lavapipe_context();
    ASSERT_TRUE(ctx);
    Result<std::unique_ptr<CrowdRenderer>> r = CrowdRenderer::create(*ctx);
    ASSERT_TRUE(r.ok());
    CrowdRenderer& renderer = *r.value();
    const uint32_t grid = renderer.register_topology(kGrid).value();
    EXPECT_EQ(renderer.topology_vertex_count(grid), 9u);
    std::vector<glm::vec3> eight(8, glm::vec3(0.0f)), nine(9, glm::vec3(0.0f));
    std::vector<DeformableMesh> meshes = {
        {grid, eight, eight, glm::mat4(1.0f), glm::vec4(1.0f)},  // wrong vertex count
        {grid, nine, eight, glm::mat4(1.0f), glm::vec4(1.0f)},   // normals != positions
        {7, nine, nine, glm::mat4(1.0f), glm::vec4(1.0f)},       // unknown topology
    };
    FrameInput frame;
    frame.meshes = meshes;
    std::vector<std::string> errors;
    EXPECT_FALSE(renderer.Validate(frame, &errors));
    ASSERT_EQ(errors.size(), 3u);
    EXPECT_NE(errors[0].find("meshes[0]"), std::string::npos);
    EXPECT_NE(errors[1].find("meshes[1]"), std::string::npos);
    EXPECT_NE(errors[2].find("topology 7"), std::string::npos);
    Result<gpu::OffscreenTarget> target = gpu::OffscreenTarget::create(*ctx, 16, 16);
    ASSERT_TRUE(target.ok());
    Status s = renderer.render(frame, target.value());
    ASSERT_FALSE(s.ok());
    EXPECT_NE(s.error().message.find("meshes[2]"), std::string::npos) << s.error().message;
    EXPECT_EQ(renderer.frame_count(), 0u) << "nothing submitted for invalid input";
}

TEST(CrowdRendererBuffers, RejectsBadTopologiesAndFormats) {
    std::unique_ptr<gpu::Context> ctx = test::lavapipe_context();
    ASSERT_TRUE(ctx);
    Result<std::unique_ptr<CrowdRenderer>> r = CrowdRenderer::create(*ctx);
    ASSERT_TRUE(r.ok());
    const std::vector<uint32_t> two = {0, 1};
    EXPECT_FALSE(r.value()->register_topology(two).ok());
    EXPECT_FALSE(r.value()->register_topology(std::span<const uint32_t>{}).ok());
    EXPECT_FALSE(r.value()->register_topology(kTri, /*vertex_count=*/2).ok());
    EXPECT_EQ(r.value()->register_topology(kTri, 10).value(), 0u);
    EXPECT_EQ(r.value()->topology_vertex_count(0), 10u);
    Result<gpu::OffscreenTarget> srgb = gpu::OffscreenTarget::create(*ctx, 16, 16, /*srgb=*/true);
    ASSERT_TRUE(srgb.ok());
    EXPECT_FALSE(r.value()->render(FrameInput{}, srgb.value()).ok()) << "renderer was built for UNORM";
}

}  // namespace
}  // namespace aloha
