// LitPipelines' descriptor sets: the per-frame storage-buffer set, the composite's layer set and the material sets
// (engine/gpu/lit_pipeline.hpp); the pipelines and layouts are made in lit_pipeline.cpp.
#include "engine/gpu/lit_pipeline.hpp"

#include "engine/gpu/buffer.hpp"
#include "engine/gpu/vk_error.hpp"

namespace aloha::gpu {
namespace {

// One descriptor of `set` at `binding`: a buffer (buffer != nullptr) or a combined image sampler.
VkWriteDescriptorSet descriptor_write(VkDescriptorSet set, uint32_t binding, const VkDescriptorBufferInfo* buffer,
                                      const VkDescriptorImageInfo* image = nullptr) {
    VkWriteDescriptorSet w{};
    w.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
    w.dstSet = set;
    w.dstBinding = binding;
    w.descriptorCount = 1;
    w.descriptorType = buffer ? VK_DESCRIPTOR_TYPE_STORAGE_BUFFER : VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    w.pBufferInfo = buffer;
    w.pImageInfo = image;
    return w;
}

}  // namespace

Result<VkDescriptorSet> LitPipelines::allocate_set() const {
    VkDescriptorSetAllocateInfo ai{};
    ai.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO;
    ai.descriptorPool = pool_;
    ai.descriptorSetCount = 1;
    ai.pSetLayouts = &set_layout_;
    VkDescriptorSet set = VK_NULL_HANDLE;
    ALOHA_VK_RETURN(vkAllocateDescriptorSets(device_, &ai, &set));
    return set;
}

void LitPipelines::write_set(VkDescriptorSet set, const Buffer& positions, const Buffer& normals,
                             const Buffer& instances, const Buffer& lines, const Buffer& lighting) const {
    const VkDescriptorBufferInfo infos[5] = {{positions.handle(), 0, VK_WHOLE_SIZE},
                                             {normals.handle(), 0, VK_WHOLE_SIZE},
                                             {instances.handle(), 0, VK_WHOLE_SIZE},
                                             {lines.handle(), 0, VK_WHOLE_SIZE},
                                             {lighting.handle(), 0, VK_WHOLE_SIZE}};
    VkWriteDescriptorSet w[5]{};
    for (uint32_t i = 0; i < 5; ++i) w[i] = descriptor_write(set, i, &infos[i]);
    vkUpdateDescriptorSets(device_, 5, w, 0, nullptr);
}

Result<VkDescriptorSet> LitPipelines::composite_set(VkImageView colour, VkSampler colour_sampler, VkImageView depth,
                                                    VkSampler depth_sampler, VkDescriptorSet reuse) {
    VkDescriptorSet set = reuse;
    if (set == VK_NULL_HANDLE) {
        VkDescriptorSetAllocateInfo ai{};
        ai.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO;
        ai.descriptorPool = composite_pool_;
        ai.descriptorSetCount = 1;
        ai.pSetLayouts = &composite_set_layout_;
        ALOHA_VK_RETURN(vkAllocateDescriptorSets(device_, &ai, &set));
    }
    const VkDescriptorImageInfo images[2] = {{colour_sampler, colour, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
                                             {depth_sampler, depth, VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL}};
    const VkWriteDescriptorSet w[2] = {descriptor_write(set, 0, nullptr, &images[0]), descriptor_write(set, 1, nullptr, &images[1])};
    vkUpdateDescriptorSets(device_, 2, w, 0, nullptr);
    return set;
}

Result<VkDescriptorSet> LitPipelines::material_set(const Buffer& uvs, VkImageView view, VkSampler sampler) {
    MaterialImages images;
    images.fill(MaterialImage{view, sampler});
    return material_set(uvs, uvs, images);
}

Result<VkDescriptorSet> LitPipelines::material_set(const Buffer& uvs, const Buffer& colours, const MaterialImages& images) {
    VkDescriptorSet set = VK_NULL_HANDLE;
    VkDescriptorSetAllocateInfo ai{};
    ai.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO;
    ai.descriptorSetCount = 1;
    ai.pSetLayouts = &material_layout_;
    VkResult r = VK_ERROR_OUT_OF_POOL_MEMORY;
    if (!material_pools_.empty()) {
        ai.descriptorPool = material_pools_.back();
        r = vkAllocateDescriptorSets(device_, &ai, &set);
    }
    if (r == VK_ERROR_OUT_OF_POOL_MEMORY || r == VK_ERROR_FRAGMENTED_POOL) {
        constexpr uint32_t kSets = 256;
        const VkDescriptorPoolSize sizes[2] = {{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 2 * kSets},
                                               {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, kMaterialTextures * kSets}};
        VkDescriptorPoolCreateInfo dpi{};
        dpi.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
        dpi.maxSets = kSets;
        dpi.poolSizeCount = 2;
        dpi.pPoolSizes = sizes;
        VkDescriptorPool pool = VK_NULL_HANDLE;
        ALOHA_VK_RETURN(vkCreateDescriptorPool(device_, &dpi, nullptr, &pool));
        material_pools_.push_back(pool);
        ai.descriptorPool = pool;
        r = vkAllocateDescriptorSets(device_, &ai, &set);
    }
    if (r != VK_SUCCESS) return vk_error("vkAllocateDescriptorSets (material)", r);
    const VkDescriptorBufferInfo buffer{uvs.handle(), 0, VK_WHOLE_SIZE};
    const VkDescriptorBufferInfo colour_buffer{colours.handle(), 0, VK_WHOLE_SIZE};
    VkDescriptorImageInfo image[kMaterialTextures]{};
    VkWriteDescriptorSet w[2 + kMaterialTextures]{};
    w[0] = descriptor_write(set, 0, &buffer);
    w[1 + kMaterialTextures] = descriptor_write(set, 1 + kMaterialTextures, &colour_buffer);
    for (uint32_t i = 0; i < kMaterialTextures; ++i) {
        image[i] = {images[i].sampler, images[i].view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
        w[1 + i] = descriptor_write(set, 1 + i, nullptr, &image[i]);
    }
    vkUpdateDescriptorSets(device_, 2 + kMaterialTextures, w, 0, nullptr);
    return set;
}

}  // namespace aloha::gpu
