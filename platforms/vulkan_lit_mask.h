// The lit-pixel scan on a Vulkan device (platforms/lit_mask.h): the rectangles are copied from the
// window into a device-local buffer, a compute pass (platforms/shaders/lit_mask.comp) writes a
// bit per pixel and a count per rectangle into a host-visible one, and only that is read.
#pragma once

#include <cstdint>

#include "platforms/lit_mask.h"
#include "platforms/vulkan_context.h"
#include "platforms/vulkan_resources.h"

namespace ra::platforms {

class VulkanLitMask {
 public:
  // Throws std::runtime_error when the device's graphics queue runs no compute shaders.
  explicit VulkanLitMask(const VulkanContext& ctx);
  ~VulkanLitMask();
  VulkanLitMask(const VulkanLitMask&) = delete;
  VulkanLitMask& operator=(const VulkanLitMask&) = delete;

  // Makes room for `layout` and writes its rectangles; returns the device-local buffer that the
  // caller copies the rectangles' pixels into (pixel k at byte 4 k) before record().
  VkBuffer prepare(const LitMaskLayout& layout);
  // Records, after the caller's copies into prepare()'s buffer (transfer stage): the counts
  // zeroed, the pass, and a barrier that makes its results visible to the host.
  void record(VkCommandBuffer cb, const LitMaskLayout& layout);
  // After the submission's wait: rectangle i's lit pixels counted, and its mask.
  uint64_t count(size_t i) const { return words()[i]; }
  const uint32_t* mask(const LitMaskLayout& layout, size_t i) const {
    return words() + layout.rects.size() + layout.rects[i].first_word;
  }

 private:
  const uint32_t* words() const { return static_cast<const uint32_t*>(words_.mapped); }
  void bind_buffers();

  const VulkanContext& ctx_;
  uint32_t max_groups_ = 0;  // limits.maxComputeWorkGroupCount[0]
  VkDescriptorSetLayout set_layout_ = VK_NULL_HANDLE;
  VkPipelineLayout layout_ = VK_NULL_HANDLE;
  VkPipeline pipeline_ = VK_NULL_HANDLE;
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
  VulkanBuffer pixels_;  // device-local: the copied rectangles
  VulkanBuffer rects_;   // host-visible: LitMaskRect per rectangle
  VulkanBuffer words_;   // host-visible, cached: counts, then masks
};

}  // namespace ra::platforms
