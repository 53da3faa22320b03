// CrowdRenderer far layer: which impostors go to the half-resolution layer, the layer's targets, its pass and
// the composite that blends it in behind everything else (systems/render/far_layer.hpp).
#include "engine/gpu/context.hpp"
#include "engine/gpu/vk_error.hpp"
#include "systems/render/crowd_renderer.hpp"

#include <glm/gtc/matrix_access.hpp>

#include <algorithm>

namespace aloha {

void CrowdRenderer::plan_far_layer_for(const FrameInput& frame, VkExtent2D extent, const ImpostorInstance* drawn) {
    FarLayerInput in;
    in.records = std::span(drawn, frame.impostors.size());
    in.order = std::span(impostor_order_).first(frame.impostors.size());
    in.depth = impostor_depth_;
    in.layouts = atlas_layouts_;
    in.clip_from_world = gpu::vulkan_clip_from_gl() * frame.camera.proj * frame.camera.view;
    const bool perspective = frame.camera.proj[2][3] != 0.0f;
    in.focal_px = perspective ? 0.5f * float(extent.height) * std::abs(frame.camera.proj[1][1]) : 0.0f;
    in.below_px = frame.impostors.empty() ? 0.0f : options_.far_layer_below_px;
    in.viewport_width = float(std::max(extent.width, 1u));
    in.viewport_height = float(std::max(extent.height, 1u));
    if (in.below_px > 0.0f) {
        // Everything drawn at full resolution must lie nearer than the far layer: meshes and proxies by their
        // origin's depth plus their reach (the largest atlas's extent, at the model's own scale).
        float extent_model = 0.0f;
        for (const ImpostorAtlasLayout& l : atlas_layouts_) extent_model = std::max(extent_model, l.width + l.height);
        const glm::vec4 forward = glm::row(frame.camera.view, 2);
        float beyond = 0.0f;
        // Only what can be on screen counts (characters held at their level for a while after leaving the view).
        auto reach_beyond = [&](const glm::mat4& model, float reach) {
            if (!sphere_outside_view(in.clip_from_world, glm::vec3(model[3]), reach))
                beyond = std::max(beyond, -glm::dot(forward, model[3]) + reach);
        };
        for (const DeformableMesh& m : frame.meshes) {
            const glm::mat4& model = m.model;
            const float scale = std::max({glm::length(glm::vec3(model[0])), glm::length(glm::vec3(model[1])), glm::length(glm::vec3(model[2]))});
            reach_beyond(model, scale * extent_model);
        }
        // A proxy box is a part of a character at scale about 1 (its matrix's scale is the box's size).
        for (const ProxyInstance& p : frame.proxies) reach_beyond(p.model, extent_model);
        in.beyond_depth = beyond;
    }
    plan_far_layer(in, far_plan_);
}

Status CrowdRenderer::ensure_far_layer(Slot& slot, VkExtent2D extent) {
    // Half the target's size, rounded up; drawn with a viewport of exactly half (record_far_layer), so layer texel
    // (x, y) covers target pixels (2x, 2y) to (2x + 1, 2y + 1).
    const VkExtent2D want{(extent.width + 1) / 2, (extent.height + 1) / 2};
    const VkExtent2D have = slot.far_layer.extent();
    if (have.width == want.width && have.height == want.height) return {};
    // The slot is retired (render() waited for its fence), so nothing in flight reads its old layer.
    Result<gpu::LayerTarget> layer = gpu::LayerTarget::create(ctx_, want.width, want.height, options_.colour_format);
    if (!layer) return layer.error();
    slot.far_layer = std::move(layer).value();
    if (slot.far_set == VK_NULL_HANDLE) {
        Result<VkDescriptorSet> set = pipes_.material_set(no_uvs_, slot.far_layer.colour_view(), slot.far_layer.sampler());
        if (!set) return set.error();
        slot.far_set = set.value();
        return {};
    }
    const VkDescriptorImageInfo image{slot.far_layer.sampler(), slot.far_layer.colour_view(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    VkWriteDescriptorSet w{};
    w.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
    w.dstSet = slot.far_set;
    w.dstBinding = 1;
    w.descriptorCount = 1;
    w.descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    w.pImageInfo = &image;
    vkUpdateDescriptorSets(ctx_.device(), 1, &w, 0, nullptr);
    return {};
}

uint32_t CrowdRenderer::record_far_layer(VkCommandBuffer cmd, Slot& slot, gpu::LitPush& push, VkExtent2D extent) {
    const gpu::TargetView view = slot.far_layer.view();
    gpu::begin_render_pass(cmd, view, VkClearColorValue{});  // transparent black: where the layer is empty
    const float height = 0.5f * float(extent.height);
    const VkViewport vp{0.0f, 0.0f, 0.5f * float(extent.width), height, 0.0f, 1.0f};
    const VkRect2D sc{{0, 0}, view.extent};
    vkCmdSetViewport(cmd, 0, 1, &vp);
    vkCmdSetScissor(cmd, 0, 1, &sc);
    const VkDescriptorSet sets[2] = {slot.set, plain_set_};
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipes_.layout(), 0, 2, sets, 0, nullptr);
    const uint32_t draws = record_impostors(cmd, slot, push, height, /*far=*/true);
    vkCmdEndRenderPass(cmd);
    return draws;
}

uint32_t CrowdRenderer::record_composite(VkCommandBuffer cmd, Slot& slot, gpu::LitPush& push) {
    const VkExtent2D layer = slot.far_layer.extent();
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipes_.composite());
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipes_.layout(), 1, 1, &slot.far_set, 0, nullptr);
    push.camera = glm::vec4(0.5f / float(layer.width), 0.5f / float(layer.height), 0.0f, 0.0f);
    push.base_colour = far_plan_.ndc_rect;
    vkCmdPushConstants(cmd, pipes_.layout(), VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(push), &push);
    vkCmdDraw(cmd, 6, 1, 0, 0);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipes_.layout(), 1, 1, &plain_set_, 0, nullptr);
    end_pass(cmd, slot, {pass_id("composite"), 1, 1, 2});
    return 1;
}

}  // namespace aloha
