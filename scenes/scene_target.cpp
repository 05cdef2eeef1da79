// The GL target of the studies' scenes (scene_target.h).
#include "scenes/scene_target.h"

#include <optional>

#include "util/errors.h"

namespace ra::scenes {
namespace {

rundir::PlatformSpec gl_platform(const std::string& platform, const std::string& purpose) {
  const std::optional<rundir::PlatformSpec> spec = rundir::find_platform(platform);
  if (!spec || !spec->draws_with_gl())
    throw util::UserError("platform '" + platform + "' has no GL driver" + purpose + " (allowed: " +
                          rundir::aliased_gl_platform_names() + ")");
  return *spec;
}

}  // namespace

SceneTarget::SceneTarget(const std::string& platform, const CameraSettings& cam,
                         const std::string& purpose)
    : spec_(gl_platform(platform, purpose)), cam_(cam) {
  context_ = platforms::create_gl_context(spec_);  // sets Mesa's environment and checks the driver
  const platforms::GlApi& gl = context_->gl();
  framebuffer_ = platforms::create_colour_depth_framebuffer(gl, cam.width, cam.height, platform);
  gl.Viewport(0, 0, cam.width, cam.height);
  gl.Enable(GL_DEPTH_TEST);
  gl.DepthFunc(GL_LESS);
  gl.MatrixMode(GL_PROJECTION);
  gl.LoadMatrixd(projection_of(cam).m.data());
  gl.MatrixMode(GL_MODELVIEW);
  gl.LoadIdentity();
}

std::string SceneTarget::gl_string(GLenum name) const {
  return reinterpret_cast<const char*>(gl().GetString(name));
}

void SceneTarget::set_viewpoint(const Viewpoint& vp) const {
  gl().MatrixMode(GL_MODELVIEW);
  gl().LoadMatrixd(look_at(vp).m.data());
}

void SceneTarget::fill_buffer(GLenum target, GLuint buffer, const void* data, std::size_t bytes,
                              GLenum usage) const {
  gl().BindBuffer(target, buffer);
  gl().BufferData(target, GLsizeiptr(bytes), data, usage);
}

GLuint SceneTarget::new_buffer(GLenum target, const void* data, std::size_t bytes,
                               GLenum usage) const {
  GLuint buffer = 0;
  gl().GenBuffers(1, &buffer);
  fill_buffer(target, buffer, data, bytes, usage);
  return buffer;
}

void SceneTarget::read_rgba(std::vector<uint8_t>& rgba) const {
  rgba.resize(std::size_t(cam_.width) * cam_.height * 4);
  gl().PixelStorei(GL_PACK_ALIGNMENT, 1);
  gl().ReadPixels(0, 0, cam_.width, cam_.height, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
}

}  // namespace ra::scenes
