// Probing platforms in forked children (see the header).
#include "platforms/platform_probe.h"

#include <unistd.h>

#include <filesystem>

#include "platforms/gl_context.h"
#include "util/errors.h"
#include "util/gl_child_process.h"

namespace ra::platforms {
namespace {

// A Vulkan platform's device, brought up as for drawing (vulkan_context.h), as JSON.
nlohmann::json vulkan_probe(const rundir::PlatformSpec& spec) {
  const std::unique_ptr<Platform> platform = create_vulkan_platform(spec);
  const DriverInfo d = platform->driver_info();
  return nlohmann::json{{"renderer", d.renderer},
                        {"version", d.version},
                        {"vendor", d.vendor},
                        {"subpixel_bits", d.subpixel_bits},
                        {"max_samples", d.max_samples},
                        {"timer_query", d.timer_query},
                        {"backend", d.backend},
                        {"line_subpixel_bits", d.line_subpixel_bits},
                        {"strict_lines", d.strict_lines},
                        {"line_modes", d.line_modes},
                        {"line_mode", d.line_mode}};
}

}  // namespace

PlatformProbe probe_platform(const rundir::PlatformSpec& spec) {
  PlatformProbe out;
  out.name = spec.name;
  if (!spec.draws_with_driver()) {
    out.available = true;
    out.driver.renderer = spec.backend == rundir::Backend::kReference ? "renderaudit reference rasterizer"
                                                              : "renderaudit faulty test platform";
    out.driver.backend = "none";
    return out;
  }
  const std::string scratch = std::filesystem::temp_directory_path().string();
  const std::string name = "renderaudit-probe-" + std::to_string(::getpid()) + "-" + spec.name;
  try {
    const nlohmann::json j = util::run_in_child(scratch, name, [&spec]() {
      if (spec.draws_with_vulkan()) return vulkan_probe(spec);
      const std::unique_ptr<GlContext> context = create_gl_context(spec);
      const GlApi& gl = context->gl();
      const auto text = [&gl](GLenum what) {
        const GLubyte* s = gl.GetString(what);
        return std::string(s ? reinterpret_cast<const char*>(s) : "");
      };
      GLint subpixel_bits = 0, max_samples = 0;
      gl.GetIntegerv(GL_SUBPIXEL_BITS, &subpixel_bits);
      gl.GetIntegerv(GL_MAX_SAMPLES, &max_samples);
      const std::string extensions = text(GL_EXTENSIONS);
      if (spec.samples > max_samples) {
        throw util::UserError(spec.name + " needs " + std::to_string(spec.samples) +
                              " samples per pixel, but " + text(GL_RENDERER) +
                              " has GL_MAX_SAMPLES " + std::to_string(max_samples));
      }
      return nlohmann::json{
          {"renderer", text(GL_RENDERER)},
          {"version", text(GL_VERSION)},
          {"vendor", text(GL_VENDOR)},
          {"subpixel_bits", subpixel_bits},
          {"max_samples", max_samples},
          {"timer_query", extensions.find("GL_ARB_timer_query") != std::string::npos},
          {"backend", context->backend()}};
    });
    out.available = true;
    out.driver.renderer = j.value("renderer", "");
    out.driver.version = j.value("version", "");
    out.driver.vendor = j.value("vendor", "");
    out.driver.subpixel_bits = j.value("subpixel_bits", 0);
    out.driver.max_samples = j.value("max_samples", 0);
    out.driver.timer_query = j.value("timer_query", false);
    out.driver.backend = j.value("backend", "");
    out.driver.line_subpixel_bits = j.value("line_subpixel_bits", 0);
    out.driver.strict_lines = j.value("strict_lines", false);
    out.driver.line_modes = j.value("line_modes", "");
    out.driver.line_mode = j.value("line_mode", "");
  } catch (const util::ChildProcessError& e) {
    out.reason = e.what();
    for (const std::string& prefix : {spec.name + ": ", "platform " + spec.name + ": "})
      if (out.reason.compare(0, prefix.size(), prefix) == 0)  // the caller names the platform
        out.reason.erase(0, prefix.size());
  }
  return out;
}

std::vector<VulkanDeviceInfo> list_vulkan_devices_in_child() {
  const std::string scratch = std::filesystem::temp_directory_path().string();
  const std::string name = "renderaudit-vulkan-devices-" + std::to_string(::getpid());
  nlohmann::json j;
  try {
    j = util::run_in_child(scratch, name, []() {
      nlohmann::json list = nlohmann::json::array();
      for (const VulkanDeviceInfo& d : list_vulkan_devices())
        list.push_back({{"index", d.index}, {"name", d.name}, {"type", d.type}});
      return list;
    });
  } catch (const util::ChildProcessError& e) {
    throw util::UserError(e.what());
  }
  std::vector<VulkanDeviceInfo> out;
  for (const nlohmann::json& d : j) {
    VulkanDeviceInfo info;
    info.index = d.value("index", 0);
    info.name = d.value("name", "");
    info.type = d.value("type", "");
    out.push_back(info);
  }
  return out;
}

std::vector<EglDevice> list_egl_devices_in_child() {
  const std::string scratch = std::filesystem::temp_directory_path().string();
  const std::string name = "renderaudit-egl-devices-" + std::to_string(::getpid());
  nlohmann::json j;
  try {
    j = util::run_in_child(scratch, name, []() {
      nlohmann::json list = nlohmann::json::array();
      for (const EglDevice& d : list_egl_devices())
        list.push_back({{"index", d.index}, {"extensions", d.extensions},
                        {"drm_node", d.drm_node}, {"software", d.software}});
      return list;
    });
  } catch (const util::ChildProcessError& e) {
    throw util::UserError(e.what());
  }
  std::vector<EglDevice> out;
  for (const nlohmann::json& d : j) {
    EglDevice device;
    device.index = d.value("index", 0);
    device.extensions = d.value("extensions", "");
    device.drm_node = d.value("drm_node", "");
    device.software = d.value("software", false);
    out.push_back(device);
  }
  return out;
}

void require_platforms_draw(const std::vector<std::string>& names, const std::string& context) {
  std::vector<rundir::PlatformSpec> specs;
  for (const std::string& name : names)
    if (const std::optional<rundir::PlatformSpec> spec = rundir::find_platform(name)) specs.push_back(*spec);
  require_platforms_draw(specs, context);
}

void require_platforms_draw(const std::vector<rundir::PlatformSpec>& specs, const std::string& context) {
  std::string problems;
  for (const rundir::PlatformSpec& spec : specs) {
    if (!spec.draws_with_driver()) continue;
    const PlatformProbe p = probe_platform(spec);
    if (!p.available) problems += "\n  " + spec.name + ": " + p.reason;
  }
  if (!problems.empty()) {
    throw util::UserError(context +
                          ": platform(s) that cannot draw on this machine (nothing was "
                          "written; `renderaudit platforms` lists what can):" +
                          problems);
  }
}

}  // namespace ra::platforms
