// OSMesa drawing of LOD meshes (lod_renderer.h).
#include "terrain_lod/lod_renderer.h"

#include <GL/gl.h>
#include <GL/glext.h>
#include <GL/osmesa.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

#include "util/errors.h"
#include "platforms/platform.h"

namespace ra::lod {
namespace {

template <typename F>
void load(F& fn, const char* name) {
  fn = reinterpret_cast<F>(OSMesaGetProcAddress(name));
  if (!fn) throw std::runtime_error(std::string("OSMesa lacks ") + name);
}

struct Vertex {
  float x, y, z;
  uint8_t rgba[4];
};

// Height ramp: t in [0, 1] from the lowest to the highest vertex.
void ramp(double t, double rgb[3]) {
  static const double stops[4][3] = {{0.20, 0.55, 0.20}, {0.55, 0.45, 0.25}, {0.55, 0.55, 0.55}, {0.97, 0.97, 0.97}};
  const double s = std::clamp(t, 0.0, 1.0) * 3;
  const int k = std::min(2, int(s));
  const double f = s - k;
  for (int c = 0; c < 3; ++c) rgb[c] = stops[k][c] + (stops[k + 1][c] - stops[k][c]) * f;
}

}  // namespace

ImageDifference image_difference(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
  ImageDifference d;
  if (a.size() != b.size() || a.empty()) throw std::invalid_argument("image_difference: sizes differ");
  const size_t pixels = a.size() / 4;
  double sum = 0;
  size_t differing = 0;
  for (size_t p = 0; p < pixels; ++p) {
    int worst = 0;
    for (int c = 0; c < 3; ++c) {
      const int diff = std::abs(int(a[4 * p + size_t(c)]) - int(b[4 * p + size_t(c)]));
      sum += diff;
      worst = std::max(worst, diff);
    }
    differing += worst > 16;
  }
  d.mean_abs = sum / double(3 * pixels);
  d.differing = double(differing) / double(pixels);
  return d;
}

struct LodRenderer::Impl {
  timing::CameraSettings cam;
  OSMesaContext context = nullptr;
  std::vector<uint8_t> colour;
  GLuint vbo = 0, ibo = 0;
  std::vector<std::pair<GLsizei, size_t>> draws;  // per tile: index count, byte offset
  PFNGLGENBUFFERSPROC gen_buffers = nullptr;
  PFNGLDELETEBUFFERSPROC delete_buffers = nullptr;
  PFNGLBINDBUFFERPROC bind_buffer = nullptr;
  PFNGLBUFFERDATAPROC buffer_data = nullptr;
};

LodRenderer::LodRenderer(const std::string& platform, const timing::CameraSettings& cam, const HeightField& f)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  const PlatformSpec* spec = find_platform(platform);
  if (!spec || !spec->gallium_driver)
    throw UserError("platform '" + platform + "' has no Mesa driver (allowed: osmesa-llvmpipe, osmesa-softpipe)");
  m.cam = cam;
  setenv("GALLIUM_DRIVER", spec->gallium_driver, 1);  // only validated names reach Mesa
  setenv("LP_NUM_THREADS", "0", 0);
  m.context = OSMesaCreateContextExt(OSMESA_RGBA, 24, 0, 0, nullptr);
  if (!m.context) throw std::runtime_error("OSMesaCreateContextExt failed for " + platform);
  m.colour.assign(size_t(cam.width) * cam.height * 4, 0);
  if (!OSMesaMakeCurrent(m.context, m.colour.data(), GL_UNSIGNED_BYTE, cam.width, cam.height))
    throw std::runtime_error("OSMesaMakeCurrent failed");
  {
    // Mesa picks the driver at the process's first context: GALLIUM_DRIVER set now has no effect
    // when an earlier context (e.g. another study or the figures) chose another one. Refuse to
    // measure on the wrong driver.
    const GLubyte* r = glGetString(GL_RENDERER);
    const std::string renderer = r ? reinterpret_cast<const char*>(r) : "";
    if (renderer.find(spec->gallium_driver) == std::string::npos) {
      OSMesaDestroyContext(m.context);
      m.context = nullptr;
      throw std::runtime_error("platform " + platform + " expects the Mesa driver '" + spec->gallium_driver +
                               "', but the OSMesa context draws with GL_RENDERER '" + renderer +
                               "' (Mesa chose another driver before: the study's drawing process, a forked child, "
                               "inherits the driver of a GL context its parent made)");
    }
  }
  load(m.gen_buffers, "glGenBuffers");
  load(m.delete_buffers, "glDeleteBuffers");
  load(m.bind_buffer, "glBindBuffer");
  load(m.buffer_data, "glBufferData");

