// The lit-pixel scan on a Vulkan device (see the header).
#include "platforms/vulkan_lit_mask.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <string>

#include "lit_mask_comp.spv.h"  // kLitMaskComp: platforms/shaders/lit_mask.comp, compiled

namespace ra::platforms {
namespace {

constexpr uint32_t kGroupSize = 64;  // the shader's local_size_x

struct PassConstants {  // the shader's push constants
  uint32_t rect_count, word_count, word_base;
};

}  // namespace

VulkanLitMask::VulkanLitMask(const VulkanContext& ctx) : ctx_(ctx) {
  if (!ctx.info().queue_computes)
    throw std::runtime_error("Vulkan device " + ctx.info().name +
                             ": its graphics queue runs no compute shaders (no scan on the device)");
  VkPhysicalDeviceProperties props{};
  vkGetPhysicalDeviceProperties(ctx.physical(), &props);
  max_groups_ = props.limits.maxComputeWorkGroupCount[0];

  VkDescriptorSetLayoutBinding bindings[3]{};
  for (uint32_t i = 0; i < 3; ++i)
    bindings[i] = {i, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr};
  VkDescriptorSetLayoutCreateInfo set{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  set.bindingCount = 3;
  set.pBindings = bindings;
  vk_check(vkCreateDescriptorSetLayout(ctx.device(), &set, nullptr, &set_layout_),
           "vkCreateDescriptorSetLayout");
  const VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(PassConstants)};
  VkPipelineLayoutCreateInfo layout{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  layout.setLayoutCount = 1;
  layout.pSetLayouts = &set_layout_;
  layout.pushConstantRangeCount = 1;
  layout.pPushConstantRanges = &range;
  vk_check(vkCreatePipelineLayout(ctx.device(), &layout, nullptr, &layout_),
           "vkCreatePipelineLayout");
  VkShaderModule module = create_shader_module(ctx, kLitMaskComp, sizeof(kLitMaskComp));
  VkComputePipelineCreateInfo pipeline{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
  pipeline.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0,
                    VK_SHADER_STAGE_COMPUTE_BIT, module, "main", nullptr};
  pipeline.layout = layout_;
  const VkResult made =
      vkCreateComputePipelines(ctx.device(), VK_NULL_HANDLE, 1, &pipeline, nullptr, &pipeline_);
  vkDestroyShaderModule(ctx.device(), module, nullptr);
  vk_check(made, "vkCreateComputePipelines");

  const VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 3};
  VkDescriptorPoolCreateInfo pool{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  pool.maxSets = 1;
  pool.poolSizeCount = 1;
  pool.pPoolSizes = &size;
  vk_check(vkCreateDescriptorPool(ctx.device(), &pool, nullptr, &pool_), "vkCreateDescriptorPool");
  VkDescriptorSetAllocateInfo alloc{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  alloc.descriptorPool = pool_;
  alloc.descriptorSetCount = 1;
  alloc.pSetLayouts = &set_layout_;
  vk_check(vkAllocateDescriptorSets(ctx.device(), &alloc, &set_), "vkAllocateDescriptorSets");
}

VulkanLitMask::~VulkanLitMask() {
  destroy_buffer(ctx_, pixels_);
  destroy_buffer(ctx_, rects_);
  destroy_buffer(ctx_, words_);
  vkDestroyDescriptorPool(ctx_.device(), pool_, nullptr);
  vkDestroyPipeline(ctx_.device(), pipeline_, nullptr);
  vkDestroyPipelineLayout(ctx_.device(), layout_, nullptr);
  vkDestroyDescriptorSetLayout(ctx_.device(), set_layout_, nullptr);
}

VkBuffer VulkanLitMask::prepare(const LitMaskLayout& layout) {
  // Buffers grow to the largest scan so far (at least 1 MiB of pixels): no allocation per batch.
  const VkDeviceSize pixel_bytes = 4 * std::max<VkDeviceSize>(layout.pixel_count, 1);
  const VkDeviceSize rect_bytes = sizeof(LitMaskRect) * std::max<size_t>(layout.rects.size(), 1);
  const VkDeviceSize word_bytes = 4 * (layout.rects.size() + layout.word_count + 1);
  bool rebind = false;
  if (pixel_bytes > pixels_.size) {
    destroy_buffer(ctx_, pixels_);
    pixels_ = create_device_buffer(ctx_, std::max<VkDeviceSize>(pixel_bytes, 1 << 20),
                                   VK_BUFFER_USAGE_TRANSFER_DST_BIT |
                                       VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    rebind = true;
  }
  if (rect_bytes > rects_.size) {
    destroy_buffer(ctx_, rects_);
    rects_ = create_host_buffer(ctx_, std::max<VkDeviceSize>(rect_bytes, 1 << 14),
                                VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, false);
    rebind = true;
  }
  if (word_bytes > words_.size) {
    destroy_buffer(ctx_, words_);
    words_ = create_host_buffer(ctx_, std::max<VkDeviceSize>(word_bytes, 1 << 16),
                                VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
                                    VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                true);
    rebind = true;
  }
  if (rebind) bind_buffers();
  std::memcpy(rects_.mapped, layout.rects.data(), sizeof(LitMaskRect) * layout.rects.size());
  return pixels_.buffer;
}

void VulkanLitMask::bind_buffers() {
  const VkDescriptorBufferInfo infos[3] = {{pixels_.buffer, 0, VK_WHOLE_SIZE},
                                           {rects_.buffer, 0, VK_WHOLE_SIZE},
                                           {words_.buffer, 0, VK_WHOLE_SIZE}};
  VkWriteDescriptorSet writes[3]{};
  for (uint32_t i = 0; i < 3; ++i) {
    writes[i] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    writes[i].dstSet = set_;
    writes[i].dstBinding = i;
    writes[i].descriptorCount = 1;
    writes[i].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    writes[i].pBufferInfo = &infos[i];
  }
  vkUpdateDescriptorSets(ctx_.device(), 3, writes, 0, nullptr);
}

void VulkanLitMask::record(VkCommandBuffer cb, const LitMaskLayout& layout) {
  if (layout.rects.empty()) return;
  const uint32_t rect_count = uint32_t(layout.rects.size());
  vkCmdFillBuffer(cb, words_.buffer, 0, 4 * VkDeviceSize(rect_count), 0);
  VkMemoryBarrier to_pass{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  to_pass.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;  // the fill and the caller's copies
  to_pass.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT;
  vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0,
                       1, &to_pass, 0, nullptr, 0, nullptr);
  vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_);
  vkCmdBindDescriptorSets(cb, VK_PIPELINE_BIND_POINT_COMPUTE, layout_, 0, 1, &set_, 0, nullptr);
  const uint64_t groups_in_all = (layout.word_count + kGroupSize - 1) / kGroupSize;
  for (uint64_t first = 0; first < groups_in_all; first += max_groups_) {
    const PassConstants c{rect_count, uint32_t(layout.word_count), uint32_t(first * kGroupSize)};
    vkCmdPushConstants(cb, layout_, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof c, &c);
    vkCmdDispatch(cb, uint32_t(std::min<uint64_t>(groups_in_all - first, max_groups_)), 1, 1);
  }
  VkMemoryBarrier to_host{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  to_host.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
  to_host.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
  vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1,
                       &to_host, 0, nullptr, 0, nullptr);
}

}  // namespace ra::platforms
