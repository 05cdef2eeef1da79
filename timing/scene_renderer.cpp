// A scene drawn through OSMesa for the rendering-time study (scene_renderer.h; Wimmer & Wonka
// 2003, sections 4.2, 7.1). The context is made as platforms/osmesa_platform.cpp makes it: the
// window-system buffer is 1x1 and never drawn to; drawing goes to a framebuffer object of the
// window size, here with a depth renderbuffer as well.
#include "timing/scene_renderer.h"

#include <GL/gl.h>
#include <GL/glext.h>
#include <GL/osmesa.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <stdexcept>

#include "util/errors.h"
#include "platforms/platform.h"

namespace ra::timing {
namespace {

template <typename F>
void load(F& fn, const char* name) {
  fn = reinterpret_cast<F>(OSMesaGetProcAddress(name));
  if (!fn) throw std::runtime_error(std::string("OSMesa lacks ") + name);
}

struct StripDraw {
  GLsizei count = 0;      // indices
  std::size_t offset = 0;  // bytes into the index buffer
  GLuint min_index = 0, max_index = 0;
  GLuint texture = 0;     // GL name
};

struct ObjectBuffers {
  GLuint vbo = 0, ibo = 0;
  std::vector<StripDraw> strips;
};

}  // namespace

struct SceneRenderer::Impl {
  RendererInfo info;
  CameraSettings cam;
  bool gpu = false;
  OSMesaContext context = nullptr;
  uint8_t winsys_pixel[4] = {};
  GLuint framebuffer = 0, colour_rb = 0, depth_rb = 0;
  GLuint occlusion_query = 0, timer_query = 0;
  std::vector<ObjectBuffers> objects;
  std::vector<GLuint> textures;
  GLuint bound_texture = 0;

  PFNGLGENFRAMEBUFFERSPROC gen_framebuffers = nullptr;
  PFNGLBINDFRAMEBUFFERPROC bind_framebuffer = nullptr;
  PFNGLGENRENDERBUFFERSPROC gen_renderbuffers = nullptr;
  PFNGLBINDRENDERBUFFERPROC bind_renderbuffer = nullptr;
  PFNGLRENDERBUFFERSTORAGEPROC renderbuffer_storage = nullptr;
  PFNGLFRAMEBUFFERRENDERBUFFERPROC framebuffer_renderbuffer = nullptr;
  PFNGLCHECKFRAMEBUFFERSTATUSPROC check_framebuffer = nullptr;
  PFNGLGENBUFFERSPROC gen_buffers = nullptr;
  PFNGLDELETEBUFFERSPROC delete_buffers = nullptr;
  PFNGLBINDBUFFERPROC bind_buffer = nullptr;
  PFNGLBUFFERDATAPROC buffer_data = nullptr;
  PFNGLDRAWRANGEELEMENTSPROC draw_range_elements = nullptr;
  PFNGLGENQUERIESPROC gen_queries = nullptr;
  PFNGLBEGINQUERYPROC begin_query = nullptr;
  PFNGLENDQUERYPROC end_query = nullptr;
  PFNGLGETQUERYOBJECTUIVPROC get_query_uiv = nullptr;
  PFNGLGETQUERYIVPROC get_query_iv = nullptr;
  PFNGLGETQUERYOBJECTUI64VPROC get_query_ui64v = nullptr;

  void release_scene() {
    for (ObjectBuffers& o : objects) {
      delete_buffers(1, &o.vbo);
      delete_buffers(1, &o.ibo);
    }
    objects.clear();
    if (!textures.empty()) glDeleteTextures(GLsizei(textures.size()), textures.data());
    textures.clear();
    bound_texture = 0;
  }

