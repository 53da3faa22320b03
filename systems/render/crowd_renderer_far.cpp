// CrowdRenderer far and distant layers: which impostors go to the half- and quarter-resolution layers, the layers'
// targets, their passes and the composite that writes them into the frame with their depth
// (systems/render/far_layer.hpp).
#include "engine/gpu/context.hpp"
#include "engine/gpu/vk_error.hpp"
#include "systems/render/crowd_renderer.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace aloha {

namespace {

// The mesh's bounding sphere (world: its model-space box through the model matrix, radius scaled by the largest
// axis scale) and its world height (the vertical extent of that box's corners).
FarMeshBound far_mesh_bound(const DeformableMesh& m) {
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    for (const glm::vec3& p : m.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
    const float scale = std::max({glm::length(glm::vec3(m.model[0])), glm::length(glm::vec3(m.model[1])), glm::length(glm::vec3(m.model[2]))});
    float top = -std::numeric_limits<float>::max(), bottom = std::numeric_limits<float>::max();
    for (int c = 0; c < 8; ++c) {
        const glm::vec3 corner((c & 1) ? hi.x : lo.x, (c & 2) ? hi.y : lo.y, (c & 4) ? hi.z : lo.z);
        const float y = (m.model * glm::vec4(corner, 1.0f)).y;
        top = std::max(top, y), bottom = std::min(bottom, y);
    }
    return {glm::vec4(glm::vec3(m.model * glm::vec4(0.5f * (lo + hi), 1.0f)), 0.5f * glm::length(hi - lo) * scale), top - bottom};
}

}  // namespace

void CrowdRenderer::plan_far_layer_for(const FrameInput& frame, VkExtent2D extent) {
    FarLayerInput in;
    in.records = frame.impostors;
    in.order = std::span(impostor_order_).first(frame.impostors.size());
    in.depth = impostor_depth_;
    in.layouts = atlas_layouts_;
    in.clip_from_world = gpu::vulkan_clip_from_gl() * frame.camera.proj * frame.camera.view;
    const bool perspective = frame.camera.proj[2][3] != 0.0f;
    in.focal_px = perspective ? 0.5f * float(extent.height) * std::abs(frame.camera.proj[1][1]) : 0.0f;
    in.below_px = far_layer_limit(far_layer_below_px_, float(extent.height));
    in.distant_below_px = far_layer_limit(options_.distant_layer_below_px, float(extent.height));
    in.viewport_width = float(std::max(extent.width, 1u));
    in.viewport_height = float(std::max(extent.height, 1u));
    // Whole (not fading) mesh groups, one per topology; a fading mesh's dither pairs pixel for pixel with its
    // partner's at full resolution. With meshes in the layer, each whole group's meshes are measured from their
    // vertices (model space, placed by the model matrix): its height says whether it is under the limit, whatever
    // its size, so every one is measured.
    far_mesh_groups_.resize(topologies_.size());
    for (size_t t = 0; t < topologies_.size(); ++t) far_mesh_groups_[t] = {group_start_[2 * t], group_count_[2 * t]};
    const float meshes_below_px = far_layer_limit(far_layer_meshes_below_px_, float(extent.height));
    far_mesh_bounds_.resize(frame.meshes.size());
    if (meshes_below_px > 0.0f && in.focal_px > 0.0f)
        for (const FarMeshGroup& g : far_mesh_groups_)
            for (uint32_t k = g.first; k < g.first + g.count; ++k) far_mesh_bounds_[order_[k]] = far_mesh_bound(frame.meshes[order_[k]]);
    in.mesh_order = order_;
    in.mesh_groups = far_mesh_groups_;
    in.mesh_bounds = far_mesh_bounds_;
    in.mesh_depth = depth_;
    in.meshes_below_px = meshes_below_px;
    plan_far_layer(in, far_plan_);
}

Status CrowdRenderer::ensure_layer(gpu::LayerTarget& layer, VkDescriptorSet& set, VkExtent2D extent, uint32_t divisor) {
    // 1 / divisor of the target's size, rounded up; drawn with a viewport of exactly that fraction (record_far_layer,
    // record_distant_layer), so layer texel (x, y) covers target pixels (d x, d y) to (d x + d - 1, d y + d - 1).
    const VkExtent2D want{(extent.width + divisor - 1) / divisor, (extent.height + divisor - 1) / divisor};
    const VkExtent2D have = layer.extent();
    if (have.width == want.width && have.height == want.height) return {};
    // The slot is retired (render() waited for its fence), so nothing in flight reads its old layer.
    Result<gpu::LayerTarget> made = gpu::LayerTarget::create(ctx_, want.width, want.height, options_.colour_format);
    if (!made) return made.error();
    layer = std::move(made).value();
    Result<VkDescriptorSet> written = pipes_.composite_set(layer.colour_view(), layer.sampler(), layer.depth_view(), layer.depth_sampler(), set);
    if (!written) return written.error();
    set = written.value();
    return {};
}

float CrowdRenderer::begin_layer_pass(VkCommandBuffer cmd, const Slot& slot, const gpu::LayerTarget& layer, uint32_t divisor,
                                      VkExtent2D extent) {
    const gpu::TargetView view = layer.view();
    gpu::begin_render_pass(cmd, view, VkClearColorValue{});  // transparent black: where the layer is empty
    const float height = float(extent.height) / float(divisor);
    const VkViewport vp{0.0f, 0.0f, float(extent.width) / float(divisor), height, 0.0f, 1.0f};
    const VkRect2D sc{{0, 0}, view.extent};
    vkCmdSetViewport(cmd, 0, 1, &vp);
    vkCmdSetScissor(cmd, 0, 1, &sc);
    const VkDescriptorSet sets[2] = {slot.set, plain_set_};
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipes_.layout(), 0, 2, sets, 0, nullptr);
    return height;
}

