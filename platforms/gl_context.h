// One place that makes a GL context for any drawing back end: Mesa's OSMesa, Mesa's surfaceless
// EGL, or a device of EGL_EXT_platform_device (a GPU through its vendor's driver). Every GL
// drawing in the project (the runner's platforms, the timing, LOD and regulation studies, the
// benchmark) goes through it, so that each back end is brought up, checked and described once.
//
// The context has no window-system framebuffer worth drawing to (OSMesa: 1x1 and never drawn; EGL:
// none, EGL_NO_SURFACE): callers draw into framebuffer objects of their own.
//
// Libraries are loaded when a platform asks for them (dlopen of libOSMesa.so.8 or libEGL.so.1), so
// that the project builds and runs where only one of them exists. Mesa picks its driver from the
// environment once per process; create_gl_context sets only validated values (PlatformSpec) and
// then checks that GL_RENDERER names the driver asked for.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "platforms/gl_api.h"
#include "rundir/platform_spec.h"

namespace ra::platforms {

class GlContext {
 public:
  virtual ~GlContext() = default;
  // Makes this context current on the calling thread (cheap when it already is).
  virtual void make_current() = 0;
  // The GL functions, fetched from this context's driver.
  const GlApi& gl() const { return gl_; }
  // "OSMesa (libOSMesa.so.8)", "EGL surfaceless (Mesa)", "EGL device 0 (EGL_NV_device_cuda)".
  const std::string& backend() const { return backend_; }

 protected:
  GlApi gl_;
  std::string backend_;
};

// Makes the context of a GL platform (spec.draws_with_gl()) current on the calling thread. Throws
// ra::util::UserError naming the platform, the reason (the EGL error name, the missing extension or
// library) and what to install; std::runtime_error when the driver fails in an unexpected way.
std::unique_ptr<GlContext> create_gl_context(const rundir::PlatformSpec& spec);

// One device of EGL_EXT_platform_device.
struct EglDevice {
  int index = 0;
  std::string extensions;  // the device's extension string (EGL_MESA_device_software, ...)
  std::string drm_node;    // EGL_DRM_DEVICE_FILE_EXT when the device has one
  bool software = false;   // EGL_MESA_device_software: Mesa's llvmpipe, not hardware
};

// The EGL devices of this machine. Throws ra::util::UserError when libEGL or EGL_EXT_device_enumeration
// is missing (with the reason).
std::vector<EglDevice> list_egl_devices();

}  // namespace ra::platforms
