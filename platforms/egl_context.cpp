// A GL context through EGL, loaded with dlopen (see gl_context.h): Mesa's surfaceless platform
// (EGL_MESA_platform_surfaceless; Mesa's own CI, piglit and dEQP draw headless this way) or a
// device of EGL_EXT_platform_device (a GPU through its vendor's driver). Desktop GL
// (EGL_OPENGL_API), compatibility profile (the drawing uses the fixed-function pipeline), made
// current without a surface (EGL_KHR_surfaceless_context).
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <dlfcn.h>

#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <sstream>
#include <string>

#include "platforms/gl_context_backends.h"
#include "util/errors.h"

namespace ra::platforms {
namespace {

const char* egl_error_name(EGLint e) {
  switch (e) {
    case EGL_SUCCESS: return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS: return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT: return "EGL_BAD_CONTEXT";
    case EGL_BAD_CURRENT_SURFACE: return "EGL_BAD_CURRENT_SURFACE";
    case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
    case EGL_BAD_NATIVE_PIXMAP: return "EGL_BAD_NATIVE_PIXMAP";
    case EGL_BAD_NATIVE_WINDOW: return "EGL_BAD_NATIVE_WINDOW";
    case EGL_BAD_PARAMETER: return "EGL_BAD_PARAMETER";
    case EGL_BAD_SURFACE: return "EGL_BAD_SURFACE";
    case EGL_CONTEXT_LOST: return "EGL_CONTEXT_LOST";
    default: return "an unknown EGL error";
  }
}

// RENDERAUDIT_EGL_EXTENSION_OVERRIDE="-EGL_foo -EGL_bar" hides extensions the library has, as
// MESA_EXTENSION_OVERRIDE does for GL ones: to see what renderaudit does on an EGL without them.
// An entry without its '-' would hide nothing: refused rather than ignored.
bool hidden_by_override(const char* name) {
  const char* o = std::getenv("RENDERAUDIT_EGL_EXTENSION_OVERRIDE");
  if (!o) return false;
  std::istringstream entries(o);
  for (std::string entry; entries >> entry;)
    if (entry.size() < 2 || entry[0] != '-')
      throw util::UserError(
          "RENDERAUDIT_EGL_EXTENSION_OVERRIDE: entry '" + entry +
          "' does not hide "
          "an extension (allowed: -EXTENSION_NAME entries separated by spaces; an "
          "extension the library lacks cannot be added)");
  const std::string list = std::string(" ") + o + " ";
  return list.find(std::string(" -") + name + " ") != std::string::npos;
}

bool has_extension(const char* list, const char* name) {
  if (!list || hidden_by_override(name)) return false;
  const std::size_t n = std::strlen(name);
  for (const char* p = list; (p = std::strstr(p, name)) != nullptr; p += n) {
    const bool starts = p == list || p[-1] == ' ';
    const bool ends = p[n] == '\0' || p[n] == ' ';
    if (starts && ends) return true;
  }
  return false;
}

// libEGL's entry points. Core functions come from the library itself, extensions through
// eglGetProcAddress.
struct EglLibrary {
  std::string name;
  PFNEGLGETPROCADDRESSPROC get_proc = nullptr;
  PFNEGLGETERRORPROC get_error = nullptr;
  PFNEGLQUERYSTRINGPROC query_string = nullptr;
  PFNEGLINITIALIZEPROC initialize = nullptr;
  PFNEGLTERMINATEPROC terminate = nullptr;
  PFNEGLBINDAPIPROC bind_api = nullptr;
  PFNEGLCHOOSECONFIGPROC choose_config = nullptr;
  PFNEGLCREATECONTEXTPROC create_context = nullptr;
  PFNEGLDESTROYCONTEXTPROC destroy_context = nullptr;
  PFNEGLMAKECURRENTPROC make_current = nullptr;
  PFNEGLGETPLATFORMDISPLAYEXTPROC get_platform_display = nullptr;  // EGL_EXT_platform_base
  PFNEGLQUERYDEVICESEXTPROC query_devices = nullptr;              // EGL_EXT_device_enumeration
  PFNEGLQUERYDEVICESTRINGEXTPROC query_device_string = nullptr;   // EGL_EXT_device_query

