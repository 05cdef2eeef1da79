// What a Vulkan platform draws with (vulkan_device.cpp): host-visible buffers, the colour
// images, the render pass and one pipeline per primitive kind, with the SPIR-V of
// platforms/shaders/ compiled at build time and embedded (running needs no shader compiler).
//
// Every image stays in VK_IMAGE_LAYOUT_GENERAL: it is drawn into, copied from, cleared and
// resolved in turn, one submission at a time, and no layout transition is then worth its cost.
#pragma once

#include <array>
#include <vector>

#include "rundir/platform_spec.h"
#include "platforms/vulkan_context.h"

namespace ra::platforms {

// A buffer in host-visible, coherent memory, mapped for its whole life.
struct VulkanBuffer {
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  void* mapped = nullptr;
  VkDeviceSize size = 0;
};
// `cached`: ask for host-cached memory first (readback: the CPU reads every byte).
VulkanBuffer create_host_buffer(const VulkanContext& ctx, VkDeviceSize size,
                                VkBufferUsageFlags usage, bool cached);
// A buffer in device-local memory (not mapped): what stays on the device.
VulkanBuffer create_device_buffer(const VulkanContext& ctx, VkDeviceSize size,
                                  VkBufferUsageFlags usage);
void destroy_buffer(const VulkanContext& ctx, VulkanBuffer& b);
// A shader module of embedded SPIR-V (`bytes` long).
VkShaderModule create_shader_module(const VulkanContext& ctx, const uint32_t* code, size_t bytes);

// An RGBA8 colour image of w x h pixels, `layers` array layers and `samples` samples per pixel
// (1 or more), in device-local memory, usable as colour attachment and as copy / resolve / clear
// source and destination; views[k] sees layer k alone.
struct VulkanImage {
  VkImage image = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  std::vector<VkImageView> views;
};
VulkanImage create_colour_image(const VulkanContext& ctx, int w, int h, int samples, int layers = 1);
void destroy_image(const VulkanContext& ctx, VulkanImage& image);

// What the shaders get per draw (push constants, 80 bytes): the matrix from object to Vulkan
// clip coordinates (column-major) and the colour.
struct DrawConstants {
  float clip_from_object[16];
  float colour[4];
};

// The render pass (one colour attachment, loaded and stored: no clear between primitives) and a
// pipeline per primitive kind (point list, line list, triangle list; viewport and scissor
// dynamic; both faces, no blending, lines of width 1 in `line_mode`).
struct VulkanPipelines {
  VkRenderPass render_pass = VK_NULL_HANDLE;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  std::array<VkPipeline, 3> by_kind{};  // indexed by int(Kind)
};
VulkanPipelines create_pipelines(const VulkanContext& ctx, int samples,
                                 rundir::PlatformSpec::LineMode line_mode);
void destroy_pipelines(const VulkanContext& ctx, VulkanPipelines& p);

}  // namespace ra::platforms