  // vertex colours from the full-resolution surface (see the header)
  double zmin = 1e300, zmax = -1e300;
  for (double z : f.z) {
    zmin = std::min(zmin, z);
    zmax = std::max(zmax, z);
  }
  const double range = zmax > zmin ? zmax - zmin : 1;
  const double sun[3] = {-0.5, 0.5, 0.70710678};  // north-west, 45 degrees up (unit length)
  std::vector<Vertex> verts(f.z.size());
  for (int j = 0; j < f.ny; ++j)
    for (int i = 0; i < f.nx; ++i) {
      const double dzdx = (f.at(std::min(i + 1, f.nx - 1), j) - f.at(std::max(i - 1, 0), j)) /
                          ((std::min(i + 1, f.nx - 1) - std::max(i - 1, 0)) * f.spacing);
      const double dzdy = (f.at(i, std::min(j + 1, f.ny - 1)) - f.at(i, std::max(j - 1, 0))) /
                          ((std::min(j + 1, f.ny - 1) - std::max(j - 1, 0)) * f.spacing);
      const double len = std::sqrt(dzdx * dzdx + dzdy * dzdy + 1);
      const double lambert = std::max(0.0, (-dzdx * sun[0] - dzdy * sun[1] + sun[2]) / len);
      double rgb[3];
      ramp((f.at(i, j) - zmin) / range, rgb);
      Vertex& v = verts[size_t(j) * f.nx + i];
      v = {float(i * f.spacing), float(j * f.spacing), float(f.at(i, j)), {0, 0, 0, 255}};
      for (int c = 0; c < 3; ++c) v.rgba[c] = uint8_t(std::clamp(255 * rgb[c] * (0.25 + 0.75 * lambert), 0.0, 255.0));
    }
  m.gen_buffers(1, &m.vbo);
  m.gen_buffers(1, &m.ibo);
  m.bind_buffer(GL_ARRAY_BUFFER, m.vbo);
  m.buffer_data(GL_ARRAY_BUFFER, GLsizeiptr(verts.size() * sizeof(Vertex)), verts.data(), GL_STATIC_DRAW);
  glEnableClientState(GL_VERTEX_ARRAY);
  glEnableClientState(GL_COLOR_ARRAY);
  glVertexPointer(3, GL_FLOAT, sizeof(Vertex), reinterpret_cast<const void*>(0));
  glColorPointer(4, GL_UNSIGNED_BYTE, sizeof(Vertex), reinterpret_cast<const void*>(3 * sizeof(float)));
  glViewport(0, 0, cam.width, cam.height);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDisable(GL_CULL_FACE);  // seen from below through a crack, a back face still shows
  glDisable(GL_LIGHTING);
  glShadeModel(GL_SMOOTH);
  glClearColor(0.55f, 0.70f, 0.90f, 1.0f);  // sky
  glMatrixMode(GL_PROJECTION);
  glLoadMatrixd(timing::projection_of(cam).m.data());
  glMatrixMode(GL_MODELVIEW);
  if (glGetError() != GL_NO_ERROR) throw std::runtime_error("GL error while setting up the terrain renderer");
}

LodRenderer::~LodRenderer() {
  if (impl_ && impl_->context) {
    impl_->delete_buffers(1, &impl_->vbo);
    impl_->delete_buffers(1, &impl_->ibo);
    OSMesaDestroyContext(impl_->context);
  }
}

std::string LodRenderer::gl_renderer() const { return reinterpret_cast<const char*>(glGetString(GL_RENDERER)); }
std::string LodRenderer::gl_version() const { return reinterpret_cast<const char*>(glGetString(GL_VERSION)); }

void LodRenderer::set_viewpoint(const Viewpoint& vp) {
  glMatrixMode(GL_MODELVIEW);
  glLoadMatrixd(timing::look_at(vp).m.data());
}

void LodRenderer::upload(const LodMesh& mesh) {
  Impl& m = *impl_;
  std::vector<uint32_t> indices;
  indices.reserve(mesh.strip_index_count());
  m.draws.clear();
  for (const TileMesh& t : mesh.tiles) {
    m.draws.push_back({GLsizei(t.strip.size()), indices.size() * sizeof(uint32_t)});
    indices.insert(indices.end(), t.strip.begin(), t.strip.end());
  }
  m.bind_buffer(GL_ELEMENT_ARRAY_BUFFER, m.ibo);
  m.buffer_data(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(indices.size() * sizeof(uint32_t)), indices.data(), GL_STREAM_DRAW);
  glFinish();
}

double LodRenderer::draw() {
  Impl& m = *impl_;
  glFinish();
  const auto t0 = std::chrono::steady_clock::now();
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  for (const auto& [count, offset] : m.draws)
    glDrawElements(GL_TRIANGLE_STRIP, count, GL_UNSIGNED_INT, reinterpret_cast<const void*>(offset));
  glFinish();
  const auto t1 = std::chrono::steady_clock::now();
  if (glGetError() != GL_NO_ERROR) throw std::runtime_error("GL error while drawing the terrain");
  return std::chrono::duration<double, std::micro>(t1 - t0).count();
}

const std::vector<uint8_t>& LodRenderer::image() const { return impl_->colour; }

}  // namespace ra::lod
