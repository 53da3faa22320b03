// CrowdRenderer per-frame work: grouping meshes by topology, copying into the mapped buffers, and
// recording the command buffer (one indexed instanced draw per topology and material, one for proxies, one for
// lines).
#include "engine/gpu/context.hpp"
#include "engine/gpu/vk_error.hpp"
#include "systems/render/crowd_renderer.hpp"
#include "systems/render/impostor_order.hpp"
#include "systems/render/proxy_mesh.hpp"

#include <glm/gtc/matrix_access.hpp>

#include <algorithm>
#include <cstring>

namespace aloha {
uint64_t CrowdRenderer::upload(const FrameInput& frame, Slot& slot) {
    const size_t nt = topologies_.size();
    // Counting sort of meshes by topology (stable, so the result depends only on the input order).
    group_count_.assign(nt, 0);
    for (const DeformableMesh& m : frame.meshes) ++group_count_[m.topology];
    group_start_.assign(nt, 0);
    group_vertex_base_.assign(nt, 0);
    uint32_t inst = 0;
    uint32_t vert = 0;
    for (size_t t = 0; t < nt; ++t) {
        group_start_[t] = inst;
        group_vertex_base_[t] = vert;
        inst += group_count_[t];
        vert += group_count_[t] * topologies_[t].vertex_count;
    }
    group_cursor_.assign(group_start_.begin(), group_start_.end());
    order_.resize(frame.meshes.size());
    for (uint32_t i = 0; i < frame.meshes.size(); ++i) order_[group_cursor_[frame.meshes[i].topology]++] = i;
    // Within a topology, nearest first: lavapipe draws the instances in order and skips the shading of 4x4
    // blocks whose depth test fails, so near characters hide the far ones' fragments (ties by input order).
    depth_.resize(frame.meshes.size());
    const glm::vec4 forward = glm::row(frame.camera.view, 2);  // view-space z of a world point (negative ahead)
    for (uint32_t i = 0; i < frame.meshes.size(); ++i) depth_[i] = -glm::dot(forward, frame.meshes[i].model[3]);
    for (size_t t = 0; t < nt; ++t)
        sort_nearest_first(std::span(order_).subspan(group_start_[t], group_count_[t]), depth_);

    std::byte* pos = slot.positions.mapped();
    std::byte* nrm = slot.normals.mapped();
    auto* instances = reinterpret_cast<gpu::LitInstance*>(slot.instances.mapped());
    uint64_t offset = 0;
    // Meshes in topology order: vertices of group t start at group_vertex_base_[t] and follow one another.
    for (uint32_t k = 0; k < order_.size(); ++k) {
        const DeformableMesh& m = frame.meshes[order_[k]];
        const size_t bytes = m.positions.size_bytes();
        std::memcpy(pos + offset, m.positions.data(), bytes);
        std::memcpy(nrm + offset, m.normals.data(), bytes);
        offset += bytes;
        instances[k].model = m.model;
        instances[k].colour = m.colour;
    }
    // Proxies have the LitInstance layout: one copy.
    if (!frame.proxies.empty())
        std::memcpy(static_cast<void*>(instances + frame.meshes.size()), frame.proxies.data(),
                    frame.proxies.size_bytes());
    // Impostors nearest first within each atlas's run (systems/render/impostor_order.hpp).
    if (!frame.impostors.empty())
        copy_impostors_nearest_first(frame.impostors, frame.camera.view,
                                     reinterpret_cast<ImpostorInstance*>(slot.instances.mapped()) + impostor_base(frame), impostor_order_,
                                     impostor_depth_);
    gpu::LitLighting lighting;
    lighting.sky = glm::vec4(frame.sky_colour, 1.0f);
    lighting.ground = glm::vec4(frame.ground_colour, 1.0f);
    lighting.key = glm::vec4(frame.key_colour, 1.0f);
    slot.lighting.write(std::as_bytes(std::span(&lighting, 1)));
    auto* lv = reinterpret_cast<gpu::LineVertex*>(slot.lines.mapped());
    for (size_t i = 0; i < frame.lines.size(); ++i) {
        const LineSegment& l = frame.lines[i];
        lv[2 * i] = {glm::vec4(l.a, 1.0f), l.colour};
        lv[2 * i + 1] = {glm::vec4(l.b, 1.0f), l.colour};
    }
    return 2 * offset + (frame.meshes.size() + frame.proxies.size()) * sizeof(gpu::LitInstance) +
           frame.impostors.size_bytes() + frame.lines.size() * 2 * sizeof(gpu::LineVertex);
}

void CrowdRenderer::end_pass(VkCommandBuffer cmd, Slot& slot, PassRecord pass) {
    if (!options_.pass_timestamps || slot.queries == VK_NULL_HANDLE) return;
    // Bottom of pipe: on lavapipe this flushes the binned scene, so the pass's rasterisation is inside it.
    slot.passes.push_back(pass);
    vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, slot.queries, static_cast<uint32_t>(slot.passes.size()));
}

