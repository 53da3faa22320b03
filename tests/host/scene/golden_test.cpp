// Golden images of the whole pipeline (scene -> World -> CrowdRenderer on lavapipe under validation):
// the close-up's character at each geometric level, the crowd in each debug colouring, and the layer
// overlay. Tolerant comparison (8 LSB per channel, at most 1% of pixels) absorbs rasterisation noise;
// ALOHA_UPDATE_GOLDEN=1 rewrites the PNGs.
#include "engine/gpu/context.hpp"
#include "engine/gpu/offscreen_target.hpp"
#include "host/scene/scene_loader.hpp"
#include "host/scene/world.hpp"
#include "systems/lod/rule_table.hpp"
#include "systems/render/image_compare.hpp"

#include <gtest/gtest.h>
#include <unistd.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>

namespace aloha {
namespace {

namespace fs = std::filesystem;
const std::string kData = std::string(ALOHA_SOURCE_DIR) + "/data/";
const std::string kGolden = std::string(ALOHA_SOURCE_DIR) + "/tests/host/scene/golden/";

// Writes a copy of the default rules whose only rule puts everyone at `level` into `dir`.
std::string single_level_rules(const fs::path& dir, const std::string& level) {
    std::ifstream in(kData + "rules/default.json");
    nlohmann::json rules = nlohmann::json::parse(in, nullptr, true, true);
    rules.erase("$schema");
    rules["rules"] = nlohmann::json::array({{{"name", "all"}, {"then", {{"geometry", level}, {"animation", "kinematic_ccd"}}}}});
    const fs::path path = dir / ("rules_" + level + ".json");
    std::ofstream(path) << rules.dump(1);
    return path.string();
}

struct Renderer {
    std::unique_ptr<gpu::Context> ctx;
    std::unique_ptr<CrowdRenderer> renderer;
    gpu::OffscreenTarget target;
};

// Runs `scene` for `frames` frames into a width x height target and returns the image.
gpu::Rgba8Image render(SceneDesc scene, uint32_t frames, uint32_t width, uint32_t height, WorldOptions options = {}) {
    scene.width = width;
    scene.height = height;
    gpu::ContextOptions co;
    co.validation = true;
    co.device = "lavapipe";
    auto ctx = gpu::Context::create(co);
    EXPECT_TRUE(ctx.ok()) << (ctx.ok() ? "" : ctx.error().to_string());
    if (!ctx.ok()) return {};
    Renderer r;
    r.ctx = std::move(ctx.value());
    auto renderer = CrowdRenderer::create(*r.ctx);
    EXPECT_TRUE(renderer.ok());
    r.renderer = std::move(renderer.value());
    auto target = gpu::OffscreenTarget::create(*r.ctx, width, height);
    EXPECT_TRUE(target.ok());
    r.target = std::move(target.value());
    gpu::Rgba8Image image;
    {
        auto world = World::create(scene, options);
        EXPECT_TRUE(world.ok()) << (world.ok() ? "" : world.error().to_string());
        if (!world.ok()) return {};
        EXPECT_TRUE(world.value()->attach_renderer(r.renderer.get(), &r.target).ok());
        for (uint32_t f = 0; f < frames; ++f) world.value()->step();
        EXPECT_TRUE(world.value()->render_status().ok()) << world.value()->render_status().error().to_string();
        auto read = r.target.read_back(*r.ctx);
        EXPECT_TRUE(read.ok());
        if (read.ok()) image = std::move(read.value());
    }
    r.renderer.reset();
    EXPECT_EQ(r.ctx->validation_message_count(), 0u);
    return image;
}

void expect_golden(const gpu::Rgba8Image& image, const std::string& name) {
    GoldenOptions options;
    options.max_fraction = 0.01;
    options.actual_dump_path = (fs::temp_directory_path() / ("aloha_actual_" + name)).string();
    const Status s = check_golden(image, kGolden + name, options);
    EXPECT_TRUE(s.ok()) << s.error().to_string();
}

SceneDesc closeup() {
    auto scene = load_scene(kData + "scenes/closeup.json");
    EXPECT_TRUE(scene.ok());
    SceneDesc s = scene.value();
    s.camera.keys = {{0.0f, {1.4f, 1.3f, 2.6f}, {0.3f, 0.95f, 0.6f}}};
    s.camera.fov_y_deg = 45.0f;
    return s;
}

// crowd_1k cut to 200 characters, seen from a fixed camera at their edge.
SceneDesc small_crowd() {
    auto scene = load_scene(kData + "scenes/crowd_1k.json");
    EXPECT_TRUE(scene.ok());
    SceneDesc s = scene.value();
    s.crowds[0].count = 200;
    s.camera.keys = {{0.0f, {2.0f, 2.5f, 16.0f}, {0.0f, 0.8f, 4.0f}}};
    return s;
}

TEST(Golden, CloseupAtEachGeometricLevel) {
    // One directory per process: two suites running at once (worktrees, ctest -j) must not remove each other's.
    const fs::path dir = fs::temp_directory_path() / ("aloha_golden_levels_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    for (const char* level : {"proxy", "skinned", "layered_low", "layered_high", "subdivided"}) {
        SceneDesc s = closeup();
        s.rules = single_level_rules(dir, level);
        expect_golden(render(s, 30, 240, 320), std::string("closeup_") + level + ".png");
    }
    fs::remove_all(dir);
}

TEST(Golden, CrowdInEachDebugColouring) {
    const SceneDesc s = small_crowd();
    for (const auto& [colour, name] : {std::pair{DebugColour::Shaded, "shaded"}, {DebugColour::ByLodLevel, "level"},
                                       {DebugColour::ByRule, "rule"}, {DebugColour::ByMotionMethod, "method"}}) {
        WorldOptions o;
        o.colour = colour;
        const gpu::Rgba8Image image = render(s, 20, 480, 270, o);
        expect_golden(image, std::string("crowd_") + name + ".png");
        if (colour != DebugColour::Shaded) continue;
        // With overlap_gpu the render system returns before the GPU has drawn the frame (the next
        // step's CPU systems run meanwhile); a read-back on the renderer's queue still sees every
        // submitted frame, so the picture after 20 steps is the serial run's bit for bit (same draws,
        // same inputs, lavapipe deterministic in one process).
        WorldOptions overlapped = o;
        overlapped.overlap_gpu = GpuOverlap::On;
        const gpu::Rgba8Image drawn_while_next_frame_runs = render(s, 20, 480, 270, overlapped);
        ASSERT_EQ(drawn_while_next_frame_runs.pixels.size(), image.pixels.size());
        EXPECT_TRUE(drawn_while_next_frame_runs.pixels == image.pixels) << "overlap_gpu changed the picture";
    }
}

TEST(Golden, LayerOverlay) {
    const fs::path dir = fs::temp_directory_path() / "aloha_golden_overlay";
    fs::create_directories(dir);
    SceneDesc s = closeup();
    s.rules = single_level_rules(dir, "layered_low");
    WorldOptions o;
    o.overlay = kOverlayBones | kOverlayMuscles | kOverlaySprings;
    expect_golden(render(s, 30, 240, 320, o), "closeup_overlay.png");
    fs::remove_all(dir);
}

}  // namespace
}  // namespace aloha
