// CrowdRenderer impostors: atlas registration and the instanced quad draws (shaders/impostor.*).
#include "engine/gpu/vk_error.hpp"
#include "systems/render/crowd_renderer.hpp"
#include "systems/render/impostor_packing.hpp"

#include <algorithm>
#include <cstddef>
#include <string>

namespace aloha {
namespace {

static_assert(sizeof(ImpostorInstance) == 64 && offsetof(ImpostorInstance, atlas) == 48,
              "ImpostorInstance is copied to the GPU as shaders/impostor.vert's Impostor record");

}  // namespace

std::vector<glm::vec4> impostor_cell_table(const TextureImage& image, const ImpostorAtlasLayout& layout) {
    const uint32_t rows = layout.rows * layout.elevations;  // every band's, one after another
    const uint32_t cw = image.width / layout.directions, ch = image.height / (2 * rows);
    uint32_t levels = 1;  // of the packed atlas: one half's size (pack_impostor_atlas)
    for (uint32_t s = std::max(image.width, image.height / 2); s > 1; s /= 2) ++levels;
    std::vector<glm::vec4> table{glm::vec4(float(cw), float(ch), float(levels), 0.0f),
                                 glm::vec4(layout.elevations > 1 ? layout.elevated_height : 0.0f, layout.depth_ratio, 0.0f, 0.0f)};
    table.reserve(2 + size_t{rows} * layout.directions);
    for (uint32_t r = 0; r < rows; ++r)
        for (uint32_t d = 0; d < layout.directions; ++d) {
            uint32_t x0 = cw, y0 = ch, x1 = 0, y1 = 0;  // covered texels [x0, x1) x [y0, y1), y down from the cell's top
            for (uint32_t y = 0; y < ch; ++y) {
                const uint8_t* row = image.rgba.data() + ((size_t{r} * ch + y) * image.width + size_t{d} * cw) * 4;
                for (uint32_t x = 0; x < cw; ++x)
                    if (row[x * 4 + 3] != 0) {
                        x0 = std::min(x0, x);
                        x1 = std::max(x1, x + 1);
                        y0 = std::min(y0, y);
                        y1 = y + 1;
                    }
            }
            table.push_back(x1 == 0 ? glm::vec4(0.0f)
                                    : glm::vec4(float(x0) / float(cw), float(ch - y1) / float(ch), float(x1) / float(cw), float(ch - y0) / float(ch)));
        }
    return table;
}

Result<uint32_t> CrowdRenderer::register_impostor_atlas(const TextureImage& image, const ImpostorAtlasLayout& layout) {
    if (layout.directions == 0 || layout.rows < 2)
        return gpu::gpu_error("register_impostor_atlas: '" + image.name + "' needs at least 1 direction and 2 rows (a phase and the standing row), has " +
                              std::to_string(layout.directions) + " x " + std::to_string(layout.rows));
    if (layout.elevations < 1 || layout.elevations > kMaxImpostorElevations)
        return gpu::gpu_error("register_impostor_atlas: '" + image.name + "' has " + std::to_string(layout.elevations) +
                              " elevations (bands of views), expected 1 to " + std::to_string(kMaxImpostorElevations));
    const uint32_t rows = layout.rows * layout.elevations;
    if (image.width % layout.directions != 0 || image.height % (2 * rows) != 0)
        return gpu::gpu_error("register_impostor_atlas: '" + image.name + "' of " + std::to_string(image.width) + " x " +
                              std::to_string(image.height) + " pixels is not " + std::to_string(layout.directions) + " x 2*" +
                              std::to_string(rows) + " whole cells");
    if (!(layout.width > 0.0f && layout.height > 0.0f) || (layout.elevations > 1 && !(layout.elevated_height > 0.0f)))
        return gpu::gpu_error("register_impostor_atlas: '" + image.name + "' has an empty quad");
    if (image.rgba.size() != size_t{image.width} * image.height * 4)
        return gpu::gpu_error("register_impostor_atlas: '" + image.name + "' has " + std::to_string(image.rgba.size()) + " bytes for " +
                              std::to_string(image.width) + " x " + std::to_string(image.height) + " RGBA8 pixels");
    // Colour and normal side by side in one texel: one texelFetch a fragment (shaders/impostor.frag).
    const PackedImpostorAtlas packed = pack_impostor_atlas(image);
    Result<gpu::Texture> packed_texture = gpu::Texture::create_rg32ui(ctx_, packed.width, packed.height, packed.levels, packed.texels);
    if (!packed_texture) return packed_texture.error();
    textures_.push_back(std::move(packed_texture).value());
    const std::vector<glm::vec4> table = impostor_cell_table(image, layout);
    Result<gpu::Buffer> cells = gpu::Buffer::create(ctx_, table.size() * sizeof(glm::vec4), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    if (!cells) return cells.error();
    cells.value().write(std::as_bytes(std::span(table)));
    const gpu::Texture& t = textures_.back();
    Result<VkDescriptorSet> set = pipes_.material_set(cells.value(), t.view(), t.sampler());
    if (!set) return set.error();
    atlases_.push_back({std::move(cells).value(), set.value()});
    atlas_layouts_.push_back(layout);
    return static_cast<uint32_t>(atlases_.size() - 1);
}

uint32_t CrowdRenderer::impostor_base(const FrameInput& frame) {
    // Impostor records follow the meshes' and proxies' LitInstances in the instance buffer, 64-byte aligned.
    const uint64_t bytes = (frame.meshes.size() + frame.proxies.size()) * sizeof(gpu::LitInstance);
    return static_cast<uint32_t>((bytes + sizeof(ImpostorInstance) - 1) / sizeof(ImpostorInstance));
}

uint32_t CrowdRenderer::record_impostors(VkCommandBuffer cmd, Slot& slot, gpu::LitPush& push, float viewport_height, ImpostorPart part) {
    uint64_t count = 0;
    for (const ImpostorRun& run : far_plan_.runs) {
        const auto [first, end] = run_part(run, part);
        count += end - first;
    }
    if (count == 0) return 0;
    const VkShaderStageFlags stages = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
    // Neighbouring views, phases and bands blended (or picked per pixel) at full resolution only, from the far layer's
    // limit on this target (the layers' thousands of small quads show the nearest, with the pipeline that reads one
    // texel a fragment, alpha-tested at the layers' threshold).
    const uint32_t blend_from = part == ImpostorPart::Near
                                    ? impostor_blend_from(impostor_views_ != ImpostorViews::Nearest,
                                                          far_layer_limit(far_layer_below_px_, viewport_height))
                                    : kImpostorNeverBlend;
    const bool blend = blend_from != kImpostorNeverBlend;
    const uint32_t upper = blend ? blend_from
                                 : impostor_alpha_test_bits(part == ImpostorPart::Near ? 0.5f : options_.far_layer_alpha_test);
    const VkPipeline pipeline = !blend ? pipes_.impostor()
                                : impostor_views_ == ImpostorViews::Pick ? pipes_.impostor_pick()
                                                                         : pipes_.impostor_blend();
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline);
    const uint32_t base = impostor_base_;
    uint32_t draws = 0;
    for (const ImpostorRun& run : far_plan_.runs) {  // one draw per run of one atlas (its part in this layer)
        const auto [first, end] = run_part(run, part);
        if (end == first) continue;
        const ImpostorAtlasLayout& layout = atlas_layouts_[run.atlas];
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipes_.layout(), 1, 1, &atlases_[run.atlas].set, 0, nullptr);
        push.offsets = glm::uvec4(layout.directions, layout.rows, base + first, impostor_mode_bits(layout.elevations, upper));
        push.base_colour = glm::vec4(layout.width, layout.bottom, layout.height, viewport_height);
        vkCmdPushConstants(cmd, pipes_.layout(), stages, 0, sizeof(push), &push);
        vkCmdDraw(cmd, 6, end - first, 0, 0);
        ++draws;
    }
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipes_.layout(), 1, 1, &plain_set_, 0, nullptr);
    const char* label = part == ImpostorPart::Near ? "impostors" : part == ImpostorPart::Far ? "far layer" : "distant layer";
    end_pass(cmd, slot, {pass_id(label), draws, count, 2 * count});
    return draws;
}

}  // namespace aloha