  // Issues the draws of one object; returns the glBindTexture calls it made.
  int64_t draw_object(int index) {
    const ObjectBuffers& o = objects.at(std::size_t(index));
    int64_t binds = 0;
    bind_buffer(GL_ARRAY_BUFFER, o.vbo);
    glVertexPointer(3, GL_FLOAT, 5 * sizeof(float), reinterpret_cast<const void*>(0));
    glTexCoordPointer(2, GL_FLOAT, 5 * sizeof(float),
                      reinterpret_cast<const void*>(3 * sizeof(float)));
    bind_buffer(GL_ELEMENT_ARRAY_BUFFER, o.ibo);
    for (const StripDraw& s : o.strips) {
      if (s.texture != bound_texture) {
        glBindTexture(GL_TEXTURE_2D, s.texture);
        bound_texture = s.texture;
        ++binds;
      }
      draw_range_elements(GL_TRIANGLE_STRIP, s.min_index, s.max_index, s.count, GL_UNSIGNED_INT,
                          reinterpret_cast<const void*>(s.offset));
    }
    return binds;
  }

  void reset_texture_state() {
    glBindTexture(GL_TEXTURE_2D, 0);
    bound_texture = 0;
  }
};

SceneRenderer::SceneRenderer(const std::string& platform, const CameraSettings& cam,
                             bool gpu_timer)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  const PlatformSpec* spec = find_platform(platform);
  if (!spec || !spec->gallium_driver)
    throw UserError("platform '" + platform +
                    "' has no Mesa driver to time (allowed: osmesa-llvmpipe, osmesa-softpipe)");
  m.cam = cam;
  m.info.platform = platform;
  m.info.gallium_driver = spec->gallium_driver;
  // Mesa reads these when the first context is made; only validated names reach it.
  setenv("GALLIUM_DRIVER", spec->gallium_driver, 1);
  setenv("LP_NUM_THREADS", "0", 0);
  m.info.lp_num_threads = std::getenv("LP_NUM_THREADS");
  m.context = OSMesaCreateContextExt(OSMESA_RGBA, 0, 0, 0, nullptr);
  if (!m.context) throw std::runtime_error("OSMesaCreateContextExt failed for " + platform);
  if (!OSMesaMakeCurrent(m.context, m.winsys_pixel, GL_UNSIGNED_BYTE, 1, 1))
    throw std::runtime_error("OSMesaMakeCurrent failed");
  load(m.gen_framebuffers, "glGenFramebuffers");
  load(m.bind_framebuffer, "glBindFramebuffer");
  load(m.gen_renderbuffers, "glGenRenderbuffers");
  load(m.bind_renderbuffer, "glBindRenderbuffer");
  load(m.renderbuffer_storage, "glRenderbufferStorage");
  load(m.framebuffer_renderbuffer, "glFramebufferRenderbuffer");
  load(m.check_framebuffer, "glCheckFramebufferStatus");
  load(m.gen_buffers, "glGenBuffers");
  load(m.delete_buffers, "glDeleteBuffers");
  load(m.bind_buffer, "glBindBuffer");
  load(m.buffer_data, "glBufferData");
  load(m.draw_range_elements, "glDrawRangeElements");
  load(m.gen_queries, "glGenQueries");
  load(m.begin_query, "glBeginQuery");
  load(m.end_query, "glEndQuery");
  load(m.get_query_uiv, "glGetQueryObjectuiv");
  load(m.get_query_iv, "glGetQueryiv");

  m.info.renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  m.info.version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
  m.info.vendor = reinterpret_cast<const char*>(glGetString(GL_VENDOR));
  const char* ext = reinterpret_cast<const char*>(glGetString(GL_EXTENSIONS));
  m.info.timer_query_listed = ext && std::strstr(ext, "GL_ARB_timer_query");
  if (m.info.timer_query_listed) {
    m.get_query_ui64v =
        reinterpret_cast<PFNGLGETQUERYOBJECTUI64VPROC>(OSMesaGetProcAddress("glGetQueryObjectui64v"));
    GLint bits = 0;
    m.get_query_iv(GL_TIME_ELAPSED, GL_QUERY_COUNTER_BITS, &bits);
    m.info.timer_query_bits = bits;
  }
  m.info.timer_query = m.info.timer_query_listed && m.info.timer_query_bits > 0 && m.get_query_ui64v;
  m.gpu = gpu_timer && m.info.timer_query;

