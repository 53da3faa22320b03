// Internal to aloha_gpu: how the lit pipelines are made (lit_pipeline.cpp) and which shaders each variant's mesh
// pipelines take (lit_pipeline_variants.cpp).
#pragma once

#include "engine/core/result.hpp"
#include "engine/gpu/lit_pipeline.hpp"

#include <vulkan/vulkan.h>

#include <array>
#include <cstdint>
#include <span>

namespace aloha::gpu::detail {

/// One graphics pipeline of the lit family: its two shaders' SPIR-V and fixed state.
struct PipelineDesc {
    std::span<const uint32_t> vert;
    std::span<const uint32_t> frag;
    VkPrimitiveTopology topology;
    VkCompareOp depth_compare;
    VkCullModeFlags cull;
};

/// Makes a pipeline of `d` for `layout` and render passes compatible with `pass` (dynamic viewport and scissor,
/// depth test and write, one colour attachment written whole).
[[nodiscard]] Result<VkPipeline> make_pipeline(VkDevice device, VkPipelineLayout layout, VkRenderPass pass, const PipelineDesc& d);

/// The mesh pipelines' descriptions, in the order mesh, culled, vertex-lit, vertex-lit culled, dithered (mesh,
/// culled, vertex-lit, vertex-lit culled), built from the shaders of `variant` (MATERIAL_PBR: the per-pixel and
/// vertex-lit light; MATERIAL_MAPS: also the maps, vertex colours and their interpolated colour). With constant
/// fragments (profiling) the mesh and vertex-lit ones use lit_constant.frag, which reads the per-pixel vertex shader's
/// flat colour, and the dithered ones the per-pixel shaders (the fading few keep their look); `variant` is then
/// ignored.
[[nodiscard]] std::array<PipelineDesc, 8> lit_descs(LitVariant variant, bool constant_fragments);

}  // namespace aloha::gpu::detail
