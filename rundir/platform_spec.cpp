// The platform table and the parsing of `egl-device:N` (see the header).
#include "rundir/platform_spec.h"

#include <cctype>
#include <charconv>

#include "rundir/build_record.h"

namespace ra::rundir {

const std::vector<PlatformSpec>& platform_specs() {
  using B = Backend;
  static const std::vector<PlatformSpec> specs = {
      {"osmesa-llvmpipe", "Mesa OSMesa with the llvmpipe driver (the embedded default)", B::kOsmesa,
       "llvmpipe"},
      {"osmesa-softpipe", "Mesa OSMesa with the softpipe driver (an independent second platform)",
       B::kOsmesa, "softpipe"},
      {"reference", "the project's exact rasterizer following the GL rules (no driver)",
       B::kReference, ""},
      {"faulty", "test platform: the reference rasterizer plus the faults of [faults]", B::kFaulty,
       ""},
      // The antialiasing condition; after the first four, so that those keep their place in
      // messages. softpipe has no multisample variant: its GL_MAX_SAMPLES is 1 (Mesa 22.3.6), and
      // glRenderbufferStorageMultisample(4) fails there.
      {"osmesa-llvmpipe-msaa4",
       "Mesa OSMesa with llvmpipe, antialiased: 4x multisampling, coverage = samples lit / 4",
       B::kOsmesa, "llvmpipe", 4},
      {"egl-llvmpipe", "Mesa surfaceless EGL with llvmpipe (the same rasterizer as osmesa-llvmpipe)",
       B::kEglSurfaceless, "llvmpipe"},
      {"egl-softpipe", "Mesa surfaceless EGL with softpipe", B::kEglSurfaceless, "softpipe"},
      {"egl-zink", "Mesa surfaceless EGL with zink: GL on Vulkan (lavapipe where no GPU)",
       B::kEglSurfaceless, "zink"},
      {"egl-llvmpipe-msaa4", "Mesa surfaceless EGL with llvmpipe, antialiased: 4x multisampling",
       B::kEglSurfaceless, "llvmpipe", 4},
      {"egl-device", "the first hardware EGL device (EGL_EXT_platform_device): a GPU's own driver",
       B::kEglDevice, ""},
      {"egl-device-msaa4", "the first hardware EGL device, antialiased: 4x multisampling",
       B::kEglDevice, "", 4},
      // Vulkan (platforms/vulkan_device.cpp): Mesa's lavapipe, and any Vulkan device.
      {"vk-lavapipe",
       "Mesa's lavapipe (Vulkan on llvmpipe), default lines: rectangles under strictLines",
       B::kVulkan, "lavapipe"},
      {"vk-lavapipe-bresenham",
       "Mesa's lavapipe, Bresenham lines (VK_EXT_line_rasterization: diamond-exit, as GL)",
       B::kVulkan, "lavapipe", 0, -1, "", "", rundir::PlatformSpec::LineMode::kBresenham},
      {"vk-lavapipe-msaa4", "Mesa's lavapipe, antialiased: 4x multisampling", B::kVulkan,
       "lavapipe", 4},
      {"vk-device", "the first Vulkan device that is not a CPU: a GPU's own Vulkan driver",
       B::kVulkan, ""},
      {"vk-device-bresenham", "the first Vulkan GPU, Bresenham lines (VK_EXT_line_rasterization)",
       B::kVulkan, "", 0, -1, "", "", rundir::PlatformSpec::LineMode::kBresenham},
      {"vk-device-msaa4", "the first Vulkan GPU, antialiased: 4x multisampling", B::kVulkan, "",
       4},
  };
  return specs;
}

std::pair<std::string, std::string> split_build(const std::string& name) {
  const std::size_t at = name.find('@');
  if (at == std::string::npos) return {name, ""};
  return {name.substr(0, at), name.substr(at + 1)};
}

bool is_build_name(const std::string& build) {
  if (build.empty() || build.size() > 64 || build[0] == '.' || build[0] == '-') return false;
  for (char c : build)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '_' && c != '-')
      return false;
  return true;
}

