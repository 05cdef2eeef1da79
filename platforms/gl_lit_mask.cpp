// The lit-pixel scan on a GL device (see the header).
#include "platforms/gl_lit_mask.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>

#include "lit_mask_comp.glsl.h"  // kLitMaskCompSource: platforms/shaders/lit_mask.comp

namespace ra::platforms {
namespace {

constexpr GLuint kGroupSize = 64;  // the shader's local_size_x

}  // namespace

GlLitMask::GlLitMask(const GlApi& gl, int glsl_version, const std::string& platform)
    : gl_(gl), platform_(platform) {
  std::string source = kLitMaskCompSource;
  const std::string version = "#version 450";
  const size_t at = source.find(version);
  if (at == std::string::npos) throw std::logic_error("lit_mask.comp: no #version 450 line");
  source.replace(at, version.size(), "#version " + std::to_string(glsl_version));
  const GLuint shader = gl_.CreateShader(GL_COMPUTE_SHADER);
  const char* text = source.c_str();
  gl_.ShaderSource(shader, 1, &text, nullptr);
  gl_.CompileShader(shader);
  GLint ok = 0;
  gl_.GetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  char log[2048] = "";
  if (!ok) {
    gl_.GetShaderInfoLog(shader, sizeof log, nullptr, log);
    gl_.DeleteShader(shader);
    throw std::runtime_error("platform " + platform_ + ": the scan's compute shader: " + log);
  }
  program_ = gl_.CreateProgram();
  gl_.AttachShader(program_, shader);
  gl_.LinkProgram(program_);
  gl_.DeleteShader(shader);
  gl_.GetProgramiv(program_, GL_LINK_STATUS, &ok);
  if (!ok) {
    gl_.GetProgramInfoLog(program_, sizeof log, nullptr, log);
    gl_.DeleteProgram(program_);
    throw std::runtime_error("platform " + platform_ + ": the scan's compute program: " + log);
  }
  rect_count_at_ = gl_.GetUniformLocation(program_, "rect_count");
  word_count_at_ = gl_.GetUniformLocation(program_, "word_count");
  word_base_at_ = gl_.GetUniformLocation(program_, "word_base");
  GLint max_groups = 0;
  gl_.GetIntegeri_v(GL_MAX_COMPUTE_WORK_GROUP_COUNT, 0, &max_groups);
  max_groups_ = GLuint(std::max(max_groups, 1));
  gl_.GenBuffers(3, buffers_);
}

GlLitMask::~GlLitMask() {
  gl_.DeleteBuffers(3, buffers_);
  gl_.DeleteProgram(program_);
}

GLuint GlLitMask::prepare(const LitMaskLayout& layout) {
  const size_t bytes[3] = {4 * size_t(layout.pixel_count), sizeof(LitMaskRect) * layout.rects.size(),
                           4 * (layout.rects.size() + size_t(layout.word_count))};
  const GLenum usage[3] = {GL_STREAM_COPY, GL_STREAM_DRAW, GL_STREAM_READ};
  for (int k = 0; k < 3; ++k) {
    if (bytes[k] <= capacity_[k]) continue;
    capacity_[k] = std::max<size_t>(bytes[k], size_t(1) << 16);  // grows to the largest scan
    gl_.BindBuffer(GL_SHADER_STORAGE_BUFFER, buffers_[k]);
    gl_.BufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(capacity_[k]), nullptr, usage[k]);
  }
  gl_.BindBuffer(GL_SHADER_STORAGE_BUFFER, buffers_[1]);
  gl_.BufferSubData(GL_SHADER_STORAGE_BUFFER, 0, GLsizeiptr(bytes[1]), layout.rects.data());
  const std::vector<uint32_t> zeros(layout.rects.size(), 0);  // the counts start at 0
  gl_.BindBuffer(GL_SHADER_STORAGE_BUFFER, buffers_[2]);
  gl_.BufferSubData(GL_SHADER_STORAGE_BUFFER, 0, GLsizeiptr(4 * zeros.size()), zeros.data());
  gl_.BindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
  return buffers_[0];
}

void GlLitMask::run(const LitMaskLayout& layout) {
  const size_t n_words = layout.rects.size() + size_t(layout.word_count);
  words_.assign(n_words, 0);
  if (layout.rects.empty()) return;
  gl_.UseProgram(program_);
  for (GLuint k = 0; k < 3; ++k) gl_.BindBufferBase(GL_SHADER_STORAGE_BUFFER, k, buffers_[k]);
  gl_.Uniform1ui(rect_count_at_, GLuint(layout.rects.size()));
  gl_.Uniform1ui(word_count_at_, GLuint(layout.word_count));
  const uint64_t groups_in_all = (layout.word_count + kGroupSize - 1) / kGroupSize;
  for (uint64_t first = 0; first < groups_in_all; first += max_groups_) {
    gl_.Uniform1ui(word_base_at_, GLuint(first * kGroupSize));
    gl_.DispatchCompute(GLuint(std::min<uint64_t>(groups_in_all - first, max_groups_)), 1, 1);
  }
  gl_.UseProgram(0);  // the drawing is fixed-function
  gl_.MemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);  // the shader's writes, then the map
  gl_.BindBuffer(GL_SHADER_STORAGE_BUFFER, buffers_[2]);
  const void* from =
      gl_.MapBufferRange(GL_SHADER_STORAGE_BUFFER, 0, GLsizeiptr(4 * n_words), GL_MAP_READ_BIT);
  if (!from) throw std::runtime_error("platform " + platform_ + ": glMapBufferRange failed");
  std::memcpy(words_.data(), from, 4 * n_words);
  gl_.UnmapBuffer(GL_SHADER_STORAGE_BUFFER);
  gl_.BindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
  for (GLuint k = 0; k < 3; ++k) gl_.BindBufferBase(GL_SHADER_STORAGE_BUFFER, k, 0);
}

}  // namespace ra::platforms
