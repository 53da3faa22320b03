// A small fixed crowd scene shared by the render tests: two topologies (a 3x3-vertex square grid and a
// triangle), three deformable meshes interleaved by topology, two proxy boxes and one line, seen through
// an orthographic camera of 32 pixels per world unit on a 128 x 128 target.
#pragma once

#include "engine/gpu/context.hpp"
#include "systems/render/crowd_renderer.hpp"
#include "systems/render/debug_colours.hpp"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <memory>

#include <vector>

namespace aloha::test {

/// A lavapipe Context with validation on (render tests fail on any validation message); null, with a test
/// failure, when it cannot be created.
inline std::unique_ptr<gpu::Context> lavapipe_context() {
    gpu::ContextOptions o;
    o.validation = true;
    o.device = "lavapipe";
    Result<std::unique_ptr<gpu::Context>> c = gpu::Context::create(o);
    EXPECT_TRUE(c.ok()) << c.error().to_string();
    return c.ok() ? std::move(c).value() : nullptr;
}

/// Renders `frame` with `r` into a fresh `size` x `size` offscreen target and reads it back.
inline Result<gpu::Rgba8Image> draw_square(CrowdRenderer& r, gpu::Context& ctx, const FrameInput& frame, uint32_t size) {
    Result<gpu::OffscreenTarget> target = gpu::OffscreenTarget::create(ctx, size, size);
    if (!target.ok()) return target.error();
    if (Status s = r.render(frame, target.value()); !s.ok()) return s.error();
    if (Status s = r.finish(); !s.ok()) return s.error();
    return target.value().read_back(ctx);
}

inline constexpr uint32_t kSceneSize = 128;
inline constexpr float kPixelsPerUnit = 32.0f;  // ortho [-2, 2] over 128 pixels

/// Owns the vertex data the FrameInput spans point at.
struct RenderScene {
    std::vector<uint32_t> grid_indices, tri_indices;
    std::vector<glm::vec3> grid_a, grid_b, tri, grid_normals, tri_normals;
    std::vector<DeformableMesh> meshes;
    std::vector<ProxyInstance> proxies;
    std::vector<LineSegment> lines;
    FrameInput frame;

    /// Builds the geometry; topology ids are those register_topology returned for grid and triangle.
    void build(uint32_t grid_topology, uint32_t tri_topology, float ambient) {
        // 3x3 grid over the unit square [-0.5, 0.5]^2, z = 0, 8 triangles.
        for (int y = 0; y < 3; ++y)
            for (int x = 0; x < 3; ++x) {
                grid_a.push_back({-0.5f + 0.5f * x, -0.5f + 0.5f * y, 0.0f});
                grid_b.push_back(0.5f * grid_a.back());  // same topology, half-size vertices
                grid_normals.push_back({0.0f, 0.0f, 1.0f});
            }
        tri = {{-0.5f, -0.5f, 0.0f}, {0.5f, -0.5f, 0.0f}, {-0.5f, 0.5f, 0.0f}};
        tri_normals.assign(3, {0.0f, 0.0f, 1.0f});
        const auto at = [](float x, float y) { return glm::translate(glm::mat4(1.0f), {x, y, 0.0f}); };
        // Interleaved topologies: grid, triangle, grid (the renderer regroups them).
        meshes.push_back({grid_topology, grid_a, grid_normals, at(-1.0f, 1.0f), colour_for_level(0)});
        meshes.push_back({tri_topology, tri, tri_normals, at(0.0f, 0.0f), colour_for_level(4)});
        meshes.push_back({grid_topology, grid_b, grid_normals, at(-1.0f, -1.0f), colour_for_level(1)});
        proxies.push_back({at(1.0f, 1.0f), colour_for_level(2)});
        proxies.push_back({glm::scale(at(1.0f, -1.0f), {0.5f, 1.5f, 0.5f}), colour_for_level(3)});
        lines.push_back({{-1.9f, -1.9f, 0.5f}, {1.9f, -1.9f, 0.5f}, colour_for_rule(5)});
        frame.camera.view = glm::lookAt(glm::vec3(0, 0, 5), glm::vec3(0), glm::vec3(0, 1, 0));
        frame.camera.proj = glm::ortho(-2.0f, 2.0f, -2.0f, 2.0f, 0.1f, 20.0f);
        frame.meshes = meshes;
        frame.proxies = proxies;
        frame.lines = lines;
        frame.clear_colour = {0.0f, 0.0f, 0.0f, 1.0f};
        frame.light_direction = {0.4f, 0.6f, 1.0f};
        frame.ambient = ambient;
    }
};

}  // namespace aloha::test