  // Framebuffer object: RGBA8 colour + 24-bit depth of the window size.
  GLint max_size = 0;
  glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &max_size);
  if (cam.width > max_size || cam.height > max_size)
    throw UserError("window " + std::to_string(cam.width) + "x" + std::to_string(cam.height) +
                    " exceeds " + platform + "'s GL_MAX_RENDERBUFFER_SIZE " +
                    std::to_string(max_size));
  m.gen_framebuffers(1, &m.framebuffer);
  m.bind_framebuffer(GL_FRAMEBUFFER, m.framebuffer);
  m.gen_renderbuffers(1, &m.colour_rb);
  m.bind_renderbuffer(GL_RENDERBUFFER, m.colour_rb);
  m.renderbuffer_storage(GL_RENDERBUFFER, GL_RGBA8, cam.width, cam.height);
  m.framebuffer_renderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, m.colour_rb);
  m.gen_renderbuffers(1, &m.depth_rb);
  m.bind_renderbuffer(GL_RENDERBUFFER, m.depth_rb);
  m.renderbuffer_storage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, cam.width, cam.height);
  m.framebuffer_renderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, m.depth_rb);
  if (m.check_framebuffer(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw std::runtime_error("incomplete framebuffer (RGBA8 + DEPTH24) for " + platform);
  GLint depth_bits = 0;
  glGetIntegerv(GL_DEPTH_BITS, &depth_bits);
  m.info.depth_bits = depth_bits;

  m.gen_queries(1, &m.occlusion_query);
  m.gen_queries(1, &m.timer_query);

  // Fixed-function state of the study: depth test, textures replace the colour, no lighting.
  glViewport(0, 0, cam.width, cam.height);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glEnable(GL_TEXTURE_2D);
  glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_REPLACE);
  for (GLenum cap : {GL_LIGHTING, GL_BLEND, GL_CULL_FACE, GL_DITHER, GL_MULTISAMPLE})
    glDisable(cap);
  glClearColor(0.5f, 0.7f, 1.0f, 1.0f);
  glClearDepth(1.0);
  glEnableClientState(GL_VERTEX_ARRAY);
  glEnableClientState(GL_TEXTURE_COORD_ARRAY);
  glMatrixMode(GL_PROJECTION);
  glLoadMatrixd(projection_of(cam).m.data());
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
  if (glGetError() != GL_NO_ERROR) throw std::runtime_error("GL error setting up " + platform);
}

SceneRenderer::~SceneRenderer() {
  if (impl_->context) {
    impl_->release_scene();
    OSMesaDestroyContext(impl_->context);
  }
}

const RendererInfo& SceneRenderer::info() const { return impl_->info; }
const CameraSettings& SceneRenderer::camera() const { return impl_->cam; }
bool SceneRenderer::measuring_gpu() const { return impl_->gpu; }
std::size_t SceneRenderer::object_count() const { return impl_->objects.size(); }

