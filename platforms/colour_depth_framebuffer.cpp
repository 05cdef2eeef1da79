#include "platforms/colour_depth_framebuffer.h"

#include <stdexcept>

#include "util/errors.h"

namespace ra::platforms {

ColourDepthFramebuffer create_colour_depth_framebuffer(const GlApi& gl, int width, int height,
                                                       const std::string& platform) {
  GLint max_size = 0;
  gl.GetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &max_size);
  if (width > max_size || height > max_size)
    throw UserError("window " + std::to_string(width) + "x" + std::to_string(height) +
                    " exceeds " + platform + "'s GL_MAX_RENDERBUFFER_SIZE " +
                    std::to_string(max_size));
  ColourDepthFramebuffer f;
  gl.GenFramebuffers(1, &f.framebuffer);
  gl.BindFramebuffer(GL_FRAMEBUFFER, f.framebuffer);
  gl.GenRenderbuffers(1, &f.colour);
  gl.BindRenderbuffer(GL_RENDERBUFFER, f.colour);
  gl.RenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
  gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, f.colour);
  gl.GenRenderbuffers(1, &f.depth);
  gl.BindRenderbuffer(GL_RENDERBUFFER, f.depth);
  gl.RenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, width, height);
  gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, f.depth);
  if (gl.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw std::runtime_error("incomplete framebuffer (RGBA8 + DEPTH24) for " + platform);
  return f;
}

}  // namespace ra::platforms
