#include "engine/gpu/lit_pipeline.hpp"
#include "engine/gpu/lit_pipeline_build.hpp"

#include "engine/gpu/buffer.hpp"
#include "engine/gpu/context.hpp"
#include "engine/gpu/vk_error.hpp"

#include "shaders/composite_frag.h"
#include "shaders/composite_vert.h"
#include "shaders/line_frag.h"
#include "shaders/impostor_blend_frag.h"
#include "shaders/impostor_blend_vert.h"
#include "shaders/impostor_pick_frag.h"
#include "shaders/impostor_frag.h"
#include "shaders/impostor_vert.h"
#include "shaders/line_vert.h"

#include <algorithm>
#include <cmath>
#include <span>
#include <utility>

namespace aloha::gpu {
namespace {

Result<VkShaderModule> make_module(VkDevice device, std::span<const uint32_t> code) {
    VkShaderModuleCreateInfo ci{};
    ci.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO;
    ci.codeSize = code.size_bytes();
    ci.pCode = code.data();
    VkShaderModule m = VK_NULL_HANDLE;
    ALOHA_VK_RETURN(vkCreateShaderModule(device, &ci, nullptr, &m));
    return m;
}


}  // namespace

namespace detail {

Result<VkPipeline> make_pipeline(VkDevice device, VkPipelineLayout layout, VkRenderPass pass, const PipelineDesc& d) {
    Result<VkShaderModule> vs = make_module(device, d.vert);
    if (!vs) return vs.error();
    Result<VkShaderModule> fs = make_module(device, d.frag);
    if (!fs) {
        vkDestroyShaderModule(device, vs.value(), nullptr);
        return fs.error();
    }
    VkPipelineShaderStageCreateInfo stages[2]{};
    stages[0].sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
    stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
    stages[0].module = vs.value();
    stages[0].pName = "main";
    stages[1] = stages[0];
    stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
    stages[1].module = fs.value();
    VkPipelineVertexInputStateCreateInfo vi{};
    vi.sType = VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO;
    VkPipelineInputAssemblyStateCreateInfo ia{};
    ia.sType = VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO;
    ia.topology = d.topology;
    VkPipelineViewportStateCreateInfo vp{};
    vp.sType = VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO;
    vp.viewportCount = 1;
    vp.scissorCount = 1;
    VkPipelineRasterizationStateCreateInfo rs{};
    rs.sType = VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO;
    rs.polygonMode = VK_POLYGON_MODE_FILL;
    rs.cullMode = d.cull;
    rs.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
    rs.lineWidth = 1.0f;
    VkPipelineMultisampleStateCreateInfo ms{};
    ms.sType = VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO;
    ms.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
    VkPipelineDepthStencilStateCreateInfo ds{};
    ds.sType = VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO;
    ds.depthTestEnable = VK_TRUE;
    ds.depthWriteEnable = VK_TRUE;
    ds.depthCompareOp = d.depth_compare;
    VkPipelineColorBlendAttachmentState cb{};
    cb.colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT | VK_COLOR_COMPONENT_B_BIT |
                        VK_COLOR_COMPONENT_A_BIT;
    VkPipelineColorBlendStateCreateInfo cbs{};
    cbs.sType = VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO;
    cbs.attachmentCount = 1;
    cbs.pAttachments = &cb;
    const VkDynamicState dyn[] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
    VkPipelineDynamicStateCreateInfo dys{};
    dys.sType = VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO;
    dys.dynamicStateCount = 2;
    dys.pDynamicStates = dyn;
    VkGraphicsPipelineCreateInfo pci{};
    pci.sType = VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO;
    pci.stageCount = 2;
    pci.pStages = stages;
    pci.pVertexInputState = &vi;
    pci.pInputAssemblyState = &ia;
    pci.pViewportState = &vp;
    pci.pRasterizationState = &rs;
    pci.pMultisampleState = &ms;
    pci.pDepthStencilState = &ds;
    pci.pColorBlendState = &cbs;
    pci.pDynamicState = &dys;
    pci.layout = layout;
    pci.renderPass = pass;
    VkPipeline p = VK_NULL_HANDLE;
    const VkResult r = vkCreateGraphicsPipelines(device, VK_NULL_HANDLE, 1, &pci, nullptr, &p);
    vkDestroyShaderModule(device, vs.value(), nullptr);
    vkDestroyShaderModule(device, fs.value(), nullptr);
    if (r != VK_SUCCESS) return vk_error("vkCreateGraphicsPipelines", r);
    return p;
}

}  // namespace detail

using detail::lit_descs;
using detail::make_pipeline;
using detail::PipelineDesc;

glm::vec3 lit_colour(glm::vec3 colour, glm::vec3 n, glm::vec4 light, const LitLighting& lighting) {
    n = glm::normalize(n);
    const float diffuse = glm::max(glm::dot(n, glm::vec3(light)), 0.0f);
    const glm::vec3 hemi = glm::mix(glm::vec3(lighting.ground), glm::vec3(lighting.sky), 0.5f + 0.5f * n.y);
    return glm::clamp(colour * (light.w * hemi + (1.0f - light.w) * glm::vec3(lighting.key) * diffuse), 0.0f, 1.0f);
}

uint32_t lit_dither_bits(float share) {
    const float s = share < 0.0f ? -share : share;
    uint32_t kept = 0;  // Bayer values b (0..15) whose threshold (b + 0.5) / 16 is below the share
    for (uint32_t b = 0; b < 16; ++b) kept += (static_cast<float>(b) + 0.5f) / 16.0f < s ? 1u : 0u;
    return kept << 8 | (share < 0.0f ? kLitDitherComplement : 0u);
}

uint32_t lit_alpha_bits(float cutoff) {
    if (!(cutoff >= 0.0f)) return 0u;
    const auto q = static_cast<uint32_t>(std::lround(std::min(cutoff, 1.0f) * 65535.0f));
    return kLitAlphaTest | q << 16;
}

glm::mat4 vulkan_clip_from_gl() {
    glm::mat4 m(1.0f);
    m[1][1] = -1.0f;  // y down
    m[2][2] = 0.5f;   // z' = 0.5 z + 0.5 w
    m[3][2] = 0.5f;
    return m;
}

Result<LitPipelines> LitPipelines::create(const Context& ctx, VkRenderPass render_pass, uint32_t max_sets,
                                         bool constant_fragments) {
    LitPipelines lp;
    lp.device_ = ctx.device();
    VkDescriptorSetLayoutBinding b[5]{};
    for (uint32_t i = 0; i < 5; ++i) {
        b[i].binding = i;
        b[i].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
        b[i].descriptorCount = 1;
        b[i].stageFlags = i == 4 ? VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT : VK_SHADER_STAGE_VERTEX_BIT;
    }
    VkDescriptorSetLayoutCreateInfo sli{};
    sli.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO;
    sli.bindingCount = 5;
    sli.pBindings = b;
    ALOHA_VK_RETURN(vkCreateDescriptorSetLayout(lp.device_, &sli, nullptr, &lp.set_layout_));
    VkDescriptorSetLayoutBinding mb[2 + kMaterialTextures]{};
    mb[0].binding = 0;
    mb[0].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    mb[0].descriptorCount = 1;
    mb[0].stageFlags = VK_SHADER_STAGE_VERTEX_BIT;
    for (uint32_t i = 1; i <= kMaterialTextures; ++i) {
        mb[i].binding = i;
        mb[i].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
        mb[i].descriptorCount = 1;
        // The vertex-lit pipelines read metallic-roughness at the vertices.
        mb[i].stageFlags = i == 1 + kMetallicRoughnessTexture ? VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT : VK_SHADER_STAGE_FRAGMENT_BIT;
    }
    mb[1 + kMaterialTextures].binding = 1 + kMaterialTextures;  // vertex colours
    mb[1 + kMaterialTextures].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    mb[1 + kMaterialTextures].descriptorCount = 1;
    mb[1 + kMaterialTextures].stageFlags = VK_SHADER_STAGE_VERTEX_BIT;
    sli.bindingCount = 2 + kMaterialTextures;
    sli.pBindings = mb;
    ALOHA_VK_RETURN(vkCreateDescriptorSetLayout(lp.device_, &sli, nullptr, &lp.material_layout_));
    const VkDescriptorSetLayout layouts[2] = {lp.set_layout_, lp.material_layout_};
    VkPushConstantRange pcr{VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(LitPush)};
    VkPipelineLayoutCreateInfo pli{};
    pli.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
    pli.setLayoutCount = 2;
    pli.pSetLayouts = layouts;
    pli.pushConstantRangeCount = 1;
    pli.pPushConstantRanges = &pcr;
    ALOHA_VK_RETURN(vkCreatePipelineLayout(lp.device_, &pli, nullptr, &lp.layout_));
    VkDescriptorPoolSize ps{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 5 * max_sets};
    VkDescriptorPoolCreateInfo dpi{};
    dpi.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
    dpi.maxSets = max_sets;
    dpi.poolSizeCount = 1;
    dpi.pPoolSizes = &ps;
    ALOHA_VK_RETURN(vkCreateDescriptorPool(lp.device_, &dpi, nullptr, &lp.pool_));
    lp.render_pass_ = render_pass;
    lp.constant_fragments_ = constant_fragments;
    const std::array<PipelineDesc, 8> lit = lit_descs(LitVariant::Plain, constant_fragments);
    constexpr VkPrimitiveTopology kTriangles = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    const std::pair<VkPipeline*, PipelineDesc> pipelines[] = {
        {&lp.mesh_, lit[0]},
        {&lp.culled_, lit[1]},
        {&lp.vertex_lit_, lit[2]},
        {&lp.vertex_lit_culled_, lit[3]},
        {&lp.lines_, {k_line_vert_spv, k_line_frag_spv, VK_PRIMITIVE_TOPOLOGY_LINE_LIST, VK_COMPARE_OP_LESS_OR_EQUAL, VK_CULL_MODE_NONE}},
        {&lp.impostor_, {k_impostor_vert_spv, k_impostor_frag_spv, kTriangles, VK_COMPARE_OP_LESS, VK_CULL_MODE_NONE}},
        {&lp.impostor_blend_, {k_impostor_blend_vert_spv, k_impostor_blend_frag_spv, kTriangles, VK_COMPARE_OP_LESS, VK_CULL_MODE_NONE}},
        {&lp.impostor_pick_, {k_impostor_blend_vert_spv, k_impostor_pick_frag_spv, kTriangles, VK_COMPARE_OP_LESS, VK_CULL_MODE_NONE}},
        {&lp.dithered_[0], lit[4]},
        {&lp.dithered_[1], lit[5]},
        {&lp.dithered_[2], lit[6]},
        {&lp.dithered_[3], lit[7]},
    };
    for (const auto& [out, desc] : pipelines) {
        Result<VkPipeline> p = make_pipeline(lp.device_, lp.layout_, render_pass, desc);
        if (!p) return p.error();
        *out = p.value();
    }
    // The composite: its own set 0 (the layer's colour and depth), the same push constants.
    VkDescriptorSetLayoutBinding cb[2]{};
    for (uint32_t i = 0; i < 2; ++i) {
        cb[i].binding = i;
        cb[i].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
        cb[i].descriptorCount = 1;
        cb[i].stageFlags = VK_SHADER_STAGE_FRAGMENT_BIT;
    }
    sli.bindingCount = 2;
    sli.pBindings = cb;
    ALOHA_VK_RETURN(vkCreateDescriptorSetLayout(lp.device_, &sli, nullptr, &lp.composite_set_layout_));
    pli.setLayoutCount = 1;
    pli.pSetLayouts = &lp.composite_set_layout_;
    ALOHA_VK_RETURN(vkCreatePipelineLayout(lp.device_, &pli, nullptr, &lp.composite_layout_));
    const VkDescriptorPoolSize cps{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 2 * kCompositeSets};
    dpi.maxSets = kCompositeSets;
    dpi.pPoolSizes = &cps;
    ALOHA_VK_RETURN(vkCreateDescriptorPool(lp.device_, &dpi, nullptr, &lp.composite_pool_));
    Result<VkPipeline> composite = make_pipeline(lp.device_, lp.composite_layout_, render_pass,
                                                 {k_composite_vert_spv, k_composite_frag_spv, kTriangles, VK_COMPARE_OP_LESS_OR_EQUAL,
                                                  VK_CULL_MODE_NONE});
    if (!composite) return composite.error();
    lp.composite_ = composite.value();
    return lp;
}

LitPipelines::LitPipelines(LitPipelines&& o) noexcept
    : device_(std::exchange(o.device_, VK_NULL_HANDLE)),
      set_layout_(std::exchange(o.set_layout_, VK_NULL_HANDLE)),
      layout_(std::exchange(o.layout_, VK_NULL_HANDLE)),
      pool_(std::exchange(o.pool_, VK_NULL_HANDLE)),
      material_layout_(std::exchange(o.material_layout_, VK_NULL_HANDLE)),
      material_pools_(std::exchange(o.material_pools_, {})),
      mesh_(std::exchange(o.mesh_, VK_NULL_HANDLE)),
      culled_(std::exchange(o.culled_, VK_NULL_HANDLE)),
      lines_(std::exchange(o.lines_, VK_NULL_HANDLE)),
      vertex_lit_(std::exchange(o.vertex_lit_, VK_NULL_HANDLE)),
      vertex_lit_culled_(std::exchange(o.vertex_lit_culled_, VK_NULL_HANDLE)),
      impostor_(std::exchange(o.impostor_, VK_NULL_HANDLE)),
      impostor_blend_(std::exchange(o.impostor_blend_, VK_NULL_HANDLE)),
      impostor_pick_(std::exchange(o.impostor_pick_, VK_NULL_HANDLE)),
      composite_(std::exchange(o.composite_, VK_NULL_HANDLE)),
      composite_set_layout_(std::exchange(o.composite_set_layout_, VK_NULL_HANDLE)),
      composite_layout_(std::exchange(o.composite_layout_, VK_NULL_HANDLE)),
      composite_pool_(std::exchange(o.composite_pool_, VK_NULL_HANDLE)),
      twins_(std::exchange(o.twins_, {})),
      render_pass_(std::exchange(o.render_pass_, VK_NULL_HANDLE)),
      constant_fragments_(o.constant_fragments_) {
    for (int i = 0; i < 4; ++i) dithered_[i] = std::exchange(o.dithered_[i], VK_NULL_HANDLE);
}

LitPipelines& LitPipelines::operator=(LitPipelines&& o) noexcept {
    if (this != &o) {
        destroy();
        device_ = std::exchange(o.device_, VK_NULL_HANDLE);
        set_layout_ = std::exchange(o.set_layout_, VK_NULL_HANDLE);
        layout_ = std::exchange(o.layout_, VK_NULL_HANDLE);
        pool_ = std::exchange(o.pool_, VK_NULL_HANDLE);
        material_layout_ = std::exchange(o.material_layout_, VK_NULL_HANDLE);
        material_pools_ = std::exchange(o.material_pools_, {});
        mesh_ = std::exchange(o.mesh_, VK_NULL_HANDLE);
        culled_ = std::exchange(o.culled_, VK_NULL_HANDLE);
        lines_ = std::exchange(o.lines_, VK_NULL_HANDLE);
        vertex_lit_ = std::exchange(o.vertex_lit_, VK_NULL_HANDLE);
        vertex_lit_culled_ = std::exchange(o.vertex_lit_culled_, VK_NULL_HANDLE);
        impostor_ = std::exchange(o.impostor_, VK_NULL_HANDLE);
        impostor_blend_ = std::exchange(o.impostor_blend_, VK_NULL_HANDLE);
        impostor_pick_ = std::exchange(o.impostor_pick_, VK_NULL_HANDLE);
        composite_ = std::exchange(o.composite_, VK_NULL_HANDLE);
        composite_set_layout_ = std::exchange(o.composite_set_layout_, VK_NULL_HANDLE);
        composite_layout_ = std::exchange(o.composite_layout_, VK_NULL_HANDLE);
        composite_pool_ = std::exchange(o.composite_pool_, VK_NULL_HANDLE);
        for (int i = 0; i < 4; ++i) dithered_[i] = std::exchange(o.dithered_[i], VK_NULL_HANDLE);
        twins_ = std::exchange(o.twins_, {});
        render_pass_ = std::exchange(o.render_pass_, VK_NULL_HANDLE);
        constant_fragments_ = o.constant_fragments_;
    }
    return *this;
}

void LitPipelines::destroy() {
    if (device_ == VK_NULL_HANDLE) return;
    if (mesh_ != VK_NULL_HANDLE) vkDestroyPipeline(device_, mesh_, nullptr);
    if (culled_ != VK_NULL_HANDLE) vkDestroyPipeline(device_, culled_, nullptr);
    if (lines_ != VK_NULL_HANDLE) vkDestroyPipeline(device_, lines_, nullptr);
    if (vertex_lit_ != VK_NULL_HANDLE) vkDestroyPipeline(device_, vertex_lit_, nullptr);
    if (vertex_lit_culled_ != VK_NULL_HANDLE) vkDestroyPipeline(device_, vertex_lit_culled_, nullptr);
    if (impostor_ != VK_NULL_HANDLE) vkDestroyPipeline(device_, impostor_, nullptr);
    if (impostor_blend_ != VK_NULL_HANDLE) vkDestroyPipeline(device_, impostor_blend_, nullptr);
    if (impostor_pick_ != VK_NULL_HANDLE) vkDestroyPipeline(device_, impostor_pick_, nullptr);
    if (composite_ != VK_NULL_HANDLE) vkDestroyPipeline(device_, composite_, nullptr);
    if (composite_pool_ != VK_NULL_HANDLE) vkDestroyDescriptorPool(device_, composite_pool_, nullptr);
    if (composite_layout_ != VK_NULL_HANDLE) vkDestroyPipelineLayout(device_, composite_layout_, nullptr);
    if (composite_set_layout_ != VK_NULL_HANDLE) vkDestroyDescriptorSetLayout(device_, composite_set_layout_, nullptr);
    composite_pool_ = VK_NULL_HANDLE;
    composite_layout_ = VK_NULL_HANDLE;
    composite_set_layout_ = VK_NULL_HANDLE;
    for (VkPipeline& p : dithered_) {
        if (p != VK_NULL_HANDLE) vkDestroyPipeline(device_, p, nullptr);
        p = VK_NULL_HANDLE;
    }
    for (std::array<VkPipeline, 8>& twins : twins_)
        for (VkPipeline& p : twins) {
            if (p != VK_NULL_HANDLE) vkDestroyPipeline(device_, p, nullptr);
            p = VK_NULL_HANDLE;
        }
    render_pass_ = VK_NULL_HANDLE;
    if (pool_ != VK_NULL_HANDLE) vkDestroyDescriptorPool(device_, pool_, nullptr);
    for (VkDescriptorPool p : material_pools_) vkDestroyDescriptorPool(device_, p, nullptr);
    material_pools_.clear();
    if (material_layout_ != VK_NULL_HANDLE) vkDestroyDescriptorSetLayout(device_, material_layout_, nullptr);
    material_layout_ = VK_NULL_HANDLE;
    if (layout_ != VK_NULL_HANDLE) vkDestroyPipelineLayout(device_, layout_, nullptr);
    if (set_layout_ != VK_NULL_HANDLE) vkDestroyDescriptorSetLayout(device_, set_layout_, nullptr);
    device_ = VK_NULL_HANDLE;
    mesh_ = culled_ = lines_ = vertex_lit_ = vertex_lit_culled_ = impostor_ = impostor_blend_ = impostor_pick_ = composite_ = VK_NULL_HANDLE;
    pool_ = VK_NULL_HANDLE;
    layout_ = VK_NULL_HANDLE;
    set_layout_ = VK_NULL_HANDLE;
}

}  // namespace aloha::gpu
