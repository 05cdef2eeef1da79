// The framebuffer the studies draw into: a framebuffer object of RGBA8 colour and 24-bit depth of
// the window's size, bound for drawing and reading (no back end here has a window-system buffer
// worth drawing to; see gl_context.h).
#pragma once

#include <string>

#include "platforms/gl_api.h"

namespace ra::platforms {

struct ColourDepthFramebuffer {
  GLuint framebuffer = 0, colour = 0, depth = 0;  // GL names
};

// Creates and binds it in the current context. Throws ra::util::UserError when the window exceeds the
// driver's GL_MAX_RENDERBUFFER_SIZE (naming `platform`), std::runtime_error when the driver
// cannot complete it.
ColourDepthFramebuffer create_colour_depth_framebuffer(const GlApi& gl, int width, int height,
                                                       const std::string& platform);

}  // namespace ra::platforms
