// The positive control of tests/scripts/api-validation-test.sh: one misuse of each API that the test's
// validators must report, so that a clean run of the real paths under them means something.
//   gl      an invalid enum to glEnable on osmesa-llvmpipe: Mesa prints "Mesa: User error" under
//           MESA_DEBUG;
//   vulkan  a copy that reads a buffer a fill has just written, with no barrier between them, on
//           vk-lavapipe: a read-after-write hazard that Khronos synchronization validation reports
//           (lavapipe runs the commands in order, so nothing else would show it).
// Exits 0 once the misuse was submitted, 1 when the platform cannot be brought up.
#include <cstdio>
#include <exception>
#include <string>

#include "platforms/gl_context.h"
#include "platforms/vulkan_context.h"
#include "platforms/vulkan_resources.h"

namespace {

using ra::platforms::vk_check;

void misuse_gl() {
  const auto context = ra::platforms::create_gl_context(*ra::rundir::find_platform("osmesa-llvmpipe"));
  context->gl().Enable(0xdead);
  std::printf("glEnable(0xdead): GL error 0x%x\n", context->gl().GetError());
}

void misuse_vulkan() {
  const ra::platforms::VulkanContext ctx(*ra::rundir::find_platform("vk-lavapipe"));
  constexpr VkDeviceSize kBytes = 4096;
  const VkBufferUsageFlags usage = VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  auto written = ra::platforms::create_host_buffer(ctx, kBytes, usage, false);
  auto copied = ra::platforms::create_host_buffer(ctx, kBytes, usage, false);
  VkCommandPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  pool_info.queueFamilyIndex = ctx.queue_family();
  VkCommandPool pool = VK_NULL_HANDLE;
  vk_check(vkCreateCommandPool(ctx.device(), &pool_info, nullptr, &pool), "vkCreateCommandPool");
  VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  alloc.commandPool = pool;
  alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  alloc.commandBufferCount = 1;
  VkCommandBuffer cb = VK_NULL_HANDLE;
  vk_check(vkAllocateCommandBuffers(ctx.device(), &alloc, &cb), "vkAllocateCommandBuffers");
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  vk_check(vkBeginCommandBuffer(cb, &begin), "vkBeginCommandBuffer");
  vkCmdFillBuffer(cb, written.buffer, 0, kBytes, 7);
  const VkBufferCopy region{0, 0, kBytes};
  vkCmdCopyBuffer(cb, written.buffer, copied.buffer, 1, &region);  // the missing barrier is the point
  vk_check(vkEndCommandBuffer(cb), "vkEndCommandBuffer");
  VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &cb;
  vk_check(vkQueueSubmit(ctx.queue(), 1, &submit, VK_NULL_HANDLE), "vkQueueSubmit");
  vk_check(vkQueueWaitIdle(ctx.queue()), "vkQueueWaitIdle");
  std::printf("fill then copy with no barrier: submitted\n");
  vkDestroyCommandPool(ctx.device(), pool, nullptr);
  ra::platforms::destroy_buffer(ctx, copied);
  ra::platforms::destroy_buffer(ctx, written);
}

}  // namespace

int main(int argc, char** argv) {
  const std::string api = argc == 2 ? argv[1] : "";
  if (api != "gl" && api != "vulkan") {
    std::fprintf(stderr, "usage: api_misuse_probe gl|vulkan\n");
    return 2;
  }
  try {
    api == "gl" ? misuse_gl() : misuse_vulkan();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "api_misuse_probe %s: %s\n", api.c_str(), e.what());
    return 1;
  }
  return 0;
}
