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

std::array<PipelineDesc, 8> lit_descs(LitVariant variant, bool constant_fragments) {
    if (constant_fragments) variant = LitVariant::Plain;
    const bool maps = variant == LitVariant::Maps, pbr = variant == LitVariant::MetallicRoughness;
    const Spirv mesh_vert = maps ? Spirv(k_lit_mesh_maps_vert_spv) : Spirv(k_lit_mesh_vert_spv);  // MR is per pixel
    const Spirv mesh_frag = constant_fragments ? Spirv(k_lit_constant_frag_spv)
                            : maps             ? Spirv(k_lit_mesh_maps_frag_spv)
                            : pbr              ? Spirv(k_lit_mesh_pbr_frag_spv)
                                               : Spirv(k_lit_mesh_frag_spv);
    const Spirv mesh_dither_frag = maps  ? Spirv(k_lit_mesh_dither_maps_frag_spv)
                                   : pbr ? Spirv(k_lit_mesh_dither_pbr_frag_spv)
                                         : Spirv(k_lit_mesh_dither_frag_spv);
    const Spirv vertex_vert = constant_fragments ? Spirv(k_lit_mesh_vert_spv)
                              : maps             ? Spirv(k_lit_mesh_vertex_lit_maps_vert_spv)
                              : pbr              ? Spirv(k_lit_mesh_vertex_lit_pbr_vert_spv)
                                                 : Spirv(k_lit_mesh_vertex_lit_vert_spv);
    // The vertex-lit fragment shaders draw only the emissive map of the maps: MR is lit at the vertices.
    const Spirv vertex_frag = constant_fragments ? Spirv(k_lit_constant_frag_spv)
                              : maps             ? Spirv(k_lit_vertex_maps_frag_spv)
                                                 : Spirv(k_lit_vertex_frag_spv);
    const Spirv vertex_dither_frag = constant_fragments ? Spirv(k_lit_mesh_dither_frag_spv)
                                     : maps             ? Spirv(k_lit_vertex_dither_maps_frag_spv)
                                                        : Spirv(k_lit_vertex_dither_frag_spv);
    constexpr VkPrimitiveTopology kTriangles = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    constexpr VkCullModeFlags kNone = VK_CULL_MODE_NONE, kBack = VK_CULL_MODE_BACK_BIT;
    return {{{mesh_vert, mesh_frag, kTriangles, VK_COMPARE_OP_LESS, kNone},
             {mesh_vert, mesh_frag, kTriangles, VK_COMPARE_OP_LESS, kBack},
             {vertex_vert, vertex_frag, kTriangles, VK_COMPARE_OP_LESS, kNone},
             {vertex_vert, vertex_frag, kTriangles, VK_COMPARE_OP_LESS, kBack},
             {mesh_vert, mesh_dither_frag, kTriangles, VK_COMPARE_OP_LESS, kNone},
             {mesh_vert, mesh_dither_frag, kTriangles, VK_COMPARE_OP_LESS, kBack},
             {vertex_vert, vertex_dither_frag, kTriangles, VK_COMPARE_OP_LESS, kNone},
             {vertex_vert, vertex_dither_frag, kTriangles, VK_COMPARE_OP_LESS, kBack}}};
}

}  // namespace detail

Status LitPipelines::ensure_variant(uint32_t mode) {
    const LitVariant variant = lit_variant(mode);
    if (variant == LitVariant::Plain) return {};
    std::array<VkPipeline, 8>& twins = twins_[static_cast<uint32_t>(variant) - 1];
    if (twins[0] != VK_NULL_HANDLE) return {};
    const std::array<detail::PipelineDesc, 8> lit = detail::lit_descs(variant, constant_fragments_);
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
    if (variant == LitVariant::Plain) return pipeline;
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
