// A scene drawn through a GL platform for the rendering-time study (scene_renderer.h; Wimmer &
// Wonka 2003, sections 4.2, 7.1). The context, the framebuffer object of the window size (colour
// and depth) and the camera's state come from the studies' scene target (scenes/scene_target.h).
#include "timing/scene_renderer.h"


#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <stdexcept>

#include "scenes/scene_target.h"

namespace ra::timing {
namespace {

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
  Impl(const std::string& platform, const scenes::CameraSettings& cam)
      : target(platform, cam, " to time"), gl(&target.gl()) {}
  scenes::SceneTarget target;
  const platforms::GlApi* gl;  // target.gl()
  RendererInfo info;
  bool gpu = false;
  GLuint occlusion_query = 0, timer_query = 0;
  std::vector<ObjectBuffers> objects;
  std::vector<GLuint> textures;
  GLuint bound_texture = 0;


  void release_scene() {
    for (ObjectBuffers& o : objects) {
      gl->DeleteBuffers(1, &o.vbo);
      gl->DeleteBuffers(1, &o.ibo);
    }
    objects.clear();
    if (!textures.empty()) gl->DeleteTextures(GLsizei(textures.size()), textures.data());
    textures.clear();
    bound_texture = 0;
  }

  // Issues the draws of one object; returns the glBindTexture calls it made.
  int64_t draw_object(int index) {
    const ObjectBuffers& o = objects.at(std::size_t(index));
    int64_t binds = 0;
    gl->BindBuffer(GL_ARRAY_BUFFER, o.vbo);
    gl->VertexPointer(3, GL_FLOAT, 5 * sizeof(float), reinterpret_cast<const void*>(0));
    gl->TexCoordPointer(2, GL_FLOAT, 5 * sizeof(float),
                      reinterpret_cast<const void*>(3 * sizeof(float)));
    gl->BindBuffer(GL_ELEMENT_ARRAY_BUFFER, o.ibo);
    for (const StripDraw& s : o.strips) {
      if (s.texture != bound_texture) {
        gl->BindTexture(GL_TEXTURE_2D, s.texture);
        bound_texture = s.texture;
        ++binds;
      }
      gl->DrawRangeElements(GL_TRIANGLE_STRIP, s.min_index, s.max_index, s.count, GL_UNSIGNED_INT,
                          reinterpret_cast<const void*>(s.offset));
    }
    return binds;
  }

  void reset_texture_state() {
    gl->BindTexture(GL_TEXTURE_2D, 0);
    bound_texture = 0;
  }
};

SceneRenderer::SceneRenderer(const std::string& platform, const scenes::CameraSettings& cam,
                             bool gpu_timer)
    : impl_(std::make_unique<Impl>(platform, cam)) {
  Impl& m = *impl_;
  const platforms::GlApi* gl = m.gl;
  m.info.platform = platform;
  m.info.gallium_driver = m.target.spec().mesa_driver;
  m.info.backend = m.target.context().backend();
  m.info.lp_num_threads = std::getenv("LP_NUM_THREADS") ? std::getenv("LP_NUM_THREADS") : "";
  m.info.renderer = m.target.gl_string(GL_RENDERER);
  m.info.version = m.target.gl_string(GL_VERSION);
  m.info.vendor = m.target.gl_string(GL_VENDOR);
  const char* ext = reinterpret_cast<const char*>(gl->GetString(GL_EXTENSIONS));
  m.info.timer_query_listed = ext && std::strstr(ext, "GL_ARB_timer_query");
  if (m.info.timer_query_listed) {
    GLint bits = 0;
    gl->GetQueryiv(GL_TIME_ELAPSED, GL_QUERY_COUNTER_BITS, &bits);
    m.info.timer_query_bits = bits;
  }
  m.info.timer_query = m.info.timer_query_listed && m.info.timer_query_bits > 0;
  m.gpu = gpu_timer && m.info.timer_query;

  GLint depth_bits = 0;
  gl->GetIntegerv(GL_DEPTH_BITS, &depth_bits);
  m.info.depth_bits = depth_bits;

  gl->GenQueries(1, &m.occlusion_query);
  gl->GenQueries(1, &m.timer_query);

  // Fixed-function state of the study (beside the target's depth test and camera): textures
  // replace the colour, no lighting.
  gl->Enable(GL_TEXTURE_2D);
  gl->TexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_REPLACE);
  for (GLenum cap : {GL_LIGHTING, GL_BLEND, GL_CULL_FACE, GL_DITHER, GL_MULTISAMPLE})
    gl->Disable(cap);
  gl->ClearColor(0.5f, 0.7f, 1.0f, 1.0f);
  gl->ClearDepth(1.0);
  gl->EnableClientState(GL_VERTEX_ARRAY);
  gl->EnableClientState(GL_TEXTURE_COORD_ARRAY);
  if (gl->GetError() != GL_NO_ERROR) throw std::runtime_error("GL error setting up " + platform);
}

