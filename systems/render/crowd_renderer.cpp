#include "systems/render/crowd_renderer.hpp"

#include "engine/gpu/frame_sync.hpp"
#include "engine/gpu/context.hpp"
#include "engine/gpu/vk_error.hpp"
#include "systems/render/proxy_mesh.hpp"

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <cstring>
#include <string>

namespace aloha {
namespace {

static_assert(sizeof(ProxyInstance) == sizeof(gpu::LitInstance) &&
                  offsetof(ProxyInstance, colour) == offsetof(gpu::LitInstance, colour),
              "ProxyInstance is copied to the GPU as LitInstance");
static_assert(sizeof(glm::vec3) == 3 * sizeof(float), "positions are uploaded as tight float triples");

constexpr uint64_t kVec3Bytes = sizeof(glm::vec3);

double ms_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

Result<std::unique_ptr<CrowdRenderer>> CrowdRenderer::create(gpu::Context& ctx, const RendererOptions& options) {
    std::unique_ptr<CrowdRenderer> r(new CrowdRenderer(ctx));
    Status s = r->init(options);
    if (!s) return s.error();
    return r;
}

RendererOptions CrowdRenderer::resolved_options() const {
    RendererOptions o = options_;
    o.far_layer_below_px = far_layer_below_px_;
    o.far_layer_meshes_below_px = far_layer_meshes_below_px_;
    o.blend_texture_mips = blend_texture_mips_;
    o.impostor_views = impostor_views_;
    return o;
}

Status CrowdRenderer::init(const RendererOptions& options) {
    if (!(options.far_layer_alpha_test > 0.0f && options.far_layer_alpha_test <= 1.0f))
        return gpu::gpu_error("CrowdRenderer: far_layer_alpha_test " + std::to_string(options.far_layer_alpha_test) +
                              " is outside (0, 1] (a coverage)");
    options_ = options;
    far_layer_below_px_ = options.far_layer_below_px.value_or(far_layer_default(ctx_.is_cpu_device()));
    blend_texture_mips_ = options.blend_texture_mips.value_or(blend_texture_mips_default(ctx_.is_cpu_device()));
    max_texture_side_ = options.max_texture_side;
    far_layer_meshes_below_px_ = options.far_layer_meshes_below_px.value_or(far_layer_meshes_default(ctx_.is_cpu_device()));
    impostor_views_ = options.impostor_views.value_or(impostor_views_default(ctx_.is_cpu_device()));
    options_.frames_in_flight = std::clamp(options.frames_in_flight, 1u, 4u);
    const VkDevice dev = ctx_.device();
    Result<VkRenderPass> pass = gpu::create_render_pass(dev, options_.colour_format,
                                                        VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
    if (!pass) return pass.error();
    compat_pass_ = pass.value();
    Result<gpu::LitPipelines> pipes = gpu::LitPipelines::create(ctx_, compat_pass_, options_.frames_in_flight,
                                                                options_.constant_fragments);
    if (!pipes) return pipes.error();
    pipes_ = std::move(pipes).value();

    slots_.resize(options_.frames_in_flight);
    for (Slot& s : slots_) {
        if (Status st = gpu::allocate_command_buffer(ctx_, &s.cmd); !st) return st;
        if (Status st = gpu::create_fence(dev, /*signalled=*/false, &s.fence); !st) return st;
        if (Status q = ensure_queries(s, 2); !q) return q;
        Result<VkDescriptorSet> set = pipes_.allocate_set();
        if (!set) return set.error();
        s.set = set.value();
        const uint64_t verts = std::max<uint64_t>(options_.initial_vertices, 1);
        bool grew = false;
        for (auto [buf, bytes] : {std::pair{&s.positions, verts * kVec3Bytes}, std::pair{&s.normals, verts * kVec3Bytes},
                                  std::pair{&s.instances, uint64_t(std::max(options_.initial_instances, 1u)) *
                                                              sizeof(gpu::LitInstance)},
                                  std::pair{&s.lines, uint64_t(std::max(options_.initial_line_segments, 1u)) * 2 *
                                                          sizeof(gpu::LineVertex)},
                                  std::pair{&s.lighting, uint64_t(sizeof(gpu::LitLighting))}}) {
            Status st = ensure(*buf, bytes, grew);
            if (!st) return st;
        }
        Status st = ensure_proxy_indices(s, std::max(options_.initial_instances, 1u));
        if (!st) return st;
    }
    growth_events_ = 0;  // initial allocations are not growth
    for (const char* fixed : {"far meshes", "far layer", "distant layer", "proxies", "impostors", "lines", "composite", "resolve"})
        pass_id(fixed);
    return init_materials();
}

CrowdRenderer::~CrowdRenderer() {
    const VkDevice dev = ctx_.device();
    vkDeviceWaitIdle(dev);
    for (Slot& s : slots_) {
        if (s.queries != VK_NULL_HANDLE) vkDestroyQueryPool(dev, s.queries, nullptr);
        if (s.fence != VK_NULL_HANDLE) vkDestroyFence(dev, s.fence, nullptr);
        if (s.cmd != VK_NULL_HANDLE) vkFreeCommandBuffers(dev, ctx_.command_pool(), 1, &s.cmd);
    }
    if (compat_pass_ != VK_NULL_HANDLE) vkDestroyRenderPass(dev, compat_pass_, nullptr);
}

uint32_t CrowdRenderer::topology_vertex_count(uint32_t topology) const {
    return topology < topologies_.size() ? topologies_[topology].vertex_count : 0;
}

bool CrowdRenderer::Validate(const FrameInput& frame, std::vector<std::string>* errors) const {
    bool ok = true;
    auto fail = [&](std::string msg) {
        ok = false;
        if (errors) errors->push_back(std::move(msg));
    };
    for (size_t i = 0; i < frame.meshes.size(); ++i) {
        const DeformableMesh& m = frame.meshes[i];
        // Strings are built only for failures: validation runs every frame over every mesh.
        auto where = [i] { return "meshes[" + std::to_string(i) + "]: "; };
        if (m.topology >= topologies_.size()) {
            fail(where() + "topology " + std::to_string(m.topology) + " is not registered (" +
                 std::to_string(topologies_.size()) + " registered)");
            continue;
        }
        const uint32_t vc = topologies_[m.topology].vertex_count;
        if (m.positions.size() != vc)
            fail(where() + std::to_string(m.positions.size()) + " positions but topology " +
                 std::to_string(m.topology) + " has " + std::to_string(vc) + " vertices");
        if (m.normals.size() != m.positions.size())
            fail(where() + std::to_string(m.normals.size()) + " normals for " + std::to_string(m.positions.size()) +
                 " positions");
        if (!(m.dither >= -1.0f && m.dither <= 1.0f)) fail(where() + "dither " + std::to_string(m.dither) + " is not in [-1, 1]");
    }
    uint64_t proxies_seen = 0;  // end of the last fade run
    for (size_t i = 0; i < frame.proxy_fades.size(); ++i) {
        const ProxyFade& f = frame.proxy_fades[i];
        if (f.first < proxies_seen || uint64_t{f.first} + f.count > frame.proxies.size())
            fail("proxy_fades[" + std::to_string(i) + "]: proxies [" + std::to_string(f.first) + ", " + std::to_string(uint64_t{f.first} + f.count) +
                 ") overlap the run before or pass the " + std::to_string(frame.proxies.size()) + " proxies");
        if (!(f.share >= 0.0f && f.share <= 1.0f)) fail("proxy_fades[" + std::to_string(i) + "]: share " + std::to_string(f.share) + " is not in [0, 1]");
        proxies_seen = std::max<uint64_t>(proxies_seen, uint64_t{f.first} + f.count);
    }
    for (size_t i = 0; i < frame.impostors.size(); ++i)
        if (frame.impostors[i].atlas >= atlases_.size())
            fail("impostors[" + std::to_string(i) + "]: atlas " + std::to_string(frame.impostors[i].atlas) + " is not registered (" +
                 std::to_string(atlases_.size()) + " registered)");
    if (glm::length(frame.light_direction) <= 0.0f) fail("light_direction must be non-zero");
    if (!(frame.ambient >= 0.0f && frame.ambient <= 1.0f)) fail("ambient must be in [0, 1]");
    for (const glm::vec3& c : {frame.sky_colour, frame.ground_colour, frame.key_colour})
        if (!(c.r >= 0.0f && c.g >= 0.0f && c.b >= 0.0f && c.r + c.g + c.b < 1e6f)) fail("light colours must be finite and >= 0");
    return ok;
}

Status CrowdRenderer::ensure(gpu::Buffer& buffer, uint64_t bytes, bool& grew) {
    if (buffer.handle() != VK_NULL_HANDLE && buffer.size() >= bytes) return {};
    const uint64_t size = std::max<uint64_t>(bytes, buffer.size() + buffer.size() / 2);
    Result<gpu::Buffer> b = gpu::Buffer::create(ctx_, size, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    if (!b) return b.error();
    buffer = std::move(b).value();
    ++growth_events_;
    grew = true;
    return {};
}

Status CrowdRenderer::ensure_proxy_indices(Slot& slot, uint32_t boxes) {
    if (slot.proxy_capacity >= boxes) return {};
    const uint32_t capacity = std::max(boxes, slot.proxy_capacity + slot.proxy_capacity / 2);
    Result<gpu::Buffer> b = gpu::Buffer::create(ctx_, uint64_t(capacity) * kBoxIndexCount * sizeof(uint32_t),
                                                VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
    if (!b) return b.error();
    slot.proxy_indices = std::move(b).value();
    fill_box_batch_indices(capacity, std::span(reinterpret_cast<uint32_t*>(slot.proxy_indices.mapped()),
                                               size_t(capacity) * kBoxIndexCount));
    if (slot.proxy_capacity > 0) ++growth_events_;
    slot.proxy_capacity = capacity;
    return {};
}

Status CrowdRenderer::ensure_queries(Slot& slot, uint32_t count) {
    if (!ctx_.timestamps_supported() || slot.query_capacity >= count) return {};
    if (slot.queries != VK_NULL_HANDLE) vkDestroyQueryPool(ctx_.device(), slot.queries, nullptr);  // slot retired
    slot.queries = VK_NULL_HANDLE;
    VkQueryPoolCreateInfo qi{};
    qi.sType = VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO;
    qi.queryType = VK_QUERY_TYPE_TIMESTAMP;
    qi.queryCount = count;
    ALOHA_VK_RETURN(vkCreateQueryPool(ctx_.device(), &qi, nullptr, &slot.queries));
    slot.query_capacity = count;
    return {};
}

void CrowdRenderer::declare_passes(std::span<const std::string> labels) {
    for (const std::string& label : labels) pass_id(label);
}

uint32_t CrowdRenderer::pass_id(std::string_view name) {
    for (uint32_t i = 0; i < pass_names_.size(); ++i)
        if (pass_names_[i] == name) return i;
    pass_names_.emplace_back(name);
    return static_cast<uint32_t>(pass_names_.size() - 1);
}

Status CrowdRenderer::retire(Slot& slot) {
    if (!slot.pending) return {};
    ALOHA_VK_RETURN(vkWaitForFences(ctx_.device(), 1, &slot.fence, VK_TRUE, UINT64_MAX));
    slot.pending = false;
    if (slot.queries != VK_NULL_HANDLE && slot.frame + 1 > last_completed_frame_) {
        // Query 0 starts the frame; query k + 1 ends timed pass k (or the frame, without pass timestamps).
        const uint32_t count = 1 + std::max<uint32_t>(1, static_cast<uint32_t>(slot.passes.size()));
        std::vector<uint64_t> ticks(count, 0);
        const VkResult r = vkGetQueryPoolResults(ctx_.device(), slot.queries, 0, count, ticks.size() * sizeof(uint64_t),
                                                 ticks.data(), sizeof(uint64_t), VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT);
        if (r != VK_SUCCESS) return gpu::vk_error("vkGetQueryPoolResults", r);
        const double to_ms = double(ctx_.timestamp_period_ns()) * 1e-6;
        auto since_start = [&](uint32_t q) { return ticks[q] >= ticks[0] ? double(ticks[q] - ticks[0]) * to_ms : 0.0; };
        last_gpu_ms_ = since_start(count - 1);
        last_passes_.clear();
        for (uint32_t k = 0; k < slot.passes.size(); ++k) {
            const PassRecord& p = slot.passes[k];
            last_passes_.push_back({pass_names_[p.name], since_start(k), since_start(k + 1) - since_start(k), p.draws,
                                    p.instances, p.triangles});
        }
        last_completed_frame_ = slot.frame + 1;
    }
    return {};
}

Status CrowdRenderer::finish() {
    // Retire oldest first so last_gpu_ms() ends on the newest frame.
    const size_t n = slots_.size();
    for (size_t k = 0; k < n; ++k) {
        Status s = retire(slots_[(frame_index_ + k) % n]);
        if (!s) return s;
    }
    return {};
}

Status CrowdRenderer::render(const FrameInput& frame, gpu::OffscreenTarget& target) {
    return render(frame, target.view());
}

Status CrowdRenderer::render(const FrameInput& frame, const gpu::TargetView& target, const FrameSync& sync) {
    std::vector<std::string> problems;
    if (!Validate(frame, &problems)) {
        std::string msg = "invalid frame input:";
        for (const std::string& p : problems) msg += "\n  " + p;
        return gpu::gpu_error(msg);
    }
    if (target.colour_format != options_.colour_format)
        return gpu::gpu_error("target colour format " + std::to_string(target.colour_format) +
                              " differs from the renderer's " + std::to_string(options_.colour_format));
    Slot& slot = slots_[frame_index_ % slots_.size()];
    Status st = retire(slot);
    if (!st) return st;

    const auto t0 = std::chrono::steady_clock::now();
    uint64_t vertices = 1;  // never 0: the storage buffers must not be empty
    for (const DeformableMesh& m : frame.meshes) vertices += m.positions.size();
    bool grew = false;
    for (auto [buf, bytes] :
         {std::pair{&slot.positions, vertices * kVec3Bytes}, std::pair{&slot.normals, vertices * kVec3Bytes},
          std::pair{&slot.instances, (uint64_t{impostor_base(frame)} + frame.impostors.size()) * sizeof(ImpostorInstance)},
          std::pair{&slot.lines, frame.lines.size() * 2 * sizeof(gpu::LineVertex)}}) {
        st = ensure(*buf, bytes, grew);
        if (!st) return st;
    }
    st = ensure_proxy_indices(slot, static_cast<uint32_t>(frame.proxies.size()));
    if (!st) return st;
    if (grew || slot.set_dirty) {
        pipes_.write_set(slot.set, slot.positions, slot.normals, slot.instances, slot.lines, slot.lighting);
        slot.set_dirty = false;
    }
    last_upload_bytes_ = upload(frame, slot, target.extent);
    if (far_plan_.far_count > 0) {
        st = ensure_layer(slot.far_layer, slot.far_set, target.extent, kFarLayerDivisor);
        if (!st) return st;
    }
    if (far_plan_.distant_count > 0) {
        st = ensure_layer(slot.distant_layer, slot.distant_set, target.extent, kDistantLayerDivisor);
        if (!st) return st;
    }
    last_upload_ms_ = ms_since(t0);
    st = record(frame, target, slot);
    if (!st) return st;

    ALOHA_VK_RETURN(vkResetFences(ctx_.device(), 1, &slot.fence));
    const VkPipelineStageFlags wait_stage = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    VkSubmitInfo si{};
    si.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
    si.waitSemaphoreCount = sync.wait != VK_NULL_HANDLE ? 1 : 0;
    si.pWaitSemaphores = &sync.wait;
    si.pWaitDstStageMask = &wait_stage;
    si.commandBufferCount = 1;
    si.pCommandBuffers = &slot.cmd;
    si.signalSemaphoreCount = sync.signal != VK_NULL_HANDLE ? 1 : 0;
    si.pSignalSemaphores = &sync.signal;
    ALOHA_VK_RETURN(vkQueueSubmit(ctx_.queue(), 1, &si, slot.fence));
    slot.pending = true;
    slot.frame = frame_index_++;
    return {};
}

}  // namespace aloha
