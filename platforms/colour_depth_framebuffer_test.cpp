// The studies' framebuffer (colour_depth_framebuffer.cpp) in an OSMesa llvmpipe context: RGBA8
// colour and 24-bit depth of the window's size, bound for drawing and reading, and a window the
// driver cannot hold refused with the platform's name and its limit.
#include "platforms/colour_depth_framebuffer.h"

#include <gtest/gtest.h>

#include <array>
#include <memory>
#include <string>
#include <tuple>

#include "platforms/gl_context.h"
#include "util/errors.h"

namespace ra::platforms {
namespace {

class ColourDepthFramebufferTest : public ::testing::Test {
 protected:
  void SetUp() override {
    context_ = create_gl_context(*rundir::find_platform("osmesa-llvmpipe"));
  }
  const GlApi& gl() const { return context_->gl(); }
  GLint renderbuffer_parameter(GLuint renderbuffer, GLenum name) const {
    GLint v = -1;
    gl().BindRenderbuffer(GL_RENDERBUFFER, renderbuffer);
    gl().GetRenderbufferParameteriv(GL_RENDERBUFFER, name, &v);
    return v;
  }
  std::unique_ptr<GlContext> context_;
};

// Three distinct GL names; the framebuffer is the one bound for drawing and reading; both
// attachments are width x height, the colour RGBA8 (8 bits a channel), the depth 24 bits.
TEST_F(ColourDepthFramebufferTest, IsRgba8AndDepth24OfTheWindowsSizeAndBound) {
  const ColourDepthFramebuffer f = create_colour_depth_framebuffer(gl(), 48, 20, "osmesa-llvmpipe");
  EXPECT_NE(f.framebuffer, 0u);
  EXPECT_NE(f.colour, 0u);
  EXPECT_NE(f.depth, 0u);
  EXPECT_NE(f.colour, f.depth);
  GLint draw = 0, read = 0;
  gl().GetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &draw);
  gl().GetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &read);
  EXPECT_EQ(GLuint(draw), f.framebuffer);
  EXPECT_EQ(GLuint(read), f.framebuffer);
  for (GLuint rb : {f.colour, f.depth}) {
    EXPECT_EQ(renderbuffer_parameter(rb, GL_RENDERBUFFER_WIDTH), 48);
    EXPECT_EQ(renderbuffer_parameter(rb, GL_RENDERBUFFER_HEIGHT), 20);
    EXPECT_EQ(renderbuffer_parameter(rb, GL_RENDERBUFFER_SAMPLES), 0);
  }
  EXPECT_EQ(renderbuffer_parameter(f.colour, GL_RENDERBUFFER_INTERNAL_FORMAT), GL_RGBA8);
  for (GLenum channel : {GL_RENDERBUFFER_RED_SIZE, GL_RENDERBUFFER_GREEN_SIZE,
                         GL_RENDERBUFFER_BLUE_SIZE, GL_RENDERBUFFER_ALPHA_SIZE})
    EXPECT_EQ(renderbuffer_parameter(f.colour, channel), 8);
  EXPECT_EQ(renderbuffer_parameter(f.depth, GL_RENDERBUFFER_INTERNAL_FORMAT), GL_DEPTH_COMPONENT24);
  EXPECT_EQ(renderbuffer_parameter(f.depth, GL_RENDERBUFFER_DEPTH_SIZE), 24);
  EXPECT_EQ(gl().GetError(), GLenum(GL_NO_ERROR));
}

// What is cleared into it reads back, colour and depth, at its far corner (inside a 48 x 20
// window, outside the 1 x 1 buffer OSMesa makes the context with).
TEST_F(ColourDepthFramebufferTest, HoldsWhatIsClearedIntoItUpToItsFarCorner) {
  create_colour_depth_framebuffer(gl(), 48, 20, "osmesa-llvmpipe");
  gl().Viewport(0, 0, 48, 20);
  gl().ClearColor(1, 0, 1, 1);
  gl().ClearDepth(0.25);
  gl().Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  gl().PixelStorei(GL_PACK_ALIGNMENT, 1);
  std::array<unsigned char, 4> rgba{};
  gl().ReadPixels(47, 19, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
  EXPECT_EQ(rgba, (std::array<unsigned char, 4>{255, 0, 255, 255}));
  float depth = -1;
  gl().ReadPixels(47, 19, 1, 1, GL_DEPTH_COMPONENT, GL_FLOAT, &depth);
  EXPECT_FLOAT_EQ(depth, 0.25f);  // 0.25 is exact in 24 bits
  EXPECT_EQ(gl().GetError(), GLenum(GL_NO_ERROR));
}

// One pixel more than GL_MAX_RENDERBUFFER_SIZE, in either direction: a user error that names the
// window, the platform and the limit; exactly the limit is not refused by this check.
TEST_F(ColourDepthFramebufferTest, AWindowBeyondTheDriversLimitIsAUserErrorNamingIt) {
  GLint max_size = 0;
  gl().GetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &max_size);
  ASSERT_GT(max_size, 0);
  const std::string limit = std::to_string(max_size), over = std::to_string(max_size + 1);
  for (const auto& [w, h, text] :
       {std::tuple{max_size + 1, 1, over + "x1"}, std::tuple{1, max_size + 1, "1x" + over}}) {
    try {
      create_colour_depth_framebuffer(gl(), w, h, "osmesa-llvmpipe");
      ADD_FAILURE() << "no error for " << text;
    } catch (const util::UserError& e) {
      EXPECT_EQ(std::string(e.what()), "window " + text +
                                           " exceeds osmesa-llvmpipe's GL_MAX_RENDERBUFFER_SIZE " +
                                           limit);
    }
  }
}

}  // namespace
}  // namespace ra::platforms
