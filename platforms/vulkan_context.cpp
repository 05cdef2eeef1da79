// Bringing up Vulkan for a platform (see the header).
#include "platforms/vulkan_context.h"

#include <dlfcn.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "platforms/driver_loading.h"
#include "rundir/build_record.h"
#include "util/atomic_file.h"
#include "util/errors.h"

namespace fs = std::filesystem;

namespace ra::platforms {
namespace {

std::string version_text(uint32_t v) {
  return std::to_string(VK_API_VERSION_MAJOR(v)) + "." + std::to_string(VK_API_VERSION_MINOR(v)) +
         "." + std::to_string(VK_API_VERSION_PATCH(v));
}

// driverVersion is vendor-defined: NVIDIA packs 10.8.8.6 bits, Mesa and most others use
// VK_MAKE_API_VERSION's layout.
std::string driver_version_text(uint32_t vendor, uint32_t v) {
  if (vendor == 0x10de)
    return std::to_string(v >> 22) + "." + std::to_string((v >> 14) & 0xff) + "." +
           std::to_string((v >> 6) & 0xff) + "." + std::to_string(v & 0x3f);
  return version_text(v);
}

std::string type_text(VkPhysicalDeviceType t) {
  switch (t) {
    case VK_PHYSICAL_DEVICE_TYPE_CPU:
      return "cpu";
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU:
      return "discrete GPU";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU:
      return "integrated GPU";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU:
      return "virtual GPU";
    default:
      return "other";
  }
}

}  // namespace

std::string resolve_icd_library(const std::string& build_dir, const std::string& library_path) {
  std::error_code ec;
  const std::string in_libs =
      rundir::build_library_dir(build_dir) + "/" + fs::path(library_path).filename().string();
  if (fs::exists(in_libs, ec)) return in_libs;
  if (!library_path.empty() && library_path[0] == '/' && fs::exists(build_dir + library_path, ec))
    return build_dir + library_path;
  throw util::UserError("driver build " + build_dir + ": its Vulkan driver file names " +
                        library_path + ", found neither as " + in_libs + " nor under the folder");
}

namespace {

// A driver build's lavapipe as the loader's only driver: the build's ICD file names the library
// by its installed path (/usr/lib/... for a Debian package, the meson prefix it was built for, a
// temporary folder, for a source build), so a copy naming the library inside the build folder
// is written there. The ICD file is under usr/share (a Debian package) or share (a meson prefix).
void use_driver_build(const rundir::PlatformSpec& spec) {
  std::error_code ec;
  fs::path icd;
  std::vector<fs::path> icd_dirs = {fs::path(spec.build_dir) / "usr/share/vulkan/icd.d",
                                    fs::path(spec.build_dir) / "share/vulkan/icd.d"};
  for (const fs::path& icd_dir : icd_dirs)
    for (const auto& e : fs::directory_iterator(icd_dir, ec))
      if (icd.empty() && e.path().filename().string().rfind("lvp_icd", 0) == 0) icd = e.path();
  if (icd.empty())
    throw util::UserError(
        "platform " + spec.name + ": the driver build folder " + spec.build_dir +
        " holds no lavapipe (" + icd_dirs[0].string() +
        "/lvp_icd.*.json, or share/vulkan/icd.d "
        "of a meson prefix); unpack the build's mesa-vulkan-drivers package into it, or build "
        "Mesa with -Dvulkan-drivers=swrast");
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(util::read_file(icd.string()));
  } catch (const std::exception& e) {
    throw util::UserError(icd.string() + ": not a readable Vulkan driver file (" + e.what() + ")");
  }
  std::string library = j["ICD"].value("library_path", "");
  if (library.empty()) throw util::UserError(icd.string() + ": 'ICD.library_path' is missing");
  j["ICD"]["library_path"] = resolve_icd_library(spec.build_dir, library);
  const std::string local = spec.build_dir + "/renderaudit_lvp_icd.json";
  util::write_file_atomic(local, j.dump(2) + "\n");
  setenv("VK_DRIVER_FILES", local.c_str(), 1);
  setenv("VK_ICD_FILENAMES", local.c_str(), 1);  // loaders before 1.3.207
}

// One instance per process, made at the first platform: the loader reads its driver list then.
VkInstance process_instance(const rundir::PlatformSpec* spec) {
  static VkInstance instance = VK_NULL_HANDLE;
  static std::string made_for_build;
  const std::string build = spec ? spec->build_dir : "";
  if (instance != VK_NULL_HANDLE) {
    if (spec && build != made_for_build)
      throw util::UserError("platform " + spec->name +
                            ": this process already loaded another Vulkan driver (one driver build "
                            "per process)");
    return instance;
  }
  if (spec && !spec->build.empty()) use_driver_build(*spec);
  // The build's lavapipe and the libraries it needs by path, before the loader asks for them
  // (platforms/driver_loading.h); for the installed driver, remember that this process uses it.
  if (spec) load_driver_build(*spec);
  // one-primitive frames: llvmpipe's thread hand-off costs more than the drawing (lavapipe too)
  setenv("LP_NUM_THREADS", "0", 0);
  // The loader: RENDERAUDIT_LIBVULKAN when set (another loader, or none, for the tests), else
  // the installed libvulkan.so.1; volk fetches every function through it.
  const char* named = std::getenv("RENDERAUDIT_LIBVULKAN");
  const std::string library = named && *named ? named : "libvulkan.so.1";
  void* loader = dlopen(library.c_str(), RTLD_NOW | RTLD_LOCAL);
  const auto get_proc =
      loader ? reinterpret_cast<PFN_vkGetInstanceProcAddr>(dlsym(loader, "vkGetInstanceProcAddr"))
             : nullptr;
  if (!get_proc)
    throw util::UserError("no Vulkan loader: " + library + " cannot be loaded" +
                          (named && *named ? " (the library RENDERAUDIT_LIBVULKAN names)"
                                           : " (apt-get install libvulkan1 mesa-vulkan-drivers)"));
  volkInitializeCustom(get_proc);
  uint32_t loader_version = VK_API_VERSION_1_0;
  if (vkEnumerateInstanceVersion) vkEnumerateInstanceVersion(&loader_version);
  if (loader_version < VK_API_VERSION_1_1)
    throw util::UserError("the Vulkan loader is version " + version_text(loader_version) +
                          "; renderaudit needs 1.1 or newer (apt-get install libvulkan1)");
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "renderaudit";
  app.apiVersion = loader_version < VK_API_VERSION_1_3 ? loader_version : VK_API_VERSION_1_3;
  VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  info.pApplicationInfo = &app;
  const VkResult r = vkCreateInstance(&info, nullptr, &instance);
  if (r == VK_ERROR_INCOMPATIBLE_DRIVER)
    throw util::UserError(
        "the Vulkan loader finds no driver (VK_ERROR_INCOMPATIBLE_DRIVER; apt-get "
        "install mesa-vulkan-drivers for lavapipe, or the GPU vendor's driver)");
  vk_check(r, "vkCreateInstance");
  volkLoadInstance(instance);
  made_for_build = build;
  return instance;
}

VulkanDeviceInfo describe(VkPhysicalDevice pd, int index, uint32_t* graphics_family) {
  VulkanDeviceInfo d;
  d.index = index;
  VkPhysicalDeviceProperties base{};
  vkGetPhysicalDeviceProperties(pd, &base);
  uint32_t n = 0;
  vkEnumerateDeviceExtensionProperties(pd, nullptr, &n, nullptr);
  std::vector<VkExtensionProperties> exts(n);
  vkEnumerateDeviceExtensionProperties(pd, nullptr, &n, exts.data());
  for (const VkExtensionProperties& e : exts)
    if (std::strcmp(e.extensionName, VK_EXT_LINE_RASTERIZATION_EXTENSION_NAME) == 0)
      d.line_rasterization = true;

  VkPhysicalDeviceLineRasterizationPropertiesEXT line_props{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_LINE_RASTERIZATION_PROPERTIES_EXT};
  VkPhysicalDeviceDriverProperties driver{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
  VkPhysicalDeviceProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
  const bool has_driver_props = base.apiVersion >= VK_API_VERSION_1_2;
  if (has_driver_props) props.pNext = &driver;
  if (d.line_rasterization) {
    line_props.pNext = props.pNext;
    props.pNext = &line_props;
  }
  vkGetPhysicalDeviceProperties2(pd, &props);
  VkPhysicalDeviceLineRasterizationFeaturesEXT line_features{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_LINE_RASTERIZATION_FEATURES_EXT};
  VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
  if (d.line_rasterization) features.pNext = &line_features;
  vkGetPhysicalDeviceFeatures2(pd, &features);

  const VkPhysicalDeviceLimits& limits = base.limits;
  d.name = base.deviceName;
  d.type = type_text(base.deviceType);
  d.vendor_id = base.vendorID;
  d.api_version = version_text(base.apiVersion);
  d.driver_version = driver_version_text(base.vendorID, base.driverVersion);
  if (has_driver_props) {
    d.driver = std::string(driver.driverName) + " " + driver.driverInfo;
    d.llvmpipe = driver.driverID == VK_DRIVER_ID_MESA_LLVMPIPE;
  } else {
    d.driver = "driver " + d.driver_version;
    d.llvmpipe = base.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU &&
                 d.name.find("llvmpipe") != std::string::npos;
  }
  d.subpixel_bits = int(limits.subPixelPrecisionBits);
  d.strict_lines = limits.strictLines;
  if (d.line_rasterization) {
    d.line_subpixel_bits = int(line_props.lineSubPixelPrecisionBits);
    d.rectangular_lines = line_features.rectangularLines;
    d.bresenham_lines = line_features.bresenhamLines;
    d.smooth_lines = line_features.smoothLines;
  }
  d.timestamp_period_ns = limits.timestampPeriod;
  for (int s : {64, 32, 16, 8, 4, 2})
    if (limits.framebufferColorSampleCounts & VkSampleCountFlags(s)) {
      d.max_samples = s;
      break;
    }
  d.precise_occlusion = features.features.occlusionQueryPrecise;

  vkGetPhysicalDeviceQueueFamilyProperties(pd, &n, nullptr);
  std::vector<VkQueueFamilyProperties> families(n);
  vkGetPhysicalDeviceQueueFamilyProperties(pd, &n, families.data());
  *graphics_family = UINT32_MAX;
  for (uint32_t i = 0; i < n; ++i)
    if (families[i].queueFlags & VK_QUEUE_GRAPHICS_BIT) {
      *graphics_family = i;
      d.timestamp_valid_bits = int(families[i].timestampValidBits);
      d.timestamps = d.timestamp_valid_bits > 0;
      d.queue_computes = (families[i].queueFlags & VK_QUEUE_COMPUTE_BIT) != 0;
      break;
    }
  return d;
}

std::vector<VkPhysicalDevice> physical_devices(VkInstance instance) {
  uint32_t n = 0;
  vk_check(vkEnumeratePhysicalDevices(instance, &n, nullptr), "vkEnumeratePhysicalDevices");
  std::vector<VkPhysicalDevice> out(n);
  vk_check(vkEnumeratePhysicalDevices(instance, &n, out.data()), "vkEnumeratePhysicalDevices");
  out.resize(n);
  return out;
}

std::string device_list(const std::vector<VulkanDeviceInfo>& devices) {
  std::string out;
  for (const VulkanDeviceInfo& d : devices)
    out +=
        (out.empty() ? "" : ", ") + std::to_string(d.index) + ": " + d.name + " (" + d.type + ")";
  return out.empty() ? "none" : out;
}

}  // namespace

void vk_check(VkResult r, const char* what) {
  if (r != VK_SUCCESS)
    throw std::runtime_error(std::string(what) + " failed with VkResult " + std::to_string(int(r)));
}

double timestamp_interval_us(uint64_t begin, uint64_t end, int valid_bits, double period_ns) {
  if (valid_bits <= 0) return std::numeric_limits<double>::quiet_NaN();
  if (valid_bits < 64) {
    const uint64_t mask = (uint64_t(1) << valid_bits) - 1;
    return double((end - begin) & mask) * period_ns / 1e3;  // modular: one wrap comes out right
  }
  if (end < begin) return std::numeric_limits<double>::quiet_NaN();
  return double(end - begin) * period_ns / 1e3;
}

std::string VulkanDeviceInfo::line_modes() const {
  std::string out;
  if (rectangular_lines) out += "rectangular";
  if (bresenham_lines) out += std::string(out.empty() ? "" : ", ") + "bresenham";
  if (smooth_lines) out += std::string(out.empty() ? "" : ", ") + "smooth";
  return out.empty() ? "default" : out;
}

std::vector<VulkanDeviceInfo> list_vulkan_devices() {
  const VkInstance instance = process_instance(nullptr);
  std::vector<VulkanDeviceInfo> out;
  uint32_t family = 0;
  const std::vector<VkPhysicalDevice> pds = physical_devices(instance);
  for (size_t i = 0; i < pds.size(); ++i) out.push_back(describe(pds[i], int(i), &family));
  return out;
}

const VulkanDeviceInfo& choose_vulkan_device(const rundir::PlatformSpec& spec,
                                             const std::vector<VulkanDeviceInfo>& devices) {
  const VulkanDeviceInfo* chosen = nullptr;
  if (spec.device >= 0) {
    if (size_t(spec.device) >= devices.size())
      throw util::UserError("platform " + spec.name + ": there is no Vulkan device " +
                            std::to_string(spec.device) +
                            " on this machine (devices: " + device_list(devices) + ")");
    chosen = &devices[spec.device];
  } else {
    for (const VulkanDeviceInfo& d : devices)
      if (spec.mesa_driver == "lavapipe" ? d.llvmpipe : d.type != "cpu") {
        chosen = &d;
        break;
      }
    if (!chosen)
      throw util::UserError("platform " + spec.name + ": " +
                            (spec.mesa_driver == "lavapipe"
                                 ? "the Vulkan loader finds no lavapipe (apt-get install "
                                   "mesa-vulkan-drivers)"
                                 : "no Vulkan device here is a GPU (name one as vk-device:N)") +
                            "; devices: " + device_list(devices));
  }
  const std::string which =
      "Vulkan device " + std::to_string(chosen->index) + " (" + chosen->name + ")";
  if (spec.line_mode == rundir::PlatformSpec::LineMode::kBresenham && !chosen->bresenham_lines)
    throw util::UserError(
        "platform " + spec.name + " draws Bresenham lines, but " + which +
        (chosen->line_rasterization
             ? " offers only these modes of VK_EXT_line_rasterization: " + chosen->line_modes()
             : " lacks VK_EXT_line_rasterization"));
  if (spec.samples > chosen->max_samples)
    throw util::UserError("platform " + spec.name + " needs " + std::to_string(spec.samples) +
                          " samples per pixel, but " + which + " offers at most " +
                          std::to_string(chosen->max_samples));
  return *chosen;
}

VulkanContext::VulkanContext(const rundir::PlatformSpec& spec) {
  if (!spec.draws_with_vulkan())
    throw std::logic_error("VulkanContext: " + spec.name + " does not draw with Vulkan");
  try {
    instance_ = process_instance(&spec);
  } catch (const util::UserError& e) {
    throw util::UserError("platform " + spec.name + ": " + e.what());
  }
  const std::vector<VkPhysicalDevice> pds = physical_devices(instance_);
  std::vector<VulkanDeviceInfo> devices;
  std::vector<uint32_t> families(pds.size());
  for (size_t i = 0; i < pds.size(); ++i) devices.push_back(describe(pds[i], int(i), &families[i]));
  info_ = choose_vulkan_device(spec, devices);
  physical_ = pds[info_.index];
  queue_family_ = families[info_.index];
  if (queue_family_ == UINT32_MAX)
    throw util::UserError("platform " + spec.name + ": Vulkan device " +
                          std::to_string(info_.index) + " (" + info_.name +
                          ") has no graphics queue");

  const float priority = 1;
  VkDeviceQueueCreateInfo queue{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  queue.queueFamilyIndex = queue_family_;
  queue.queueCount = 1;
  queue.pQueuePriorities = &priority;
  VkPhysicalDeviceFeatures features{};
  features.occlusionQueryPrecise = info_.precise_occlusion;
  VkPhysicalDeviceLineRasterizationFeaturesEXT line{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_LINE_RASTERIZATION_FEATURES_EXT};
  line.bresenhamLines = spec.line_mode == rundir::PlatformSpec::LineMode::kBresenham;
  std::vector<const char*> extensions;
  VkDeviceCreateInfo info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
  if (line.bresenhamLines) {
    extensions.push_back(VK_EXT_LINE_RASTERIZATION_EXTENSION_NAME);
    info.pNext = &line;
  }
  info.queueCreateInfoCount = 1;
  info.pQueueCreateInfos = &queue;
  info.enabledExtensionCount = uint32_t(extensions.size());
  info.ppEnabledExtensionNames = extensions.data();
  info.pEnabledFeatures = &features;
  vk_check(vkCreateDevice(physical_, &info, nullptr, &device_), "vkCreateDevice");
  vkGetDeviceQueue(device_, queue_family_, 0, &queue_);
}

VulkanContext::~VulkanContext() {
  if (device_) {
    vkDeviceWaitIdle(device_);
    vkDestroyDevice(device_, nullptr);
  }
}

uint32_t VulkanContext::memory_type(uint32_t type_bits, VkMemoryPropertyFlags required) const {
  VkPhysicalDeviceMemoryProperties props{};
  vkGetPhysicalDeviceMemoryProperties(physical_, &props);
  for (uint32_t i = 0; i < props.memoryTypeCount; ++i)
    if ((type_bits & (1u << i)) && (props.memoryTypes[i].propertyFlags & required) == required)
      return i;
  throw std::runtime_error("Vulkan device " + info_.name + ": no memory type with properties " +
                           std::to_string(required));
}

std::string VulkanContext::backend() const {
  return "Vulkan device " + std::to_string(info_.index) + " (" + info_.driver + ")";
}

}  // namespace ra::platforms
