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
uint64_t CrowdRenderer::upload(const FrameInput& frame, Slot& slot, VkExtent2D extent) {
    const size_t nt = topologies_.size(), ng = 2 * nt;
    // Counting sort of meshes by group 2 * topology + dithered (stable, so the result depends only on the input
    // order): a topology's fading meshes follow its others and are drawn with the dithered pipelines.
    const auto group_of = [](const DeformableMesh& m) { return 2 * size_t{m.topology} + (m.dither < 1.0f ? 1 : 0); };
    group_count_.assign(ng, 0);
    for (const DeformableMesh& m : frame.meshes) ++group_count_[group_of(m)];
    group_start_.assign(ng, 0);
    group_vertex_base_.assign(ng, 0);
    uint32_t inst = 0;
    uint32_t vert = 0;
    for (size_t g = 0; g < ng; ++g) {
        group_start_[g] = inst;
        group_vertex_base_[g] = vert;
        inst += group_count_[g];
        vert += group_count_[g] * topologies_[g / 2].vertex_count;
    }
    group_cursor_.assign(group_start_.begin(), group_start_.end());
    order_.resize(frame.meshes.size());
    for (uint32_t i = 0; i < frame.meshes.size(); ++i) order_[group_cursor_[group_of(frame.meshes[i])]++] = i;
    // Within a group, nearest first: lavapipe draws the instances in order and skips the shading of 4x4
    // blocks whose depth test fails, so near characters hide the far ones' fragments (ties by input order).
    depth_.resize(frame.meshes.size());
    const glm::vec4 forward = glm::row(frame.camera.view, 2);  // view-space z of a world point (negative ahead)
    for (uint32_t i = 0; i < frame.meshes.size(); ++i) depth_[i] = -glm::dot(forward, frame.meshes[i].model[3]);
    for (size_t g = 0; g < ng; ++g)
        sort_nearest_first(std::span(order_).subspan(group_start_[g], group_count_[g]), depth_);
    // Impostors nearest first within each atlas's run (systems/render/impostor_order.hpp); the far layer
    // (systems/render/far_layer.hpp) then moves each run's and each whole mesh group's far part behind its others,
    // before anything is copied (a mesh's vertices follow its place in the order).
    impostor_base_ = impostor_base(frame);
    sort_impostors_nearest_first(frame.impostors, frame.camera.view, impostor_order_, impostor_depth_);
    plan_far_layer_for(frame, extent);

    std::byte* pos = slot.positions.mapped();
    std::byte* nrm = slot.normals.mapped();
    auto* instances = reinterpret_cast<gpu::LitInstance*>(slot.instances.mapped());
    uint64_t offset = 0;
    // Meshes in group order: vertices of group g start at group_vertex_base_[g] and follow one another.
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
    auto* impostors = reinterpret_cast<ImpostorInstance*>(slot.instances.mapped()) + impostor_base_;
    for (size_t k = 0; k < frame.impostors.size(); ++k) impostors[k] = frame.impostors[impostor_order_[k]];
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

uint32_t CrowdRenderer::record_proxies(const FrameInput& frame, VkCommandBuffer cmd, Slot& slot, gpu::LitPush& push) {
    if (frame.proxies.empty()) return 0;
    // Box mode: indexed, non-instanced draws of unit boxes (see shaders/lit_mesh.vert), back faces culled (boxes
    // are closed and wound counter-clockwise from outside): one draw per stretch between the fade runs, then
    // one dithered draw per run.
    const VkShaderStageFlags stages = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
    const auto meshes = static_cast<uint32_t>(frame.meshes.size()), n = static_cast<uint32_t>(frame.proxies.size());
    vkCmdBindIndexBuffer(cmd, slot.proxy_indices.handle(), 0, VK_INDEX_TYPE_UINT32);
    push.base_colour = glm::vec4(1.0f);
    uint32_t draws = 0;
    auto boxes = [&](uint32_t first, uint32_t count, uint32_t dither) {
        push.offsets = glm::uvec4(0, 0, meshes + first, gpu::kLitBoxes | dither);
        vkCmdPushConstants(cmd, pipes_.layout(), stages, 0, sizeof(push), &push);
        vkCmdDrawIndexed(cmd, kBoxIndexCount * count, 1, 0, 0, 0);
        ++draws;
    };
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipes_.mesh_culled());
    uint32_t cursor = 0;
    for (const ProxyFade& f : frame.proxy_fades) {
        if (f.first > cursor) boxes(cursor, f.first - cursor, 0u);
        cursor = f.first + f.count;
    }
    if (cursor < n) boxes(cursor, n - cursor, 0u);
    if (!frame.proxy_fades.empty()) {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipes_.dithered(false, true));
        for (const ProxyFade& f : frame.proxy_fades)
            if (f.count > 0) boxes(f.first, f.count, gpu::lit_dither_bits(f.share));
    }
    end_pass(cmd, slot, {pass_id("proxies"), draws, frame.proxies.size(), uint64_t(kBoxIndexCount / 3) * frame.proxies.size()});
    return draws;
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
    gpu::LitPush push;
    push.view_proj = gpu::vulkan_clip_from_gl() * frame.camera.proj * frame.camera.view;
    push.light = glm::vec4(glm::normalize(frame.light_direction), frame.ambient);
    // The way to the eye: towards its position, or along its +Z axis everywhere (RenderCamera::eye_at_infinity).
    const glm::mat4 eye = glm::inverse(frame.camera.view);
    push.camera = frame.camera.eye_at_infinity ? glm::vec4(glm::normalize(glm::vec3(eye[2])), 0.0f) : glm::vec4(glm::vec3(eye[3]), 1.0f);
    uint32_t draws = 0;
    // The far layer first, in its own render pass: the frame's pass composites it (record_composite).
    if (far_plan_.far_count > 0) draws += record_far_layer(frame, cmd, slot, push, target.extent);
    if (far_plan_.distant_count > 0) draws += record_distant_layer(cmd, slot, push, target.extent);
    gpu::begin_render_pass(cmd, target, VkClearColorValue{{frame.clear_colour.r, frame.clear_colour.g, frame.clear_colour.b, frame.clear_colour.a}});
    const VkViewport vp{0.0f, 0.0f, float(target.extent.width), float(target.extent.height), 0.0f, 1.0f};
    const VkRect2D sc{{0, 0}, target.extent};
    vkCmdSetViewport(cmd, 0, 1, &vp);
    vkCmdSetScissor(cmd, 0, 1, &sc);

    const VkShaderStageFlags stages = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
    const bool any_mesh = !frame.meshes.empty() || !frame.proxies.empty() || !frame.impostors.empty();
    if (any_mesh) {
        const VkDescriptorSet sets[2] = {slot.set, plain_set_};
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipes_.layout(), 0, 2, sets, 0, nullptr);
    }
    VkPipeline bound = VK_NULL_HANDLE;
    PassRecord pass;
    bool in_pass = false;
    auto draw_group = [&](uint32_t g, uint32_t first, uint32_t count, VkPipeline pipeline, uint32_t dither) {
        draws += draw_mesh_group(cmd, frame, g, first, count, pipeline, dither, push, bound);
    };
    for (const uint32_t t : draw_order_) {
        const uint32_t whole = 2 * t, faded = 2 * t + 1;
        // The whole group's near part here; its far part went to the far layer (record_far_layer).
        const uint32_t near = far_plan_.mesh_splits[t] - group_start_[whole];
        if (near + group_count_[faded] == 0) continue;
        if (in_pass && pass.name != topologies_[t].pass) {
            end_pass(cmd, slot, pass);
            pass = {};
        }
        in_pass = true;
        pass.name = topologies_[t].pass;
        pass.instances += near + group_count_[faded];
        pass.triangles += uint64_t(topologies_[t].index_count / 3) * (near + group_count_[faded]);
        const uint32_t draws_before = draws;
        const Topology& topo = topologies_[t];
        vkCmdBindIndexBuffer(cmd, topo.indices.handle(), 0, VK_INDEX_TYPE_UINT32);
        if (near > 0) draw_group(whole, 0, near, whole_pipeline(topo), 0u);
        // Fading meshes: one draw (per material) per run of equal dither bits, in the group's (nearest-first) order.
        const VkPipeline dithered = pipes_.dithered(topo.vertex_lighting, topo.cull_back_faces);
        for (uint32_t k = 0; k < group_count_[faded];) {
            const uint32_t bits = gpu::lit_dither_bits(frame.meshes[order_[group_start_[faded] + k]].dither);
            uint32_t end = k + 1;
            while (end < group_count_[faded] && gpu::lit_dither_bits(frame.meshes[order_[group_start_[faded] + end]].dither) == bits) ++end;
            draw_group(faded, k, end - k, dithered, bits);
            k = end;
        }
        pass.draws += draws - draws_before;
    }
    if (in_pass) end_pass(cmd, slot, pass);
    draws += record_proxies(frame, cmd, slot, push);
    draws += record_impostors(cmd, slot, push, float(target.extent.height), ImpostorPart::Near);
    // The far and distant layers, depth-tested against everything above (and the lines below against them).
    if (far_plan_.far_count + far_plan_.distant_count > 0) draws += record_composite(cmd, slot, push);
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