  std::string error() const { return egl_error_name(get_error()); }
};

// Loads libEGL once per process; `who` names the platform in messages. RENDERAUDIT_LIBEGL picks
// another library (a vendor's loader, or a test's missing one).
const EglLibrary& egl_library(const std::string& who, const std::string& packages) {
  static EglLibrary lib;
  if (lib.get_proc) return lib;
  const char* name = std::getenv("RENDERAUDIT_LIBEGL");
  const bool named = name && *name;
  if (!named) name = "libEGL.so.1";
  void* handle = dlopen(name, RTLD_NOW | RTLD_LOCAL);
  if (!handle) {
    const std::string error = dlerror();
    if (named)  // the variable chose it: say so, not only which package has the default
      throw util::UserError(who + ": cannot load " + name + " (" + error +
                            "), the library "
                            "RENDERAUDIT_LIBEGL names; point it at an EGL library or unset it (the "
                            "default libEGL.so.1 comes with: apt-get install " +
                            packages + ")");
    throw util::UserError(who + ": cannot load " + name + " (" + error +
                          "); install it with: apt-get install " + packages);
  }
  const auto symbol = [&](const char* fn) {
    void* p = dlsym(handle, fn);
    if (!p) throw util::UserError(who + ": " + name + " lacks " + fn + ": not an EGL 1.4 library");
    return p;
  };
  EglLibrary l;
  l.name = name;
  l.get_proc = reinterpret_cast<PFNEGLGETPROCADDRESSPROC>(symbol("eglGetProcAddress"));
  l.get_error = reinterpret_cast<PFNEGLGETERRORPROC>(symbol("eglGetError"));
  l.query_string = reinterpret_cast<PFNEGLQUERYSTRINGPROC>(symbol("eglQueryString"));
  l.initialize = reinterpret_cast<PFNEGLINITIALIZEPROC>(symbol("eglInitialize"));
  l.terminate = reinterpret_cast<PFNEGLTERMINATEPROC>(symbol("eglTerminate"));
  l.bind_api = reinterpret_cast<PFNEGLBINDAPIPROC>(symbol("eglBindAPI"));
  l.choose_config = reinterpret_cast<PFNEGLCHOOSECONFIGPROC>(symbol("eglChooseConfig"));
  l.create_context = reinterpret_cast<PFNEGLCREATECONTEXTPROC>(symbol("eglCreateContext"));
  l.destroy_context = reinterpret_cast<PFNEGLDESTROYCONTEXTPROC>(symbol("eglDestroyContext"));
  l.make_current = reinterpret_cast<PFNEGLMAKECURRENTPROC>(symbol("eglMakeCurrent"));
  // client extensions: queried on EGL_NO_DISPLAY
  const char* client = l.query_string(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (has_extension(client, "EGL_EXT_platform_base")) {
    l.get_platform_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
        l.get_proc("eglGetPlatformDisplayEXT"));
  }
  if (has_extension(client, "EGL_EXT_device_enumeration") ||
      has_extension(client, "EGL_EXT_device_base")) {
    l.query_devices =
        reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(l.get_proc("eglQueryDevicesEXT"));
  }
  if (has_extension(client, "EGL_EXT_device_query") ||
      has_extension(client, "EGL_EXT_device_base")) {
    l.query_device_string =
        reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(l.get_proc("eglQueryDeviceStringEXT"));
  }
  lib = l;
  return lib;
}

std::vector<EGLDeviceEXT> query_devices(const EglLibrary& egl, const std::string& who) {
  if (!egl.query_devices || !egl.query_device_string) {
    throw util::UserError(who + ": " + egl.name +
                          " lacks EGL_EXT_device_enumeration / EGL_EXT_device_query (client "
                          "extensions), so no EGL device can be picked");
  }
  EGLint count = 0;
  if (!egl.query_devices(0, nullptr, &count))
    throw util::UserError(who + ": eglQueryDevicesEXT failed with " + egl.error());
  std::vector<EGLDeviceEXT> devices(static_cast<std::size_t>(count));
  if (count > 0 && !egl.query_devices(count, devices.data(), &count))
    throw util::UserError(who + ": eglQueryDevicesEXT failed with " + egl.error());
  devices.resize(static_cast<std::size_t>(count));
  return devices;
}

EglDevice describe_device(const EglLibrary& egl, EGLDeviceEXT device, int index) {
  EglDevice d;
  d.index = index;
  const char* ext = egl.query_device_string(device, EGL_EXTENSIONS);
  d.extensions = ext ? ext : "";
  d.software = has_extension(ext, "EGL_MESA_device_software");
  if (has_extension(ext, "EGL_EXT_device_drm")) {
    const char* node = egl.query_device_string(device, EGL_DRM_DEVICE_FILE_EXT);
    d.drm_node = node ? node : "";
  }
  return d;
}

std::string device_list_text(const std::vector<EglDevice>& devices) {
  if (devices.empty()) return "this machine has no EGL device";
  std::string out = "this machine's EGL devices: ";
  for (const EglDevice& d : devices) {
    out += (d.index ? "; " : "") + std::to_string(d.index) + ": " +
           (d.software ? "Mesa software (EGL_MESA_device_software)"
                       : (d.drm_node.empty() ? d.extensions : d.drm_node));
  }
  return out;
}

class EglContext : public GlContext {
 public:
  explicit EglContext(const rundir::PlatformSpec& spec) : egl_(egl_library(spec.name, rundir::packages_for(spec))) {
    const std::string& who = spec.name;
    if (!egl_.get_platform_display) {
      throw util::UserError(
          who + ": " + egl_.name +
          " lacks EGL_EXT_platform_base (client extension), which headless EGL needs");
    }
    if (spec.backend == rundir::Backend::kEglSurfaceless) {
      const char* client = egl_.query_string(EGL_NO_DISPLAY, EGL_EXTENSIONS);
      if (!has_extension(client, "EGL_MESA_platform_surfaceless")) {
        throw util::UserError(who + ": " + egl_.name +
                              " lacks EGL_MESA_platform_surfaceless: Mesa's EGL is not installed "
                              "(apt-get install " +
                              rundir::packages_for(spec) + ")");
      }
      display_ = egl_.get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY,
                                           nullptr);
      backend_ = "EGL surfaceless (Mesa, " + spec.mesa_driver + ")";
    } else {
      const std::vector<EGLDeviceEXT> devices = query_devices(egl_, who);
      std::vector<EglDevice> described;
      for (std::size_t i = 0; i < devices.size(); ++i)
        described.push_back(describe_device(egl_, devices[i], static_cast<int>(i)));
      int index = spec.device;
      if (index < 0) {
        for (const EglDevice& d : described)
          if (!d.software) {
            index = d.index;
            break;
          }
        if (index < 0) {
          throw util::UserError(who + ": no hardware EGL device (" + device_list_text(described) +
                                "); name one with egl-device:N, or use egl-llvmpipe for Mesa's "
                                "software renderer");
        }
      }
      if (index >= static_cast<int>(devices.size())) {
        throw util::UserError(who + ": no EGL device " + std::to_string(index) + " (" +
                              device_list_text(described) + ")");
      }
      display_ = egl_.get_platform_display(EGL_PLATFORM_DEVICE_EXT, devices[index], nullptr);
      const EglDevice& d = described[static_cast<std::size_t>(index)];
      backend_ = "EGL device " + std::to_string(index) +
                 (d.software ? " (Mesa software)" : d.drm_node.empty() ? "" : " (" + d.drm_node + ")");
    }
    if (display_ == EGL_NO_DISPLAY)
      throw util::UserError(who + ": eglGetPlatformDisplayEXT failed with " + egl_.error());
    EGLint major = 0, minor = 0;
    if (!egl_.initialize(display_, &major, &minor))
      throw util::UserError(who + ": eglInitialize failed with " + egl_.error() +
                            " (is the driver installed? apt-get install " + rundir::packages_for(spec) +
                            ")");
    const char* ext = egl_.query_string(display_, EGL_EXTENSIONS);
    if (!has_extension(ext, "EGL_KHR_surfaceless_context")) {
      throw util::UserError(who +
                            ": the display lacks EGL_KHR_surfaceless_context, which drawing "
                            "without a window needs");
    }
    if (!egl_.bind_api(EGL_OPENGL_API))
      throw util::UserError(who + ": eglBindAPI(EGL_OPENGL_API) failed with " + egl_.error() +
                            ": the driver offers no desktop OpenGL");
    EGLConfig config = EGL_NO_CONFIG_KHR;
    if (!has_extension(ext, "EGL_KHR_no_config_context") &&
        !has_extension(ext, "EGL_MESA_configless_context")) {
      const EGLint want[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
      EGLint n = 0;
      if (!egl_.choose_config(display_, want, &config, 1, &n) || n < 1)
        throw util::UserError(who + ": no EGL config renders desktop OpenGL (" + egl_.error() +
                              ")");
    }
    // No version asked: the highest compatibility-profile version the driver has.
    context_ = egl_.create_context(display_, config, EGL_NO_CONTEXT, nullptr);
    if (context_ == EGL_NO_CONTEXT)
      throw util::UserError(who + ": eglCreateContext failed with " + egl_.error());
    make_current();
    const PFNEGLGETPROCADDRESSPROC get_proc = egl_.get_proc;
    gl_.load([get_proc](const char* name) { return reinterpret_cast<void*>(get_proc(name)); });
  }

