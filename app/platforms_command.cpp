// `renderaudit platforms [--json]`: every platform this machine can draw through, with its
// driver's identity, and every one it cannot, with the reason and the packages that would provide
// it. Each GL platform is probed in its own child process (platforms/platform_probe.h).
#include <cstdio>
#include <nlohmann/json.hpp>

#include "app/commands.h"
#include "platforms/gl_context.h"
#include "platforms/platform_probe.h"
#include "util/errors.h"

namespace ra::app {
namespace {

// The fixed-name platforms, then egl-device:N for every EGL device (when EGL can list them) and
// vk-device:N for every Vulkan device (when the Vulkan loader can list them).
std::vector<rundir::PlatformSpec> platforms_to_probe(std::string* device_note,
                                                     std::string* vulkan_note) {
  std::vector<rundir::PlatformSpec> specs;
  for (const rundir::PlatformSpec& s : rundir::platform_specs())
    if (s.backend != rundir::Backend::kFaulty) specs.push_back(s);
  try {
    for (const platforms::EglDevice& d : platforms::list_egl_devices_in_child()) {
      rundir::PlatformSpec s = *rundir::find_platform("egl-device:" + std::to_string(d.index));
      s.description = "EGL device " + std::to_string(d.index) +
                      (d.software           ? ": Mesa's software device (EGL_MESA_device_software)"
                       : d.drm_node.empty() ? ""
                                            : " (" + d.drm_node + ")");
      specs.push_back(s);
    }
  } catch (const util::UserError& e) {
    *device_note = e.what();
  }
  try {
    // in a child: this process forks for every probe after this (platform_probe.h)
    for (const platforms::VulkanDeviceInfo& d : platforms::list_vulkan_devices_in_child()) {
      rundir::PlatformSpec s = *rundir::find_platform("vk-device:" + std::to_string(d.index));
      s.description = "Vulkan device " + std::to_string(d.index) + " (" + d.type + ")";
      specs.push_back(s);
    }
  } catch (const util::UserError& e) {
    *vulkan_note = e.what();
  }
  return specs;
}

}  // namespace

void register_platforms_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand(
      "platforms",
      "List the platforms this machine can draw through (GL_RENDERER, GL_VERSION, GL_VENDOR,\n"
      "GL_SUBPIXEL_BITS, GL_MAX_SAMPLES, timer queries; for Vulkan the device, API and driver\n"
      "version, subPixelPrecisionBits, lineSubPixelPrecisionBits, strictLines, line modes,\n"
      "timestamps) and, for each one it cannot, why and which packages would provide it. Each\n"
      "driver platform is brought up in a child process.");
  struct Options {
    bool as_json = false;
    bool embedded_default = false;
    std::vector<std::string> names;
  };
  const auto opts = std::make_shared<Options>();  // alive as long as the callbacks
  cmd->add_option("names", opts->names,
                  "probe only these platforms; PLATFORM@BUILD draws with a build of the build "
                  "cache (`renderaudit builds list`), e.g. osmesa-llvmpipe@mesa-25.0.7");
  cmd->add_flag("--json", opts->as_json, "one JSON document on stdout");
  cmd->add_flag("--embedded-default", opts->embedded_default,
                "print the platform `make` draws with: osmesa-llvmpipe where OSMesa works, else "
                "egl-llvmpipe (the same driver through EGL); exit 2 with the reasons when neither "
                "can draw");
  cmd->callback([opts, &exit_code] {
    if (opts->embedded_default) {
      std::string reasons;
      for (const char* name : {"osmesa-llvmpipe", "egl-llvmpipe"}) {
        const platforms::PlatformProbe p = platforms::probe_platform(*rundir::find_platform(name));
        if (p.available) {
          std::printf("%s\n", name);
          exit_code = kExitOk;
          return;
        }
        reasons += std::string("\n  ") + name + ": " + p.reason;
      }
      throw util::UserError("neither embedded platform can draw on this machine:" + reasons);
    }
    std::string device_note, vulkan_note;
    std::vector<rundir::PlatformSpec> specs;
    if (opts->names.empty()) {
      specs = platforms_to_probe(&device_note, &vulkan_note);
    } else {
      for (const std::string& n : opts->names) {
        const std::optional<rundir::PlatformSpec> s = rundir::find_platform(n);
        if (!s)
          throw util::UserError("unknown platform '" + n +
                                "' (allowed: " + rundir::platform_names() + ")");
        specs.push_back(*s);
      }
    }
    nlohmann::json list = nlohmann::json::array();
    for (const rundir::PlatformSpec& spec : specs) {
      const platforms::PlatformProbe p = platforms::probe_platform(spec);
      nlohmann::json j = {
          {"name", spec.name}, {"description", spec.description}, {"available", p.available}};
      if (p.available) {
        j["renderer"] = p.driver.renderer;
        j["version"] = p.driver.version;
        j["vendor"] = p.driver.vendor;
        j["subpixel_bits"] = p.driver.subpixel_bits;
        j["max_samples"] = p.driver.max_samples;
        j["timer_query"] = p.driver.timer_query;
        j["backend"] = p.driver.backend;
        if (spec.draws_with_vulkan()) {
          j["line_subpixel_bits"] = p.driver.line_subpixel_bits;
          j["strict_lines"] = p.driver.strict_lines;
          j["line_modes"] = p.driver.line_modes;
          j["line_mode"] = p.driver.line_mode;
        }
      } else {
        j["reason"] = p.reason;
        j["packages"] = rundir::packages_for(spec);
      }
      list.push_back(j);
    }
    if (opts->as_json) {
      nlohmann::json doc = {{"platforms", list}};
      if (!device_note.empty()) doc["egl_devices"] = device_note;
      if (!vulkan_note.empty()) doc["vulkan_devices"] = vulkan_note;
      std::printf("%s\n", doc.dump(2).c_str());
    } else {
      for (const nlohmann::json& j : list) {
        const std::string name = j["name"];
        if (j["available"] && j["backend"] == "none") {
          std::printf("%-22s %s\n", name.c_str(), j["description"].get<std::string>().c_str());
        } else if (j["available"] && j.contains("line_modes")) {
          std::printf(
              "%-22s %s | %s | subPixelPrecisionBits %d | lineSubPixelPrecisionBits %d | "
              "strictLines %d | line modes: %s (draws %s) | max samples %d | timestamps "
              "%s | %s\n",
              name.c_str(), j["renderer"].get<std::string>().c_str(),
              j["version"].get<std::string>().c_str(), j["subpixel_bits"].get<int>(),
              j["line_subpixel_bits"].get<int>(), j["strict_lines"].get<bool>() ? 1 : 0,
              j["line_modes"].get<std::string>().c_str(), j["line_mode"].get<std::string>().c_str(),
              j["max_samples"].get<int>(), j["timer_query"].get<bool>() ? "yes" : "no",
              j["backend"].get<std::string>().c_str());
        } else if (j["available"]) {
          std::printf(
              "%-22s %s | %s | %s | subpixel bits %d | max samples %d | timer query %s | %s\n",
              name.c_str(), j["renderer"].get<std::string>().c_str(),
              j["version"].get<std::string>().c_str(), j["vendor"].get<std::string>().c_str(),
              j["subpixel_bits"].get<int>(), j["max_samples"].get<int>(),
              j["timer_query"].get<bool>() ? "yes" : "no", j["backend"].get<std::string>().c_str());
        } else {
          const std::string reason = j["reason"];
          const std::string packages = j["packages"];
          std::printf("%-22s cannot draw here: %s%s\n", name.c_str(), reason.c_str(),
                      reason.find("apt-get") != std::string::npos || packages.empty()
                          ? ""
                          : (" (needs: " + packages + ")").c_str());
        }
      }
      if (!device_note.empty()) std::printf("EGL devices: %s\n", device_note.c_str());
      if (!vulkan_note.empty()) std::printf("Vulkan devices: %s\n", vulkan_note.c_str());
    }
    exit_code = kExitOk;
  });
}

}  // namespace ra::app
