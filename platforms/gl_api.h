// The GL entry points the project calls, as pointers fetched from the context's own
// GetProcAddress (OSMesaGetProcAddress or eglGetProcAddress). Calling through them, rather than
// through symbols linked at build time, lets one binary draw through OSMesa (Mesa's shared glapi)
// and through EGL (glvnd, which dispatches to Mesa or to a GPU vendor's library) and load either
// library only when a platform asks for it.
#pragma once

#define GL_GLEXT_PROTOTYPES 1  // prototypes, for decltype only: nothing here links to them
#include <GL/gl.h>
#include <GL/glext.h>

#include <functional>

namespace ra::platforms {

// Every function, without its "gl" prefix.
#define RA_GL_FUNCTIONS(X)                                                                     \
  X(Begin) X(BindBuffer) X(BindFramebuffer) X(BindRenderbuffer) X(BindTexture) X(BeginQuery)   \
  X(BlitFramebuffer) X(BufferData) X(CheckFramebufferStatus) X(Clear) X(ClearColor)            \
  X(ClearDepth) X(Color4f) X(Color4ub) X(ColorPointer) X(DeleteBuffers)                        \
  X(DeleteFramebuffers) X(DeleteRenderbuffers) X(DeleteTextures) X(DepthFunc) X(Disable)       \
  X(DrawElements) X(DrawRangeElements) X(Enable) X(EnableClientState) X(End) X(EndQuery)       \
  X(Finish) X(FramebufferRenderbuffer) X(GenBuffers) X(GenFramebuffers) X(GenQueries)          \
  X(GenRenderbuffers) X(GenTextures) X(GetError) X(GetIntegerv) X(GetMultisamplefv)            \
  X(GetQueryObjectui64v) X(GetQueryObjectuiv) X(GetQueryiv) X(GetRenderbufferParameteriv)      \
  X(GetString) X(LineWidth) X(LoadIdentity) X(LoadMatrixd) X(MapBufferRange) X(MatrixMode)     \
  X(PixelStorei) X(UnmapBuffer)                                                                \
  X(PointSize) X(PolygonMode) X(PopMatrix) X(PushMatrix) X(ReadBuffer) X(ReadPixels)           \
  X(RenderbufferStorage) X(RenderbufferStorageMultisample) X(ShadeModel) X(TexCoordPointer)    \
  X(TexEnvi) X(TexImage2D) X(TexParameteri) X(Vertex2d) X(Vertex3d) X(VertexPointer)           \
  X(Viewport)

// GL 4.3's compute shaders and storage buffers: only the lit-pixel scan on the device uses them
// (gl_lit_mask.cpp), so a driver without them still draws.
#define RA_GL_COMPUTE_FUNCTIONS(X)                                                             \
  X(AttachShader) X(BindBufferBase) X(BufferSubData) X(CompileShader) X(CreateProgram)         \
  X(CreateShader) X(DeleteProgram) X(DeleteShader) X(DispatchCompute) X(GetIntegeri_v)         \
  X(GetProgramInfoLog) X(GetProgramiv) X(GetShaderInfoLog) X(GetShaderiv)                      \
  X(GetUniformLocation) X(LinkProgram) X(MemoryBarrier) X(ShaderSource) X(Uniform1ui)          \
  X(UseProgram)

struct GlApi {
#define RA_GL_MEMBER(name) decltype(&::gl##name) name = nullptr;
  RA_GL_FUNCTIONS(RA_GL_MEMBER)
  RA_GL_COMPUTE_FUNCTIONS(RA_GL_MEMBER)
#undef RA_GL_MEMBER

  // Fetches every function with `get_proc` ("glClear" -> address). Throws std::runtime_error
  // naming the first one of RA_GL_FUNCTIONS the driver does not give; those of
  // RA_GL_COMPUTE_FUNCTIONS stay null when missing (has_compute()).
  void load(const std::function<void*(const char*)>& get_proc);
  // Every compute entry point was given (whether the context's version has them: GL_VERSION).
  bool has_compute() const;
};

}  // namespace ra::platforms