Status CrowdRenderer::record(const FrameInput& frame, const gpu::TargetView& target, Slot& slot) {
    VkCommandBuffer cmd = slot.cmd;
    ALOHA_VK_RETURN(vkResetCommandBuffer(cmd, 0));
    VkCommandBufferBeginInfo bi{};
    bi.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
    bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    ALOHA_VK_RETURN(vkBeginCommandBuffer(cmd, &bi));
    slot.passes.clear();
    if (options_.pass_timestamps) {
        // One query to start, one after every pass: at most every label, then the frame's end.
        if (Status q = ensure_queries(slot, static_cast<uint32_t>(pass_names_.size()) + 2); !q) return q;
    }
    if (slot.queries != VK_NULL_HANDLE) {
        vkCmdResetQueryPool(cmd, slot.queries, 0, slot.query_capacity);
        vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, slot.queries, 0);
    }
    VkClearValue clears[2]{};
    clears[0].color = {{frame.clear_colour.r, frame.clear_colour.g, frame.clear_colour.b, frame.clear_colour.a}};
    clears[1].depthStencil = {1.0f, 0};
    VkRenderPassBeginInfo rbi{};
    rbi.sType = VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO;
    rbi.renderPass = target.render_pass;
    rbi.framebuffer = target.framebuffer;
    rbi.renderArea = {{0, 0}, target.extent};
    rbi.clearValueCount = 2;
    rbi.pClearValues = clears;
    vkCmdBeginRenderPass(cmd, &rbi, VK_SUBPASS_CONTENTS_INLINE);
    const VkViewport vp{0.0f, 0.0f, float(target.extent.width), float(target.extent.height), 0.0f, 1.0f};
    const VkRect2D sc{{0, 0}, target.extent};
    vkCmdSetViewport(cmd, 0, 1, &vp);
    vkCmdSetScissor(cmd, 0, 1, &sc);

    gpu::LitPush push;
    push.view_proj = gpu::vulkan_clip_from_gl() * frame.camera.proj * frame.camera.view;
    push.light = glm::vec4(glm::normalize(frame.light_direction), frame.ambient);
    push.camera = glm::vec4(glm::vec3(glm::inverse(frame.camera.view)[3]), 1.0f);
    const VkShaderStageFlags stages = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
    uint32_t draws = 0;
    const bool any_mesh = !frame.meshes.empty() || !frame.proxies.empty() || !frame.impostors.empty();
    const uint32_t normals = frame.write_normals ? uint32_t{gpu::kLitNormals} : 0u;
    if (any_mesh) {
        const VkDescriptorSet sets[2] = {slot.set, plain_set_};
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipes_.layout(), 0, 2, sets, 0, nullptr);
    }
    VkPipeline bound = VK_NULL_HANDLE;
    PassRecord pass;
    bool in_pass = false;
    for (const uint32_t t : draw_order_) {
        if (group_count_[t] == 0) continue;
        if (in_pass && pass.name != topologies_[t].pass) {
            end_pass(cmd, slot, pass);
            pass = {};
        }
        in_pass = true;
        pass.name = topologies_[t].pass;
        pass.instances += group_count_[t];
        pass.triangles += uint64_t(topologies_[t].index_count / 3) * group_count_[t];
        const uint32_t draws_before = draws;
        const Topology& topo = topologies_[t];
        const VkPipeline want = topo.vertex_lighting ? (topo.cull_back_faces ? pipes_.vertex_lit_culled() : pipes_.vertex_lit())
                                                     : (topo.cull_back_faces ? pipes_.mesh_culled() : pipes_.mesh());
        if (want != bound) {
            vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, want);
            bound = want;
        }
        vkCmdBindIndexBuffer(cmd, topo.indices.handle(), 0, VK_INDEX_TYPE_UINT32);
        if (!frame.materials || topo.ranges.empty()) {
            push.offsets = glm::uvec4(group_vertex_base_[t], topo.vertex_count, group_start_[t], gpu::kLitMesh | normals);
            push.base_colour = glm::vec4(1.0f);
            vkCmdPushConstants(cmd, pipes_.layout(), stages, 0, sizeof(push), &push);
            vkCmdDrawIndexed(cmd, topo.index_count, group_count_[t], 0, 0, 0);
            ++draws;
            pass.draws += draws - draws_before;
            continue;
        }
        for (const Range& r : topo.ranges) {  // one draw per material, every instance of the topology
            const Material& m = materials_[r.material];
            vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipes_.layout(), 1, 1, &r.set, 0, nullptr);
            const uint32_t textured = m.texture >= 0 && topo.uvs.handle() != VK_NULL_HANDLE ? uint32_t{gpu::kLitTexturedMesh} : 0u;
            push.offsets = glm::uvec4(group_vertex_base_[t], topo.vertex_count, group_start_[t], textured | normals);
            push.base_colour = m.colour;
            vkCmdPushConstants(cmd, pipes_.layout(), stages, 0, sizeof(push), &push);
            vkCmdDrawIndexed(cmd, r.index_count, group_count_[t], r.first_index, 0, 0);
            ++draws;
        }
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipes_.layout(), 1, 1, &plain_set_, 0, nullptr);
        pass.draws += draws - draws_before;
    }
    if (in_pass) end_pass(cmd, slot, pass);
    if (!frame.proxies.empty()) {
        // Box mode: one indexed, non-instanced draw of all proxies (see shaders/lit_mesh.vert), back faces
        // culled (boxes are closed and wound counter-clockwise from outside).
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipes_.mesh_culled());
        push.offsets = glm::uvec4(0, 0, static_cast<uint32_t>(frame.meshes.size()), gpu::kLitBoxes);
        push.base_colour = glm::vec4(1.0f);
        vkCmdPushConstants(cmd, pipes_.layout(), stages, 0, sizeof(push), &push);
        vkCmdBindIndexBuffer(cmd, slot.proxy_indices.handle(), 0, VK_INDEX_TYPE_UINT32);
        vkCmdDrawIndexed(cmd, kBoxIndexCount * static_cast<uint32_t>(frame.proxies.size()), 1, 0, 0, 0);
        ++draws;
        end_pass(cmd, slot, {pass_id("proxies"), 1, frame.proxies.size(), uint64_t(kBoxIndexCount / 3) * frame.proxies.size()});
    }
    draws += record_impostors(frame, cmd, slot, push, float(target.extent.height));
    if (!frame.lines.empty()) {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipes_.lines());
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipes_.layout(), 0, 1, &slot.set, 0, nullptr);
        push.offsets = glm::uvec4(0);
        vkCmdPushConstants(cmd, pipes_.layout(), stages, 0, sizeof(push), &push);
        vkCmdDraw(cmd, static_cast<uint32_t>(frame.lines.size() * 2), 1, 0, 0);
        ++draws;
        end_pass(cmd, slot, {pass_id("lines"), 1, frame.lines.size(), 0});
    }
    vkCmdEndRenderPass(cmd);
    if (options_.pass_timestamps)
        end_pass(cmd, slot, {pass_id("resolve"), 0, 0, 0});
    else if (slot.queries != VK_NULL_HANDLE)
        vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, slot.queries, 1);
    ALOHA_VK_RETURN(vkEndCommandBuffer(cmd));
    last_draw_count_ = draws;
    return {};
}

}  // namespace aloha
