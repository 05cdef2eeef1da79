// Choosing and checking a GL back end (see the header); the back ends are osmesa_context.cpp and
// egl_context.cpp.
#include "platforms/gl_context.h"

#include <cstdlib>
#include <stdexcept>

#include "platforms/driver_loading.h"
#include "platforms/gl_context_backends.h"
#include "util/errors.h"

namespace ra::platforms {
namespace {

// Mesa reads these when the process makes its first context. Only the validated values of
// PlatformSpec reach them.
void set_mesa_environment(const rundir::PlatformSpec& spec) {
  if (spec.backend == rundir::Backend::kEglDevice) return;  // the device decides
  if (spec.mesa_driver == "zink") {
    // zink is a Gallium driver loaded by the DRI loader; without a GPU it runs on lavapipe
    setenv("MESA_LOADER_DRIVER_OVERRIDE", "zink", 1);
    setenv("LIBGL_ALWAYS_SOFTWARE", "1", 1);
    unsetenv("GALLIUM_DRIVER");
    // Mesa's Vulkan device-select layer asks libwayland for a display, which prints "error:
    // XDG_RUNTIME_DIR is invalid or not set" (twice) when the variable is unset or empty.
    // Surfaceless drawing needs no display server: a folder that does not exist makes the
    // connection fail quietly, and changes nothing else (the layer's device order stays).
    if (const char* x = std::getenv("XDG_RUNTIME_DIR"); !x || !*x)
      setenv("XDG_RUNTIME_DIR", "/nonexistent/renderaudit-no-display-server", 1);
  } else {
    setenv("GALLIUM_DRIVER", spec.mesa_driver.c_str(), 1);
    // newer Mesa falls back to a software driver through EGL only when this is set
    if (spec.backend == rundir::Backend::kEglSurfaceless) setenv("LIBGL_ALWAYS_SOFTWARE", "1", 1);
  }
  // one-primitive frames: llvmpipe's thread hand-off costs more than the drawing
  setenv("LP_NUM_THREADS", "0", 0);
}

}  // namespace

std::unique_ptr<GlContext> create_gl_context(const rundir::PlatformSpec& spec) {
  if (!spec.draws_with_gl())
    throw std::logic_error("create_gl_context: " + spec.name + " does not draw with GL");
  set_mesa_environment(spec);
  load_driver_build(spec);  // the build's libraries by path, before anything asks by soname
  std::unique_ptr<GlContext> context = spec.backend == rundir::Backend::kOsmesa
                                           ? create_osmesa_context(spec)
                                           : create_egl_context(spec);
  // Mesa picks the driver at the process's first context: an earlier context (another study, the
  // figures) may have chosen another one, and a driver missing from the system makes Mesa fall
  // back silently. Refuse to measure on the wrong driver.
  if (!spec.mesa_driver.empty()) {
    const GLubyte* r = context->gl().GetString(GL_RENDERER);
    const std::string renderer = r ? reinterpret_cast<const char*>(r) : "";
    if (renderer.find(spec.mesa_driver) == std::string::npos) {
      std::string hint = "Mesa chose another driver before, or this one is not installed";
      if (spec.mesa_driver == "zink")
        hint = "zink needs a Vulkan driver: apt-get install mesa-vulkan-drivers libvulkan1";
      throw util::UserError("platform " + spec.name + " expects the Mesa driver '" +
                            spec.mesa_driver + "', but " + context->backend() +
                            " draws with GL_RENDERER '" + renderer + "' (" + hint + ")");
    }
  }
  return context;
}

}  // namespace ra::platforms
