// The lit-pixel scan on a GL device (platforms/lit_mask.h): the rectangles are read by
// glReadPixels into a buffer object that stays on the device, a compute shader
// (platforms/shaders/lit_mask.comp, GL 4.3) writes a bit per pixel and a count per rectangle into
// another, and only that one is mapped.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "platforms/gl_api.h"
#include "platforms/lit_mask.h"

namespace ra::platforms {

class GlLitMask {
 public:
  // Compiles the shader for GLSL `glsl_version` (430 or 450) in the current context; throws
  // std::runtime_error with the compiler's log, naming `platform`, when it fails.
  GlLitMask(const GlApi& gl, int glsl_version, const std::string& platform);
  ~GlLitMask();
  GlLitMask(const GlLitMask&) = delete;
  GlLitMask& operator=(const GlLitMask&) = delete;

  // Makes room for `layout` and uploads its rectangles; returns the buffer that the caller reads
  // the rectangles' pixels into as GL_PIXEL_PACK_BUFFER (pixel k at byte 4 k) before run().
  GLuint prepare(const LitMaskLayout& layout);
  // The pass, then its results mapped and copied (a bit per pixel).
  void run(const LitMaskLayout& layout);
  uint64_t count(size_t i) const { return words_[i]; }
  const uint32_t* mask(const LitMaskLayout& layout, size_t i) const {
    return words_.data() + layout.rects.size() + layout.rects[i].first_word;
  }

 private:
  const GlApi& gl_;
  std::string platform_;
  GLuint program_ = 0;
  GLint rect_count_at_ = -1, word_count_at_ = -1, word_base_at_ = -1;  // uniform locations
  GLuint max_groups_ = 0;  // GL_MAX_COMPUTE_WORK_GROUP_COUNT in x
  GLuint buffers_[3] = {0, 0, 0};  // pixels, rectangles, counts and masks
  size_t capacity_[3] = {0, 0, 0};  // their sizes in bytes
  std::vector<uint32_t> words_;     // counts, then masks, of the last run()
};

}  // namespace ra::platforms
