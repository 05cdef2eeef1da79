// The GL target the studies draw their scenes into: a platform's context (platforms/gl_context.h),
// a framebuffer object of the window's size with RGBA8 colour and 24-bit depth
// (platforms/colour_depth_framebuffer.h), and the fixed-function state every study shares: the
// viewport of the window, depth test on (GL_LESS), the camera's projection and the modelview
// matrix of a viewpoint. What is drawn and how it is timed is the study's (timing/scene_renderer.h,
// terrain_lod/lod_renderer.h).
//
// Mesa picks its driver when the first context of a process is made: one platform per process.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "platforms/gl_api.h"
#include "platforms/colour_depth_framebuffer.h"
#include "platforms/gl_context.h"
#include "rundir/platform_spec.h"
#include "scenes/camera.h"
#include "scenes/scene.h"

namespace ra::scenes {

class SceneTarget {
 public:
  // Makes the context of `platform` (sets Mesa's environment and checks the driver) and the
  // framebuffer, and sets the shared state; the modelview matrix is the identity. `purpose`
  // completes the message for a platform without a GL driver: "platform 'P' has no GL
  // driver<purpose> (allowed: ...)". Throws ra::util::UserError for such a platform or a window
  // the driver cannot hold, std::runtime_error when GL fails.
  SceneTarget(const std::string& platform, const CameraSettings& cam,
              const std::string& purpose = "");
  SceneTarget(const SceneTarget&) = delete;
  SceneTarget& operator=(const SceneTarget&) = delete;

  const platforms::GlApi& gl() const { return context_->gl(); }
  platforms::GlContext& context() { return *context_; }
  const rundir::PlatformSpec& spec() const { return spec_; }
  const CameraSettings& camera() const { return cam_; }

  // glGetString(name) as text.
  std::string gl_string(GLenum name) const;

  // Sets the modelview matrix of `vp` (the projection is the camera's).
  void set_viewpoint(const Viewpoint& vp) const;

  // Binds `buffer` to `target` (GL_ARRAY_BUFFER, GL_ELEMENT_ARRAY_BUFFER) and fills it with
  // `bytes` bytes of `data`.
  void fill_buffer(GLenum target, GLuint buffer, const void* data, std::size_t bytes,
                   GLenum usage) const;
  // A new buffer object, bound to `target` and filled as fill_buffer does.
  GLuint new_buffer(GLenum target, const void* data, std::size_t bytes, GLenum usage) const;

  // The framebuffer's colour: width * height RGBA8, rows bottom-up, into `rgba` (resized).
  void read_rgba(std::vector<uint8_t>& rgba) const;

 private:
  rundir::PlatformSpec spec_;
  CameraSettings cam_;
  std::unique_ptr<platforms::GlContext> context_;
  platforms::ColourDepthFramebuffer framebuffer_;
};

}  // namespace ra::scenes
