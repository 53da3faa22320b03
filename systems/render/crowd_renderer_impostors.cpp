// CrowdRenderer impostors: atlas registration and the instanced quad draws (shaders/impostor.*).
#include "engine/gpu/vk_error.hpp"
#include "systems/render/crowd_renderer.hpp"

#include <cstddef>

namespace aloha {
namespace {

static_assert(sizeof(ImpostorInstance) == 64 && offsetof(ImpostorInstance, atlas) == 48,
              "ImpostorInstance is copied to the GPU as shaders/impostor.vert's Impostor record");

}  // namespace

Result<uint32_t> CrowdRenderer::register_impostor_atlas(const TextureImage& image, const ImpostorAtlasLayout& layout) {
    if (layout.directions == 0 || layout.rows < 2)
        return gpu::gpu_error("register_impostor_atlas: '" + image.name + "' needs at least 1 direction and 2 rows (a phase and the standing row), has " +
                              std::to_string(layout.directions) + " x " + std::to_string(layout.rows));
    if (image.width % layout.directions != 0 || image.height % (2 * layout.rows) != 0)
        return gpu::gpu_error("register_impostor_atlas: '" + image.name + "' of " + std::to_string(image.width) + " x " +
                              std::to_string(image.height) + " pixels is not " + std::to_string(layout.directions) + " x 2*" +
                              std::to_string(layout.rows) + " whole cells");
    if (!(layout.width > 0.0f && layout.height > 0.0f))
        return gpu::gpu_error("register_impostor_atlas: '" + image.name + "' has an empty quad");
    TextureImage clamped = image;  // cells at the edges must not wrap to the other side
    clamped.wrap_u = clamped.wrap_v = TextureWrap::ClampToEdge;
    clamped.nearest = false;
    Result<uint32_t> texture = register_texture(clamped);
    if (!texture) return texture.error();
    const gpu::Texture& t = textures_[texture.value()];
    Result<VkDescriptorSet> set = pipes_.material_set(no_uvs_, t.view(), t.sampler());
    if (!set) return set.error();
    atlases_.push_back({layout, set.value()});
    return static_cast<uint32_t>(atlases_.size() - 1);
}

uint32_t CrowdRenderer::impostor_base(const FrameInput& frame) {
    // Impostor records follow the meshes' and proxies' LitInstances in the instance buffer, 64-byte aligned.
    const uint64_t bytes = (frame.meshes.size() + frame.proxies.size()) * sizeof(gpu::LitInstance);
    return static_cast<uint32_t>((bytes + sizeof(ImpostorInstance) - 1) / sizeof(ImpostorInstance));
}

uint32_t CrowdRenderer::record_impostors(const FrameInput& frame, VkCommandBuffer cmd, Slot& slot, gpu::LitPush& push) {
    if (frame.impostors.empty()) return 0;
    const VkShaderStageFlags stages = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipes_.impostor());
    const uint32_t base = impostor_base(frame);
    uint32_t draws = 0;
    const auto n = static_cast<uint32_t>(frame.impostors.size());
    for (uint32_t first = 0; first < n;) {  // one draw per run of one atlas
        const uint32_t atlas = frame.impostors[first].atlas;
        uint32_t end = first + 1;
        while (end < n && frame.impostors[end].atlas == atlas) ++end;
        const Atlas& a = atlases_[atlas];
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipes_.layout(), 1, 1, &a.set, 0, nullptr);
        push.offsets = glm::uvec4(a.layout.directions, a.layout.rows, base + first, 0u);
        push.base_colour = glm::vec4(a.layout.width, a.layout.bottom, a.layout.height, 0.0f);
        vkCmdPushConstants(cmd, pipes_.layout(), stages, 0, sizeof(push), &push);
        vkCmdDraw(cmd, 6, end - first, 0, 0);
        ++draws;
        first = end;
    }
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipes_.layout(), 1, 1, &plain_set_, 0, nullptr);
    end_pass(cmd, slot, {pass_id("impostors"), draws, frame.impostors.size(), 2 * uint64_t{n}});
    return draws;
}

}  // namespace aloha