uint32_t CrowdRenderer::record_far_layer(const FrameInput& frame, VkCommandBuffer cmd, Slot& slot, gpu::LitPush& push,
                                        VkExtent2D extent) {
    const float height = begin_layer_pass(cmd, slot, slot.far_layer, kFarLayerDivisor, extent);
    // The far meshes (each whole group's tail, nearest first), then the far impostors behind them.
    uint32_t draws = 0;
    VkPipeline bound = VK_NULL_HANDLE;
    PassRecord meshes{pass_id("far meshes"), 0, 0, 0};
    for (const uint32_t t : draw_order_) {
        const FarMeshGroup& g = far_mesh_groups_[t];
        const uint32_t split = far_plan_.mesh_splits[t], end = g.first + g.count;
        if (split == end) continue;
        vkCmdBindIndexBuffer(cmd, topologies_[t].indices.handle(), 0, VK_INDEX_TYPE_UINT32);
        meshes.draws += draw_mesh_group(cmd, frame, 2 * t, split - g.first, end - split, whole_pipeline(topologies_[t]), 0u, push, bound);
        meshes.instances += end - split;
        meshes.triangles += uint64_t(topologies_[t].index_count / 3) * (end - split);
    }
    if (meshes.instances > 0) end_pass(cmd, slot, meshes);
    draws += meshes.draws + record_impostors(cmd, slot, push, height, ImpostorPart::Far);
    vkCmdEndRenderPass(cmd);
    return draws;
}

uint32_t CrowdRenderer::record_distant_layer(VkCommandBuffer cmd, Slot& slot, gpu::LitPush& push, VkExtent2D extent) {
    const float height = begin_layer_pass(cmd, slot, slot.distant_layer, kDistantLayerDivisor, extent);
    const uint32_t draws = record_impostors(cmd, slot, push, height, ImpostorPart::Distant);
    vkCmdEndRenderPass(cmd);
    return draws;
}

uint32_t CrowdRenderer::record_composite(VkCommandBuffer cmd, Slot& slot, gpu::LitPush& push) {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipes_.composite());
    uint32_t draws = 0;
    // Each layer over its rectangle; the shader maps a target pixel to layer coordinates by 1 / (divisor * size).
    auto composite = [&](const gpu::LayerTarget& layer, VkDescriptorSet set, uint32_t divisor, const glm::vec4& rect) {
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipes_.composite_layout(), 0, 1, &set, 0, nullptr);
        const glm::vec2 texels = float(divisor) * glm::vec2(float(layer.extent().width), float(layer.extent().height));
        push.camera = glm::vec4(1.0f / texels, 0.0f, 0.0f);
        push.base_colour = rect;
        vkCmdPushConstants(cmd, pipes_.composite_layout(), VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(push), &push);
        vkCmdDraw(cmd, 6, 1, 0, 0);
        ++draws;
    };
    if (far_plan_.far_count > 0) composite(slot.far_layer, slot.far_set, kFarLayerDivisor, far_plan_.ndc_rect);
    if (far_plan_.distant_count > 0) composite(slot.distant_layer, slot.distant_set, kDistantLayerDivisor, far_plan_.distant_ndc_rect);
    end_pass(cmd, slot, {pass_id("composite"), draws, draws, 2ull * draws});
    return draws;
}

}  // namespace aloha