VkPipeline CrowdRenderer::whole_pipeline(const Topology& topo) const {
    return topo.vertex_lighting ? (topo.cull_back_faces ? pipes_.vertex_lit_culled() : pipes_.vertex_lit())
                                : (topo.cull_back_faces ? pipes_.mesh_culled() : pipes_.mesh());
}

uint32_t CrowdRenderer::draw_mesh_group(VkCommandBuffer cmd, const FrameInput& frame, uint32_t g, uint32_t first, uint32_t count,
                                        VkPipeline pipeline, uint32_t dither, gpu::LitPush& push, VkPipeline& bound) {
    const VkShaderStageFlags stages = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
    const uint32_t normals = frame.write_normals ? uint32_t{gpu::kLitNormals} : 0u;
    const Topology& topo = topologies_[g / 2];
    if (pipeline != bound) {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline);
        bound = pipeline;
    }
    const uint32_t vertex_base = group_vertex_base_[g] + first * topo.vertex_count, instance_base = group_start_[g] + first;
    if (!frame.materials || topo.ranges.empty()) {
        push.offsets = glm::uvec4(vertex_base, topo.vertex_count, instance_base, gpu::kLitMesh | normals | dither);
        push.base_colour = glm::vec4(1.0f);
        vkCmdPushConstants(cmd, pipes_.layout(), stages, 0, sizeof(push), &push);
        vkCmdDrawIndexed(cmd, topo.index_count, count, 0, 0, 0);
        return 1;
    }
    uint32_t draws = 0;
    for (const Range& r : topo.ranges) {  // one draw per material, every instance of the run
        // An alpha-tested material is drawn with the dithered pipeline (the one that may discard), keeping
        // every pixel unless the group is fading; the others keep the pipeline without discard.
        const bool alpha_test = (r.mode & gpu::kLitAlphaTest) != 0;
        const VkPipeline wanted = pipes_.for_mode(alpha_test ? pipes_.dithered(topo.vertex_lighting, topo.cull_back_faces) : pipeline, r.mode);
        const uint32_t range_dither = alpha_test && dither == 0 ? gpu::lit_dither_bits(1.0f) : dither;
        if (wanted != bound) {
            vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, wanted);
            bound = wanted;
        }
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipes_.layout(), 1, 1, &r.set, 0, nullptr);
        push.offsets = glm::uvec4(vertex_base, topo.vertex_count, instance_base, r.mode | normals | range_dither);
        push.base_colour = materials_[r.material].colour;
        vkCmdPushConstants(cmd, pipes_.layout(), stages, 0, sizeof(push), &push);
        vkCmdDrawIndexed(cmd, r.index_count, count, r.first_index, 0, 0);
        ++draws;
    }
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipes_.layout(), 1, 1, &plain_set_, 0, nullptr);
    return draws;
}

}  // namespace aloha
