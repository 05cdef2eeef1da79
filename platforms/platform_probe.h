// Asking a platform whether it can draw here, before anything is written: each GL platform is
// brought up in a forked child (Mesa picks its driver once per process, and a driver that crashes
// takes only the child with it), which reports the driver's identity or why it cannot draw.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "platforms/gl_context.h"
#include "platforms/platform.h"
#include "platforms/vulkan_context.h"

namespace ra::platforms {

struct PlatformProbe {
  std::string name;
  bool available = false;
  DriverInfo driver;   // when available
  std::string reason;  // when not: the error, with the package that would provide it
};

// Probes one platform (the non-GL ones are always available). Never throws for a platform that
// cannot draw: that is the result.
PlatformProbe probe_platform(const rundir::PlatformSpec& spec);

// The Vulkan devices (index, name, type; platforms/vulkan_context.h), listed in a forked child:
// a process that has brought up a Vulkan driver must not fork later (NVIDIA's driver deadlocks
// in the child), and every probe forks. Throws ra::util::UserError with the child's reason when it
// cannot list them (no loader, no driver).
std::vector<VulkanDeviceInfo> list_vulkan_devices_in_child();
// The EGL devices (platforms/gl_context.h), listed in a forked child for the same reason: a
// parent that has loaded NVIDIA's EGL driver leaves every later forked probe without a Vulkan or
// EGL driver. Throws ra::util::UserError with the reason when EGL cannot list them.
std::vector<EglDevice> list_egl_devices_in_child();

// Throws ra::util::UserError listing every GL platform of `names` that cannot draw here, with each one's
// reason (the run then stops before its directory is written). Unknown names are the experiment
// parser's business and are skipped here.
void require_platforms_draw(const std::vector<std::string>& names, const std::string& context);
// The same for resolved platforms (an experiment's driver builds: rundir/experiment.h).
void require_platforms_draw(const std::vector<rundir::PlatformSpec>& specs, const std::string& context);

}  // namespace ra::platforms