  ~EglContext() override {
    if (current_ == this) current_ = nullptr;
    if (context_ != EGL_NO_CONTEXT) {
      egl_.make_current(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
      egl_.destroy_context(display_, context_);
    }
    // eglTerminate is left out: Mesa may tear down state other contexts of the display share.
  }

  // glvnd's eglGetCurrentContext costs about 1.4 us (measured here), as much as drawing a small
  // primitive: the context this thread last made current is remembered instead. Every switch
  // between the project's contexts goes through here; the figures' VTK context lives in other
  // processes than the drawing ones.
  void make_current() override {
    if (current_ == this) return;
    if (!egl_.make_current(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_))
      throw std::runtime_error("eglMakeCurrent failed with " + egl_.error());
    current_ = this;
  }

 private:
  static thread_local const EglContext* current_;
  const EglLibrary& egl_;
  EGLDisplay display_ = EGL_NO_DISPLAY;
  EGLContext context_ = EGL_NO_CONTEXT;
};

thread_local const EglContext* EglContext::current_ = nullptr;

}  // namespace

std::unique_ptr<GlContext> create_egl_context(const rundir::PlatformSpec& spec) {
  return std::make_unique<EglContext>(spec);
}

std::vector<EglDevice> list_egl_devices() {
  const rundir::PlatformSpec device = *rundir::find_platform("egl-device");
  const EglLibrary& egl = egl_library("egl-device", rundir::packages_for(device));
  const std::vector<EGLDeviceEXT> devices = query_devices(egl, "egl-device");
  std::vector<EglDevice> out;
  for (std::size_t i = 0; i < devices.size(); ++i)
    out.push_back(describe_device(egl, devices[i], static_cast<int>(i)));
  return out;
}

}  // namespace ra::platforms
