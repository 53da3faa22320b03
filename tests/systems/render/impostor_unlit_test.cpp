// Impostors of unlit materials (KHR_materials_unlit) on lavapipe under validation: the figure of
// impostor_figure.hpp with an unlit body and a lit head, baked and drawn as an impostor under the characters'
// lighting, matches the direct render (body its albedo as it is, head shaded) within the same tolerance as the
// all-lit figure: the bake writes no normal for unlit surfaces, and the impostor shader shows the albedo
// unshaded in the share of each texel that was unlit.
#include "impostor_figure.hpp"
#include "render_scene.hpp"

#include <gtest/gtest.h>

namespace aloha {
namespace {

using namespace impostor_test;

TEST(ImpostorUnlit, UnlitBodyAndLitHeadMatchADirectRender) {
    std::unique_ptr<gpu::Context> ctx = test::lavapipe_context();
    ASSERT_TRUE(ctx);
    const Figure fig;
    const size_t body_vertices = size_t{25} * 33;  // the first ellipsoid: (24 + 1) rings x (32 + 1) segments
    std::vector<uint16_t> vertex_material(fig.positions.size(), 1);
    std::fill(vertex_material.begin(), vertex_material.begin() + static_cast<std::ptrdiff_t>(body_vertices), uint16_t{0});
    std::vector<SurfaceMaterial> materials(2);
    materials[0].name = "unlit body";
    materials[0].unlit = true;
    materials[0].base_colour = {0.6f, 0.3f, 0.2f, 1.0f};
    materials[1].name = "lit head";
    materials[1].base_colour = {0.3f, 0.5f, 0.7f, 1.0f};
    ImpostorBakeInput in = bake_input(fig, 2);
    in.vertex_material = vertex_material;
    in.materials = materials;
    Result<ImpostorAtlas> atlas = bake_impostor_atlas(*ctx, in);
    ASSERT_TRUE(atlas.ok()) << atlas.error().to_string();

    Result<std::unique_ptr<CrowdRenderer>> made = CrowdRenderer::create(*ctx);
    ASSERT_TRUE(made.ok()) << made.error().to_string();
    CrowdRenderer& r = *made.value();
    const std::vector<uint32_t> ids = {r.register_material(materials[0]).value(), r.register_material(materials[1]).value()};
    Result<uint32_t> topology = r.register_topology(fig.indices, 0, true, {{}, vertex_material, ids, {}});
    ASSERT_TRUE(topology.ok()) << topology.error().to_string();
    Result<uint32_t> id = r.register_impostor_atlas(atlas.value().image, atlas.value().layout);
    ASSERT_TRUE(id.ok()) << id.error().to_string();
    for (const uint32_t d : {0u, 5u, 12u}) {
        SCOPED_TRACE("direction " + std::to_string(d));
        const float azimuth = 6.28318531f * float(d) / 16.0f;
        FrameInput direct = camera_frame(azimuth);
        const std::vector<DeformableMesh> meshes = {{topology.value(), fig.positions, fig.normals, glm::mat4(1.0f), glm::vec4(1.0f)}};
        direct.meshes = meshes;
        Result<gpu::Rgba8Image> a = draw(r, *ctx, direct);
        ASSERT_TRUE(a.ok()) << a.error().to_string();
        FrameInput quad = camera_frame(azimuth);
        ImpostorInstance inst;
        inst.forward_phase = glm::vec4(0.0f, 1.0f, 0.0f, 1.0f);
        inst.colour = glm::vec4(1.0f);
        inst.atlas = id.value();
        quad.impostors = std::span(&inst, 1);
        Result<gpu::Rgba8Image> b = draw(r, *ctx, quad);
        ASSERT_TRUE(b.ok()) << b.error().to_string();
        expect_matches(a.value(), b.value());
    }
    EXPECT_TRUE(ctx->validation_messages().empty());
}

}  // namespace
}  // namespace aloha
