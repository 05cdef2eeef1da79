// Platform names: what each name in an experiment file draws through. Only values from this table
// ever reach Mesa's environment (GALLIUM_DRIVER=swrast made OSMesa 22.3 segfault).
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace ra::rundir {

// The first words of every refusal to draw with another driver than the one that made a run's
// records (platforms/renderer_check.h); the processes that start drawers (the coordinator, the
// audit's re-renders) recognise a child's refusal by them.
inline constexpr const char* kDriverMismatch = "driver mismatch";

// How a platform draws.
enum class Backend {
  kOsmesa,          // Mesa's OSMesa (libOSMesa.so.8); the driver picked by GALLIUM_DRIVER
  kEglSurfaceless,  // Mesa's EGL_MESA_platform_surfaceless; the driver picked by the environment
  kEglDevice,       // a device of EGL_EXT_platform_device: a GPU through its vendor's driver
  kVulkan,          // a Vulkan physical device through the loader (libvulkan.so.1)
  kReference,       // the project's exact rasterizer (no driver)
  kFaulty,          // test platform: the reference plus injected faults
};

struct PlatformSpec {
  std::string name;  // as written in experiment files
  std::string description;
  Backend backend = Backend::kReference;
  // The Mesa driver the environment asks for ("llvmpipe", "softpipe", "zink"); empty for EGL
  // devices (the device decides) and the non-GL platforms.
  std::string mesa_driver;
  // Samples per pixel of the multisample colour buffer drawn into: 0 for the aliased platforms
  // (one sample at the pixel centre, the paper's condition), 4 for the antialiasing condition
  // (`*-msaa4`, see platforms/readback_measurement.cpp).
  int samples = 0;
  // kEglDevice: the index among EGL devices (`egl-device:N`); -1 for `egl-device`, the first
  // device that is not Mesa's software one.
  int device = -1;
  // `PLATFORM@BUILD`: the driver build it draws with (rundir/build_record.h) and the folder
  // that build's files were unpacked into; both empty for the installed driver.
  std::string build = "";
  std::string build_dir = "";

  // kVulkan: how lines are rasterized. kDefault is the pipeline's default (rectangles where the
  // device has strictLines, else parallelograms or Bresenham); kBresenham asks for
  // VK_EXT_line_rasterization's Bresenham mode (diamond-exit, as GL).
  enum class LineMode { kDefault, kBresenham };
  LineMode line_mode = LineMode::kDefault;

  bool draws_with_gl() const {
    return backend == Backend::kOsmesa || backend == Backend::kEglSurfaceless ||
           backend == Backend::kEglDevice;
  }
  bool draws_with_vulkan() const { return backend == Backend::kVulkan; }
  // A driver draws (GL or Vulkan), not the project's own rasterizer: what is probed, whose
  // identity goes into the run's driver file and is checked by every process that draws.
  bool draws_with_driver() const { return draws_with_gl() || draws_with_vulkan(); }
};

// The platforms with a fixed name, in the order messages list them (`egl-device:N`,
// `egl-device:N-msaa4`, `vk-device:N`, `vk-device:N-bresenham` and `vk-device:N-msaa4` are parsed
// by find_platform).
const std::vector<PlatformSpec>& platform_specs();
// The platform called `name`, or nullopt. `PLATFORM@BUILD` (an OSMesa or surfaceless EGL
// platform, or vk-lavapipe and its variants, BUILD of letters, digits and `._-`) is PLATFORM drawn with driver build BUILD, whose
// folder defaults to BUILD in the build cache (build_cache_dir()); an experiment's [builds] table
// may name another (rundir/experiment.h).
std::optional<PlatformSpec> find_platform(const std::string& name);
// Splits `PLATFORM@BUILD`; BUILD is empty for an unqualified name.
std::pair<std::string, std::string> split_build(const std::string& name);
// Whether `build` is a valid build name (1 to 64 of [A-Za-z0-9._-], not starting with '.' or '-').
bool is_build_name(const std::string& build);
std::string platform_names();  // "osmesa-llvmpipe, osmesa-softpipe, ..., egl-device:N"

// The aliased GL platforms (draws_with_gl, samples 0): the ones the timing, LOD and regulation
// studies draw on. A list for messages ("osmesa-llvmpipe, ..., egl-device:N"), and the test.
std::string aliased_gl_platform_names();
bool is_aliased_gl_platform(const std::string& name);

// Debian packages a back end needs, for messages ("libegl1 libegl-mesa0").
std::string packages_for(const PlatformSpec& spec);

}  // namespace ra::rundir
