// One place that brings up Vulkan for the Vulkan platforms (`vk-lavapipe`, `vk-device:N`, their
// Bresenham and 4-sample variants): the loader, an instance, the physical device a platform
// names, and a logical device with one graphics queue and the line mode the platform asks for.
//
// The loader (libvulkan.so.1, or the file RENDERAUDIT_LIBVULKAN names) is opened at run time and
// its functions fetched by volk, so the project builds and runs where it is missing; only the
// platforms that need it then fail, with the packages to install. Device
// indices are those of vkEnumeratePhysicalDevices, as `renderaudit platforms` lists them.
// `vk-lavapipe` is the device whose driver is Mesa's llvmpipe (VK_DRIVER_ID_MESA_LLVMPIPE);
// `vk-device` the first device that is not a CPU. A driver build (`vk-lavapipe@BUILD`) is that
// build's lavapipe, given to the loader as its only driver (VK_DRIVER_FILES).
#pragma once

#include <volk.h>

#include <memory>
#include <string>
#include <vector>

#include "rundir/platform_spec.h"

namespace ra::platforms {

// What a Vulkan physical device says about itself.
struct VulkanDeviceInfo {
  int index = 0;               // in vkEnumeratePhysicalDevices' order
  std::string name;            // deviceName, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
  std::string type;            // "cpu", "discrete GPU", "integrated GPU", "virtual GPU", "other"
  std::string driver;          // driverName + driverInfo: "llvmpipe Mesa 22.3.6 (LLVM 15.0.6)"
  std::string driver_version;  // driverVersion decoded (NVIDIA's own bit layout, else a.b.c)
  std::string api_version;     // apiVersion, e.g. "1.3.230"
  uint32_t vendor_id = 0;
  bool llvmpipe = false;       // driverID VK_DRIVER_ID_MESA_LLVMPIPE: Mesa's lavapipe
  int subpixel_bits = 0;       // limits.subPixelPrecisionBits
  int line_subpixel_bits = 0;  // VK_EXT_line_rasterization's lineSubPixelPrecisionBits (0: none)
  bool strict_lines = false;   // limits.strictLines: default lines are rectangles
  bool line_rasterization = false;  // VK_EXT_line_rasterization
  bool rectangular_lines = false, bresenham_lines = false, smooth_lines = false;
  bool timestamps = false;         // the graphics queue has timestampValidBits > 0
  int timestamp_valid_bits = 0;    // its timestampValidBits: the counter wraps at 2^bits (36 on
                                   // some Intel GPUs, 64 on NVIDIA and AMD)
  double timestamp_period_ns = 0;  // limits.timestampPeriod
  int max_samples = 1;             // the largest of limits.framebufferColorSampleCounts
  bool precise_occlusion = false;  // features.occlusionQueryPrecise
  bool queue_computes = false;  // the graphics queue runs compute shaders too (the lit-pixel scan)

  // "rectangular, bresenham, smooth" (the modes VK_EXT_line_rasterization offers), or "default".
  std::string line_modes() const;
};

// The loader's devices. Throws ra::util::UserError when libvulkan.so.1 cannot be loaded or no
// instance can be made (naming the packages), std::runtime_error on an unexpected Vulkan error.
std::vector<VulkanDeviceInfo> list_vulkan_devices();

// The lavapipe library a build's ICD file names by `library_path` (an absolute, installed path):
// the file of that name in the build's library folder (a Debian package's usr/lib/<multiarch>, a
// meson prefix's lib/<multiarch>), else build_dir + library_path. Throws UserError naming both.
std::string resolve_icd_library(const std::string& build_dir, const std::string& library_path);

// The device `spec` draws on, among `devices`. Throws ra::util::UserError naming the platform when
// it names no device here (an index beyond the list, no lavapipe, no GPU) or when the device lacks
// what the platform needs (the Bresenham line mode, 4 samples per pixel), listing the devices.
const VulkanDeviceInfo& choose_vulkan_device(const rundir::PlatformSpec& spec,
                                             const std::vector<VulkanDeviceInfo>& devices);

// A logical device for one Vulkan platform: one graphics queue, the line mode enabled.
class VulkanContext {
 public:
  // Loads the loader, makes the instance, chooses the device and creates it (errors as above).
  explicit VulkanContext(const rundir::PlatformSpec& spec);
  ~VulkanContext();
  VulkanContext(const VulkanContext&) = delete;
  VulkanContext& operator=(const VulkanContext&) = delete;

  const VulkanDeviceInfo& info() const { return info_; }
  VkPhysicalDevice physical() const { return physical_; }
  VkDevice device() const { return device_; }
  VkQueue queue() const { return queue_; }
  uint32_t queue_family() const { return queue_family_; }
  // A memory type index with `required` properties among `type_bits`; throws when none.
  uint32_t memory_type(uint32_t type_bits, VkMemoryPropertyFlags required) const;
  // "Vulkan device 0 (lavapipe)": what DriverInfo::backend says.
  std::string backend() const;

 private:
  VkInstance instance_ = VK_NULL_HANDLE;
  VkPhysicalDevice physical_ = VK_NULL_HANDLE;
  VkDevice device_ = VK_NULL_HANDLE;
  VkQueue queue_ = VK_NULL_HANDLE;
  uint32_t queue_family_ = 0;
  VulkanDeviceInfo info_;
};

// Microseconds from timestamp `begin` to timestamp `end` of a counter of `valid_bits` bits that
// ticks every `period_ns` nanoseconds: bits above valid_bits ignored, one wrap between the two
// counted. NaN without a counter (valid_bits 0), or when a 64-bit `end` precedes `begin`.
double timestamp_interval_us(uint64_t begin, uint64_t end, int valid_bits, double period_ns);

// Throws std::runtime_error naming `what` and the VkResult when `r` is not VK_SUCCESS.
void vk_check(VkResult r, const char* what);

}  // namespace ra::platforms
