// LitPipelines' variants (engine/gpu/lit_pipeline.hpp, gpu::LitVariant): the shaders each variant's mesh pipelines
// take, the twins built for a material's variant and the choice of pipeline per LitMode bits.
#include "engine/gpu/lit_pipeline.hpp"
#include "engine/gpu/lit_pipeline_build.hpp"

#include "shaders/lit_constant_frag.h"
#include "shaders/lit_mesh_dither_frag.h"
#include "shaders/lit_mesh_dither_maps_frag.h"
#include "shaders/lit_mesh_dither_pbr_frag.h"
#include "shaders/lit_mesh_frag.h"
#include "shaders/lit_mesh_maps_frag.h"
#include "shaders/lit_mesh_maps_vert.h"
#include "shaders/lit_mesh_pbr_frag.h"
#include "shaders/lit_mesh_vert.h"
#include "shaders/lit_mesh_vertex_lit_maps_vert.h"
#include "shaders/lit_mesh_vertex_lit_pbr_vert.h"
#include "shaders/lit_mesh_vertex_lit_vert.h"
#include "shaders/lit_vertex_dither_frag.h"
#include "shaders/lit_vertex_dither_maps_frag.h"
#include "shaders/lit_vertex_frag.h"
#include "shaders/lit_vertex_maps_frag.h"

#include <cassert>

namespace aloha::gpu {
namespace detail {

using Spirv = std::span<const uint32_t>;

// The shaders of one build of the mesh pipelines: per pixel (vertex shader, fragment shader, its dithered build) and
// vertex-lit (the same three).
struct LitShaders {
    Spirv mesh_vert, mesh_frag, mesh_dither_frag, vertex_vert, vertex_frag, vertex_dither_frag;
};

std::array<PipelineDesc, 8> lit_descs(LitVariant variant, bool constant_fragments) {
    // Per LitVariant. Metallic-roughness is lit per pixel by the fragment shader and at the vertices by the vertex-lit
    // vertex shader; the vertex-lit fragment shaders draw only the emissive map of the maps.
    static const LitShaders kBuilds[3] = {
        {k_lit_mesh_vert_spv, k_lit_mesh_frag_spv, k_lit_mesh_dither_frag_spv, k_lit_mesh_vertex_lit_vert_spv,
         k_lit_vertex_frag_spv, k_lit_vertex_dither_frag_spv},
        {k_lit_mesh_vert_spv, k_lit_mesh_pbr_frag_spv, k_lit_mesh_dither_pbr_frag_spv, k_lit_mesh_vertex_lit_pbr_vert_spv,
         k_lit_vertex_frag_spv, k_lit_vertex_dither_frag_spv},
        {k_lit_mesh_maps_vert_spv, k_lit_mesh_maps_frag_spv, k_lit_mesh_dither_maps_frag_spv, k_lit_mesh_vertex_lit_maps_vert_spv,
         k_lit_vertex_maps_frag_spv, k_lit_vertex_dither_maps_frag_spv},
    };
    LitShaders b = kBuilds[static_cast<uint32_t>(variant)];
    if (constant_fragments)  // profiling: the plain build with lit_constant.frag, whose flat colour the per-pixel vertex shader feeds
        b = {k_lit_mesh_vert_spv, k_lit_constant_frag_spv, k_lit_mesh_dither_frag_spv, k_lit_mesh_vert_spv, k_lit_constant_frag_spv,
             k_lit_mesh_dither_frag_spv};
    constexpr VkPrimitiveTopology kTriangles = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    constexpr VkCullModeFlags kNone = VK_CULL_MODE_NONE, kBack = VK_CULL_MODE_BACK_BIT;
    return {{{b.mesh_vert, b.mesh_frag, kTriangles, VK_COMPARE_OP_LESS, kNone},
             {b.mesh_vert, b.mesh_frag, kTriangles, VK_COMPARE_OP_LESS, kBack},
             {b.vertex_vert, b.vertex_frag, kTriangles, VK_COMPARE_OP_LESS, kNone},
             {b.vertex_vert, b.vertex_frag, kTriangles, VK_COMPARE_OP_LESS, kBack},
             {b.mesh_vert, b.mesh_dither_frag, kTriangles, VK_COMPARE_OP_LESS, kNone},
             {b.mesh_vert, b.mesh_dither_frag, kTriangles, VK_COMPARE_OP_LESS, kBack},
             {b.vertex_vert, b.vertex_dither_frag, kTriangles, VK_COMPARE_OP_LESS, kNone},
             {b.vertex_vert, b.vertex_dither_frag, kTriangles, VK_COMPARE_OP_LESS, kBack}}};
}

}  // namespace detail

Status LitPipelines::ensure_variant(uint32_t mode) {
    const LitVariant variant = lit_variant(mode);
    if (variant == LitVariant::Plain || constant_fragments_) return {};  // profiling draws every material plain
    std::array<VkPipeline, 8>& twins = twins_[static_cast<uint32_t>(variant) - 1];
    if (twins[0] != VK_NULL_HANDLE) return {};
    const std::array<detail::PipelineDesc, 8> lit = detail::lit_descs(variant, false);
    std::array<VkPipeline, 8> made{};
    for (size_t i = 0; i < made.size(); ++i) {
        Result<VkPipeline> p = detail::make_pipeline(device_, layout_, render_pass_, lit[i]);
        if (!p) {
            for (VkPipeline q : made)
                if (q != VK_NULL_HANDLE) vkDestroyPipeline(device_, q, nullptr);
            return p.error();
        }
        made[i] = p.value();
    }
    twins = made;
    return {};
}

VkPipeline LitPipelines::for_mode(VkPipeline pipeline, uint32_t mode) const {
    const LitVariant variant = lit_variant(mode);
    if (variant == LitVariant::Plain || constant_fragments_) return pipeline;
    const std::array<VkPipeline, 8>& twins = twins_[static_cast<uint32_t>(variant) - 1];
    const VkPipeline plain[8] = {mesh_, culled_, vertex_lit_, vertex_lit_culled_, dithered_[0], dithered_[1], dithered_[2], dithered_[3]};
    for (size_t i = 0; i < 8; ++i)
        if (plain[i] == pipeline) {
            assert(twins[i] != VK_NULL_HANDLE && "LitPipelines::for_mode: ensure_variant() was not called for this mode");
            return twins[i];
        }
    assert(false && "LitPipelines::for_mode: not a mesh pipeline");
    return pipeline;
}

}  // namespace aloha::gpu