SceneRenderer::~SceneRenderer() {
  if (impl_) {
    impl_->target.context().make_current();
    impl_->release_scene();
  }
}

const RendererInfo& SceneRenderer::info() const { return impl_->info; }
const scenes::CameraSettings& SceneRenderer::camera() const { return impl_->target.camera(); }
bool SceneRenderer::measuring_gpu() const { return impl_->gpu; }

void SceneRenderer::upload(const scenes::Scene& scene) {
  const platforms::GlApi* gl = impl_->gl;
  Impl& m = *impl_;
  m.release_scene();
  m.textures.resize(scene.textures.size());
  if (!m.textures.empty()) gl->GenTextures(GLsizei(m.textures.size()), m.textures.data());
  for (std::size_t t = 0; t < scene.textures.size(); ++t) {
    const scenes::Texture& tex = scene.textures[t];
    if (tex.rgba.size() != std::size_t(tex.width) * tex.height * 4)
      throw std::runtime_error("texture " + std::to_string(t) + " has the wrong size");
    gl->BindTexture(GL_TEXTURE_2D, m.textures[t]);
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
    gl->TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, tex.width, tex.height, 0, GL_RGBA, GL_UNSIGNED_BYTE,
                 tex.rgba.data());
  }
  m.reset_texture_state();
  m.objects.resize(scene.objects.size());
  std::vector<float> interleaved;
  std::vector<uint32_t> indices;
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    const scenes::StripMesh& mesh = scene.objects[i].mesh;
    ObjectBuffers& o = m.objects[i];
    const std::size_t nv = mesh.vertex_count();
    interleaved.assign(nv * 5, 0.0f);
    for (std::size_t v = 0; v < nv; ++v) {
      for (int c = 0; c < 3; ++c) interleaved[v * 5 + c] = mesh.positions[v * 3 + c];
      if (mesh.texcoords.size() >= (v + 1) * 2)
        for (int c = 0; c < 2; ++c) interleaved[v * 5 + 3 + c] = mesh.texcoords[v * 2 + c];
    }
    indices.clear();
    for (const scenes::TriangleStrip& s : mesh.strips) {
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
    o.vbo = m.target.new_buffer(GL_ARRAY_BUFFER, interleaved.data(),
                                interleaved.size() * sizeof(float), GL_STATIC_DRAW);
    o.ibo = m.target.new_buffer(GL_ELEMENT_ARRAY_BUFFER, indices.data(),
                                indices.size() * sizeof(uint32_t), GL_STATIC_DRAW);
  }
  gl->Finish();
  if (gl->GetError() != GL_NO_ERROR) throw std::runtime_error("GL error uploading the scene");
}

void SceneRenderer::set_viewpoint(const scenes::Viewpoint& vp) { impl_->target.set_viewpoint(vp); }

DrawTime SceneRenderer::time_draw(const std::vector<int>& objects, bool with_clear,
                                  std::vector<int64_t>* state_changes) {
  const platforms::GlApi* gl = impl_->gl;
  Impl& m = *impl_;
  if (!with_clear) gl->Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  m.reset_texture_state();
  gl->Finish();  // the pipeline is idle when the clock starts
  if (state_changes) state_changes->assign(objects.size(), 0);
  DrawTime out;
  const auto t0 = std::chrono::steady_clock::now();
  if (m.gpu) gl->BeginQuery(GL_TIME_ELAPSED, m.timer_query);
  if (with_clear) gl->Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  for (std::size_t i = 0; i < objects.size(); ++i) {
    const int64_t binds = m.draw_object(objects[i]);
    if (state_changes) (*state_changes)[i] = binds;
  }
  if (m.gpu) gl->EndQuery(GL_TIME_ELAPSED);
  gl->Finish();
  out.cpu_us =
      std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
  out.gpu_us = std::numeric_limits<double>::quiet_NaN();
  if (m.gpu) {
    GLuint64 ns = 0;
    gl->GetQueryObjectui64v(m.timer_query, GL_QUERY_RESULT, &ns);
    out.gpu_us = double(ns) / 1000.0;
  }
  return out;
}

int64_t SceneRenderer::pixels_alone(int object) {
  const platforms::GlApi* gl = impl_->gl;
  Impl& m = *impl_;
  // Depth test off: every fragment the object generates passes (no clear needed).
  gl->Disable(GL_DEPTH_TEST);
  m.reset_texture_state();
  gl->BeginQuery(GL_SAMPLES_PASSED, m.occlusion_query);
  m.draw_object(object);
  gl->EndQuery(GL_SAMPLES_PASSED);
  gl->Enable(GL_DEPTH_TEST);
  GLuint samples = 0;
  gl->GetQueryObjectuiv(m.occlusion_query, GL_QUERY_RESULT, &samples);
  return int64_t(samples);
}

}  // namespace ra::timing
