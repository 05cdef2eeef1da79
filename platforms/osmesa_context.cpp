// A GL context through Mesa's OSMesa, loaded with dlopen (see gl_context.h). The window-system
// buffer is 1x1 and never drawn to: drawing goes to framebuffer objects (glFinish on OSMesa's own
// buffer copies the whole window into the caller's memory, about 150 us at 907x907).
#include <dlfcn.h>

#include <cstdlib>
#include <stdexcept>
#include <string>

#include "rundir/build_record.h"
#include "platforms/gl_context_backends.h"
#include "util/errors.h"

namespace ra::platforms {
namespace {

// OSMesa's interface (GL/osmesa.h), declared here so that the build does not need its header.
using OSMesaContext = struct osmesa_context*;
using CreateContextExt = OSMesaContext (*)(GLenum format, GLint depth_bits, GLint stencil_bits,
                                           GLint accum_bits, OSMesaContext share);
using MakeCurrent = GLboolean (*)(OSMesaContext, void* buffer, GLenum type, GLsizei width,
                                  GLsizei height);
using GetCurrentContext = OSMesaContext (*)();
using DestroyContext = void (*)(OSMesaContext);
using GetProcAddress = void* (*)(const char*);
constexpr GLenum kOsmesaRgba = GL_RGBA;

class OsmesaContext : public GlContext {
 public:
  explicit OsmesaContext(const rundir::PlatformSpec& spec) {
    // A driver build's own library; else RENDERAUDIT_LIBOSMESA, else the installed one.
    const std::string build_library =
        spec.build.empty() ? "" : rundir::build_library_dir(spec.build_dir) + "/libOSMesa.so.8";
    const char* library = std::getenv("RENDERAUDIT_LIBOSMESA");
    const bool named = build_library.empty() && library && *library;
    if (!build_library.empty()) library = build_library.c_str();
    if (!library || !*library) library = "libOSMesa.so.8";
    library_ = dlopen(library, RTLD_NOW | RTLD_LOCAL);
    if (!library_) {
      // when the variable chose the library, it is named: the package alone would mislead
      throw util::UserError(
          "platform " + spec.name + ": cannot load " + library + " (" + dlerror() +
          (named ? "), the library RENDERAUDIT_LIBOSMESA names; point it at an "
                   "OSMesa library or unset it (the default libOSMesa.so.8 comes "
                   "with: apt-get install "
                 : "); install it with: apt-get install ") +
          rundir::packages_for(spec) + (named ? ")" : "") + " (OSMesa was removed from Mesa 25.1; egl-" +
          spec.mesa_driver + " draws with the same driver through EGL)");
    }
    const auto symbol = [&](const char* name) {
      void* p = dlsym(library_, name);
      if (!p)
        throw util::UserError(std::string(library) + " lacks " + name + ": not an OSMesa library");
      return p;
    };
    create_ = reinterpret_cast<CreateContextExt>(symbol("OSMesaCreateContextExt"));
    make_current_ = reinterpret_cast<MakeCurrent>(symbol("OSMesaMakeCurrent"));
    get_current_ = reinterpret_cast<GetCurrentContext>(symbol("OSMesaGetCurrentContext"));
    destroy_ = reinterpret_cast<DestroyContext>(symbol("OSMesaDestroyContext"));
    const auto get_proc = reinterpret_cast<GetProcAddress>(symbol("OSMesaGetProcAddress"));

    context_ = create_(kOsmesaRgba, 0, 0, 0, nullptr);
    if (!context_) throw std::runtime_error("OSMesaCreateContextExt failed for " + spec.name);
    make_current();
    gl_.load([get_proc](const char* name) { return get_proc(name); });
    backend_ = std::string("OSMesa (") + library + ")";
  }

  ~OsmesaContext() override {
    if (context_) destroy_(context_);
    // the library stays loaded: Mesa's threads and atexit handlers may still refer to it
  }

  void make_current() override {
    if (get_current_() != context_ &&
        !make_current_(context_, winsys_pixel_, GL_UNSIGNED_BYTE, 1, 1))
      throw std::runtime_error("OSMesaMakeCurrent failed");
  }

 private:
  void* library_ = nullptr;
  CreateContextExt create_ = nullptr;
  MakeCurrent make_current_ = nullptr;
  GetCurrentContext get_current_ = nullptr;
  DestroyContext destroy_ = nullptr;
  OSMesaContext context_ = nullptr;
  unsigned char winsys_pixel_[4] = {};
};

}  // namespace

std::unique_ptr<GlContext> create_osmesa_context(const rundir::PlatformSpec& spec) {
  return std::make_unique<OsmesaContext>(spec);
}

}  // namespace ra::platforms
