// CrowdRenderer warm-up: every registered pipeline, texture and target state drawn once at load, so that a software
// rasteriser compiles its shader variants then rather than in the frame that first needs them.
#include "engine/gpu/context.hpp"
#include "systems/render/crowd_renderer.hpp"

#include <algorithm>
#include <cstring>

namespace aloha {

Status CrowdRenderer::warm_up() {
    Slot& slot = slots_[frame_index_ % slots_.size()];
    if (Status s = retire(slot); !s.ok()) return s;
    if (slot.set_dirty) {
        pipes_.write_set(slot.set, slot.positions, slot.normals, slot.instances, slot.lines, slot.lighting);
        slot.set_dirty = false;
    }
    if (warm_target_.extent().width == 0) {
        Result<gpu::LayerTarget> made = gpu::LayerTarget::create(ctx_, 8, 8, options_.colour_format);
        if (!made) return made.error();
        warm_target_ = std::move(made).value();
    }
    // Record 0 of the instance buffer zeroed: a mesh instance with a zero matrix (every vertex at the origin: nothing
    // drawn), an impostor of phase 0 facing +Z (its cell index in range).
    std::memset(slot.instances.mapped(), 0, std::max(sizeof(gpu::LitInstance), sizeof(ImpostorInstance)));
    const uint64_t vertex_capacity = slot.positions.size() / sizeof(glm::vec3);
    const VkShaderStageFlags stages = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
    return ctx_.submit_once([&](VkCommandBuffer cmd) {
        const float height = begin_layer_pass(cmd, slot, warm_target_, 1, warm_target_.extent());
        gpu::LitPush push;
        // Each topology's first triangle of each material (or untextured), whole and dithered: the pipelines its
        // meshes are drawn with, with the textures they bind.
        for (const Topology& topo : topologies_) {
            if (topo.vertex_count > vertex_capacity) continue;  // larger than the first frame's buffers: warmed when drawn
            vkCmdBindIndexBuffer(cmd, topo.indices.handle(), 0, VK_INDEX_TYPE_UINT32);
            for (const VkPipeline pipeline : {whole_pipeline(topo), pipes_.dithered(topo.vertex_lighting, topo.cull_back_faces)}) {
                const uint32_t dither = pipeline == whole_pipeline(topo) ? 0u : gpu::lit_dither_bits(0.5f);
                auto draw = [&](VkDescriptorSet set, uint32_t mode, uint32_t first_index) {
                    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipes_.for_mode(pipeline, mode));  // the material variant's twin
                    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipes_.layout(), 1, 1, &set, 0, nullptr);
                    push.offsets = glm::uvec4(0u, topo.vertex_count, 0u, mode | dither);
                    vkCmdPushConstants(cmd, pipes_.layout(), stages, 0, sizeof(push), &push);
                    vkCmdDrawIndexed(cmd, 3, 1, first_index, 0, 0);
                };
                draw(plain_set_, gpu::kLitMesh, 0);
                for (const Range& r : topo.ranges) {
                    draw(r.set, r.mode, r.first_index);
                }
            }
        }
        // Each impostor atlas, with both impostor pipelines (the nearest view; blended views).
        for (const VkPipeline pipeline : {pipes_.impostor(), pipes_.impostor_blend()}) {
            if (atlases_.empty()) break;
            vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline);
            const uint32_t upper = pipeline == pipes_.impostor() ? impostor_alpha_test_bits(0.5f) : 0u;
            for (size_t a = 0; a < atlases_.size(); ++a) {
                const ImpostorAtlasLayout& layout = atlas_layouts_[a];
                vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipes_.layout(), 1, 1, &atlases_[a].set, 0, nullptr);
                push.offsets = glm::uvec4(layout.directions, layout.rows, 0u, impostor_mode_bits(layout.elevations, upper));
                push.base_colour = glm::vec4(layout.width, layout.bottom, layout.height, height);
                vkCmdPushConstants(cmd, pipes_.layout(), stages, 0, sizeof(push), &push);
                vkCmdDraw(cmd, 6, 1, 0, 0);
            }
        }
        vkCmdEndRenderPass(cmd);
    });
}

}  // namespace aloha
