// Buffers, images, the render pass and the pipelines of the Vulkan platforms (see the header).
#include "platforms/vulkan_resources.h"

#include <cstdint>
#include <stdexcept>

#include "primitive_frag.spv.h"  // kPrimitiveFrag: platforms/shaders/primitive.frag, compiled
#include "primitive_vert.spv.h"  // kPrimitiveVert: platforms/shaders/primitive.vert, compiled

namespace ra::platforms {

namespace {

VulkanBuffer create_buffer(const VulkanContext& ctx, VkDeviceSize size, VkBufferUsageFlags usage,
                           VkMemoryPropertyFlags preferred, VkMemoryPropertyFlags required) {
  VulkanBuffer b;
  b.size = size;
  VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  info.size = size;
  info.usage = usage;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  vk_check(vkCreateBuffer(ctx.device(), &info, nullptr, &b.buffer), "vkCreateBuffer");
  VkMemoryRequirements req{};
  vkGetBufferMemoryRequirements(ctx.device(), b.buffer, &req);
  uint32_t type = 0;
  try {
    type = ctx.memory_type(req.memoryTypeBits, preferred);
  } catch (const std::runtime_error&) {
    type = ctx.memory_type(req.memoryTypeBits, required);
  }
  VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  alloc.allocationSize = req.size;
  alloc.memoryTypeIndex = type;
  vk_check(vkAllocateMemory(ctx.device(), &alloc, nullptr, &b.memory), "vkAllocateMemory");
  vk_check(vkBindBufferMemory(ctx.device(), b.buffer, b.memory, 0), "vkBindBufferMemory");
  return b;
}

}  // namespace

VulkanBuffer create_host_buffer(const VulkanContext& ctx, VkDeviceSize size,
                                VkBufferUsageFlags usage, bool cached) {
  const VkMemoryPropertyFlags host =
      VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
  VulkanBuffer b =
      create_buffer(ctx, size, usage, cached ? host | VK_MEMORY_PROPERTY_HOST_CACHED_BIT : host, host);
  vk_check(vkMapMemory(ctx.device(), b.memory, 0, VK_WHOLE_SIZE, 0, &b.mapped), "vkMapMemory");
  return b;
}

VulkanBuffer create_device_buffer(const VulkanContext& ctx, VkDeviceSize size,
                                  VkBufferUsageFlags usage) {
  return create_buffer(ctx, size, usage, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, 0);
}

void destroy_buffer(const VulkanContext& ctx, VulkanBuffer& b) {
  if (b.buffer) vkDestroyBuffer(ctx.device(), b.buffer, nullptr);
  if (b.memory) vkFreeMemory(ctx.device(), b.memory, nullptr);  // unmaps
  b = VulkanBuffer{};
}

VulkanImage create_colour_image(const VulkanContext& ctx, int w, int h, int samples, int layers) {
  VulkanImage out;
  VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  info.imageType = VK_IMAGE_TYPE_2D;
  info.format = VK_FORMAT_R8G8B8A8_UNORM;
  info.extent = {uint32_t(w), uint32_t(h), 1};
  info.mipLevels = 1;
  info.arrayLayers = uint32_t(layers);
  info.samples = VkSampleCountFlagBits(samples);
  info.tiling = VK_IMAGE_TILING_OPTIMAL;
  info.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
               VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  vk_check(vkCreateImage(ctx.device(), &info, nullptr, &out.image), "vkCreateImage");
  VkMemoryRequirements req{};
  vkGetImageMemoryRequirements(ctx.device(), out.image, &req);
  VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  alloc.allocationSize = req.size;
  alloc.memoryTypeIndex = ctx.memory_type(req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  vk_check(vkAllocateMemory(ctx.device(), &alloc, nullptr, &out.memory), "vkAllocateMemory");
  vk_check(vkBindImageMemory(ctx.device(), out.image, out.memory, 0), "vkBindImageMemory");
  for (int k = 0; k < layers; ++k) {
    VkImageViewCreateInfo view{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    view.image = out.image;
    view.viewType = VK_IMAGE_VIEW_TYPE_2D;
    view.format = info.format;
    view.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, uint32_t(k), 1};
    out.views.push_back(VK_NULL_HANDLE);
    vk_check(vkCreateImageView(ctx.device(), &view, nullptr, &out.views.back()),
             "vkCreateImageView");
  }
  return out;
}

void destroy_image(const VulkanContext& ctx, VulkanImage& image) {
  for (VkImageView v : image.views)
    if (v) vkDestroyImageView(ctx.device(), v, nullptr);
  if (image.image) vkDestroyImage(ctx.device(), image.image, nullptr);
  if (image.memory) vkFreeMemory(ctx.device(), image.memory, nullptr);
  image = VulkanImage{};
}

namespace {

VkRenderPass create_render_pass(const VulkanContext& ctx, int samples) {
  VkAttachmentDescription colour{};
  colour.format = VK_FORMAT_R8G8B8A8_UNORM;
  colour.samples = VkSampleCountFlagBits(samples);
  colour.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;  // earlier primitives stay: no clear per primitive
  colour.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  colour.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
  colour.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  colour.initialLayout = VK_IMAGE_LAYOUT_GENERAL;
  colour.finalLayout = VK_IMAGE_LAYOUT_GENERAL;
  VkAttachmentReference ref{0, VK_IMAGE_LAYOUT_GENERAL};
  VkSubpassDescription subpass{};
  subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  subpass.colorAttachmentCount = 1;
  subpass.pColorAttachments = &ref;
  // Clears, copies and resolves of earlier submissions before the draw; the draw before the
  // copies and resolves after it.
  const VkPipelineStageFlags transfer = VK_PIPELINE_STAGE_TRANSFER_BIT;
  const VkPipelineStageFlags output = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
  const VkAccessFlags colour_rw =
      VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
  const VkAccessFlags transfer_rw = VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
  const VkSubpassDependency deps[2] = {
      {VK_SUBPASS_EXTERNAL, 0, transfer | output, output, transfer_rw | colour_rw, colour_rw, 0},
      {0, VK_SUBPASS_EXTERNAL, output, transfer | output, colour_rw, transfer_rw | colour_rw, 0}};
  VkRenderPassCreateInfo info{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
  info.attachmentCount = 1;
  info.pAttachments = &colour;
  info.subpassCount = 1;
  info.pSubpasses = &subpass;
  info.dependencyCount = 2;
  info.pDependencies = deps;
  VkRenderPass pass = VK_NULL_HANDLE;
  vk_check(vkCreateRenderPass(ctx.device(), &info, nullptr, &pass), "vkCreateRenderPass");
  return pass;
}

}  // namespace

VkShaderModule create_shader_module(const VulkanContext& ctx, const uint32_t* code, size_t bytes) {
  VkShaderModuleCreateInfo info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  info.codeSize = bytes;
  info.pCode = code;
  VkShaderModule m = VK_NULL_HANDLE;
  vk_check(vkCreateShaderModule(ctx.device(), &info, nullptr, &m), "vkCreateShaderModule");
  return m;
}

VulkanPipelines create_pipelines(const VulkanContext& ctx, int samples,
                                 rundir::PlatformSpec::LineMode line_mode) {
  VulkanPipelines p;
  p.render_pass = create_render_pass(ctx, samples);
  VkPushConstantRange range{VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                            sizeof(DrawConstants)};
  VkPipelineLayoutCreateInfo layout{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  layout.pushConstantRangeCount = 1;
  layout.pPushConstantRanges = &range;
  vk_check(vkCreatePipelineLayout(ctx.device(), &layout, nullptr, &p.layout),
           "vkCreatePipelineLayout");

  VkShaderModule vert = create_shader_module(ctx, kPrimitiveVert, sizeof(kPrimitiveVert));
  VkShaderModule frag = create_shader_module(ctx, kPrimitiveFrag, sizeof(kPrimitiveFrag));
  VkPipelineShaderStageCreateInfo stages[2] = {
      {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_VERTEX_BIT,
       vert, "main", nullptr},
      {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0,
       VK_SHADER_STAGE_FRAGMENT_BIT, frag, "main", nullptr}};
  VkVertexInputBindingDescription binding{0, 4 * sizeof(float), VK_VERTEX_INPUT_RATE_VERTEX};
  VkVertexInputAttributeDescription attribute{0, 0, VK_FORMAT_R32G32B32A32_SFLOAT, 0};
  VkPipelineVertexInputStateCreateInfo input{
      VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
  input.vertexBindingDescriptionCount = 1;
  input.pVertexBindingDescriptions = &binding;
  input.vertexAttributeDescriptionCount = 1;
  input.pVertexAttributeDescriptions = &attribute;
  VkPipelineViewportStateCreateInfo viewport{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
  viewport.viewportCount = 1;
  viewport.scissorCount = 1;
  // The paper's conditions: both faces filled, width 1, no blending, no depth test.
  VkPipelineRasterizationStateCreateInfo raster{
      VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
  raster.polygonMode = VK_POLYGON_MODE_FILL;
  raster.cullMode = VK_CULL_MODE_NONE;
  raster.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
  raster.lineWidth = 1;
  VkPipelineRasterizationLineStateCreateInfoEXT line{
      VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_LINE_STATE_CREATE_INFO_EXT};
  if (line_mode == rundir::PlatformSpec::LineMode::kBresenham) {
    line.lineRasterizationMode = VK_LINE_RASTERIZATION_MODE_BRESENHAM_EXT;
    raster.pNext = &line;
  }
  VkPipelineMultisampleStateCreateInfo multisample{
      VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
  multisample.rasterizationSamples = VkSampleCountFlagBits(samples);
  VkPipelineColorBlendAttachmentState blend{};
  blend.colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT |
                         VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;
  VkPipelineColorBlendStateCreateInfo colour{
      VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
  colour.attachmentCount = 1;
  colour.pAttachments = &blend;
  const VkDynamicState dynamic_states[2] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
  VkPipelineDynamicStateCreateInfo dynamic{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
  dynamic.dynamicStateCount = 2;
  dynamic.pDynamicStates = dynamic_states;

  const VkPrimitiveTopology topologies[3] = {VK_PRIMITIVE_TOPOLOGY_POINT_LIST,
                                             VK_PRIMITIVE_TOPOLOGY_LINE_LIST,
                                             VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST};
  for (int k = 0; k < 3; ++k) {
    VkPipelineInputAssemblyStateCreateInfo assembly{
        VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
    assembly.topology = topologies[k];
    VkGraphicsPipelineCreateInfo info{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
    info.stageCount = 2;
    info.pStages = stages;
    info.pVertexInputState = &input;
    info.pInputAssemblyState = &assembly;
    info.pViewportState = &viewport;
    info.pRasterizationState = &raster;
    info.pMultisampleState = &multisample;
    info.pColorBlendState = &colour;
    info.pDynamicState = &dynamic;
    info.layout = p.layout;
    info.renderPass = p.render_pass;
    vk_check(
        vkCreateGraphicsPipelines(ctx.device(), VK_NULL_HANDLE, 1, &info, nullptr, &p.by_kind[k]),
        "vkCreateGraphicsPipelines");
  }
  vkDestroyShaderModule(ctx.device(), vert, nullptr);
  vkDestroyShaderModule(ctx.device(), frag, nullptr);
  return p;
}

void destroy_pipelines(const VulkanContext& ctx, VulkanPipelines& p) {
  for (VkPipeline& pipeline : p.by_kind)
    if (pipeline) vkDestroyPipeline(ctx.device(), pipeline, nullptr);
  if (p.layout) vkDestroyPipelineLayout(ctx.device(), p.layout, nullptr);
  if (p.render_pass) vkDestroyRenderPass(ctx.device(), p.render_pass, nullptr);
  p = VulkanPipelines{};
}

}  // namespace ra::platforms