void SceneRenderer::upload(const Scene& scene) {
  Impl& m = *impl_;
  m.release_scene();
  m.textures.resize(scene.textures.size());
  if (!m.textures.empty()) glGenTextures(GLsizei(m.textures.size()), m.textures.data());
  for (std::size_t t = 0; t < scene.textures.size(); ++t) {
    const Texture& tex = scene.textures[t];
    if (tex.rgba.size() != std::size_t(tex.width) * tex.height * 4)
      throw std::runtime_error("texture " + std::to_string(t) + " has the wrong size");
    glBindTexture(GL_TEXTURE_2D, m.textures[t]);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, tex.width, tex.height, 0, GL_RGBA, GL_UNSIGNED_BYTE,
                 tex.rgba.data());
  }
  m.reset_texture_state();
  m.objects.resize(scene.objects.size());
  std::vector<float> interleaved;
  std::vector<uint32_t> indices;
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    const StripMesh& mesh = scene.objects[i].mesh;
    ObjectBuffers& o = m.objects[i];
    const std::size_t nv = mesh.vertex_count();
    interleaved.assign(nv * 5, 0.0f);
    for (std::size_t v = 0; v < nv; ++v) {
      for (int c = 0; c < 3; ++c) interleaved[v * 5 + c] = mesh.positions[v * 3 + c];
      if (mesh.texcoords.size() >= (v + 1) * 2)
        for (int c = 0; c < 2; ++c) interleaved[v * 5 + 3 + c] = mesh.texcoords[v * 2 + c];
    }
    indices.clear();
    for (const TriangleStrip& s : mesh.strips) {
      if (s.indices.size() < 3) continue;  // draws nothing
      StripDraw d;
      d.count = GLsizei(s.indices.size());
      d.offset = indices.size() * sizeof(uint32_t);
      d.min_index = std::numeric_limits<GLuint>::max();
      for (uint32_t k : s.indices) {
        if (k >= nv) throw std::runtime_error(scene.objects[i].name + ": index out of range");
        d.min_index = std::min<GLuint>(d.min_index, k);
        d.max_index = std::max<GLuint>(d.max_index, k);
      }
      if (s.texture < 0 || std::size_t(s.texture) >= m.textures.size())
        throw std::runtime_error(scene.objects[i].name + ": texture index out of range");
      d.texture = m.textures[std::size_t(s.texture)];
      indices.insert(indices.end(), s.indices.begin(), s.indices.end());
      o.strips.push_back(d);
    }
    m.gen_buffers(1, &o.vbo);
    m.bind_buffer(GL_ARRAY_BUFFER, o.vbo);
    m.buffer_data(GL_ARRAY_BUFFER, GLsizeiptr(interleaved.size() * sizeof(float)),
                  interleaved.data(), GL_STATIC_DRAW);
    m.gen_buffers(1, &o.ibo);
    m.bind_buffer(GL_ELEMENT_ARRAY_BUFFER, o.ibo);
    m.buffer_data(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(indices.size() * sizeof(uint32_t)),
                  indices.data(), GL_STATIC_DRAW);
  }
  glFinish();
  if (glGetError() != GL_NO_ERROR) throw std::runtime_error("GL error uploading the scene");
}

void SceneRenderer::set_viewpoint(const Viewpoint& vp) {
  glMatrixMode(GL_MODELVIEW);
  glLoadMatrixd(look_at(vp).m.data());
}

DrawTime SceneRenderer::time_draw(const std::vector<int>& objects, bool with_clear,
                                  std::vector<int64_t>* state_changes) {
  Impl& m = *impl_;
  if (!with_clear) glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  m.reset_texture_state();
  glFinish();  // the pipeline is idle when the clock starts
  if (state_changes) state_changes->assign(objects.size(), 0);
  DrawTime out;
  const auto t0 = std::chrono::steady_clock::now();
  if (m.gpu) m.begin_query(GL_TIME_ELAPSED, m.timer_query);
  if (with_clear) glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  for (std::size_t i = 0; i < objects.size(); ++i) {
    const int64_t binds = m.draw_object(objects[i]);
    if (state_changes) (*state_changes)[i] = binds;
  }
  if (m.gpu) m.end_query(GL_TIME_ELAPSED);
  glFinish();
  out.cpu_us =
      std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
  out.gpu_us = std::numeric_limits<double>::quiet_NaN();
  if (m.gpu) {
    GLuint64 ns = 0;
    m.get_query_ui64v(m.timer_query, GL_QUERY_RESULT, &ns);
    out.gpu_us = double(ns) / 1000.0;
  }
  return out;
}

int64_t SceneRenderer::pixels_alone(int object) {
  Impl& m = *impl_;
  // Depth test off: every fragment the object generates passes (no clear needed).
  glDisable(GL_DEPTH_TEST);
  m.reset_texture_state();
  m.begin_query(GL_SAMPLES_PASSED, m.occlusion_query);
  m.draw_object(object);
  m.end_query(GL_SAMPLES_PASSED);
  glEnable(GL_DEPTH_TEST);
  GLuint samples = 0;
  m.get_query_uiv(m.occlusion_query, GL_QUERY_RESULT, &samples);
  return int64_t(samples);
}

}  // namespace ra::timing