std::optional<PlatformSpec> find_platform(const std::string& name) {
  if (const auto [base, build] = split_build(name); name.find('@') != std::string::npos) {
    std::optional<PlatformSpec> s = find_platform(base);
    if (!s || !is_build_name(build) ||
        (s->backend != Backend::kOsmesa && s->backend != Backend::kEglSurfaceless &&
         s->backend != Backend::kFaulty && s->mesa_driver != "lavapipe"))
      return std::nullopt;
    s->name = name;
    s->description += ", driver build " + build;
    s->build = build;
    s->build_dir = build_cache_dir() + "/" + build;
    return s;
  }
  for (const PlatformSpec& s : platform_specs())
    if (name == s.name) return s;
  // egl-device:N[-msaa4] and vk-device:N[-bresenham|-msaa4]
  const bool vulkan = name.compare(0, 10, "vk-device:") == 0;
  const std::string prefix = vulkan ? "vk-device:" : "egl-device:";
  if (name.compare(0, prefix.size(), prefix) != 0) return std::nullopt;
  std::string digits = name.substr(prefix.size());
  const auto strip = [&digits](const std::string& suffix) {
    const bool has = digits.size() > suffix.size() &&
                     digits.compare(digits.size() - suffix.size(), suffix.size(), suffix) == 0;
    if (has) digits.resize(digits.size() - suffix.size());
    return has;
  };
  const bool antialiased = strip("-msaa4");
  const bool bresenham = vulkan && !antialiased && strip("-bresenham");
  int index = -1;
  const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), index);
  if (digits.empty() || ec != std::errc() || end != digits.data() + digits.size() || index < 0 ||
      index > 255)
    return std::nullopt;
  PlatformSpec s;
  s.name = name;
  s.description = vulkan ? "Vulkan device " + std::to_string(index) + " (as `renderaudit platforms` lists it)"
                         : "EGL device " + std::to_string(index) + " (EGL_EXT_platform_device)";
  s.description += antialiased ? ", antialiased: 4x multisampling"
                   : bresenham ? ", Bresenham lines (VK_EXT_line_rasterization)"
                               : "";
  s.backend = vulkan ? Backend::kVulkan : Backend::kEglDevice;
  s.device = index;
  s.samples = antialiased ? 4 : 0;
  if (bresenham) s.line_mode = rundir::PlatformSpec::LineMode::kBresenham;
  return s;
}

std::string platform_names() {
  std::string out;
  for (const auto& s : platform_specs()) out += (out.empty() ? "" : ", ") + s.name;
  return out + ", egl-device:N, vk-device:N, and PLATFORM@BUILD for a driver build";
}

std::string aliased_gl_platform_names() {
  std::string out;
  for (const auto& s : platform_specs())
    if (s.draws_with_gl() && s.samples == 0) out += (out.empty() ? "" : ", ") + s.name;
  return out + ", egl-device:N";
}

bool is_aliased_gl_platform(const std::string& name) {
  const std::optional<PlatformSpec> spec = find_platform(name);
  return spec && spec->draws_with_gl() && spec->samples == 0;
}

std::string packages_for(const PlatformSpec& spec) {
  switch (spec.backend) {
    case Backend::kOsmesa:
      return "libosmesa6";
    case Backend::kEglSurfaceless:
      return spec.mesa_driver == "zink"
                 ? "libegl1 libegl-mesa0 libgl1-mesa-dri mesa-vulkan-drivers libvulkan1"
                 : "libegl1 libegl-mesa0 libgl1-mesa-dri";
    case Backend::kEglDevice:
      return "libegl1 and the GPU vendor's EGL driver (e.g. libnvidia-egl or libegl-mesa0)";
    case Backend::kVulkan:
      return spec.mesa_driver == "lavapipe"
                 ? "libvulkan1 mesa-vulkan-drivers"
                 : "libvulkan1 and the GPU vendor's Vulkan driver (e.g. libnvidia-gl or "
                   "mesa-vulkan-drivers)";
    case Backend::kReference:
    case Backend::kFaulty:
      return "";
  }
  return "";
}

}  // namespace ra::rundir
