// Drawing of LOD meshes through a GL platform (lod_renderer.h), into the studies' scene target
// (scenes/scene_target.h: a framebuffer object of the window size, colour and depth); the image is
// read back only when asked for, outside the timing.
#include "terrain_lod/lod_renderer.h"


#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

#include "scenes/scene_target.h"

namespace ra::lod {
namespace {

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
  Impl(const std::string& platform, const scenes::CameraSettings& cam)
      : target(platform, cam), gl(&target.gl()) {}
  scenes::SceneTarget target;
  const platforms::GlApi* gl;  // target.gl()
  std::vector<uint8_t> colour;  // the last frame, read back when image() asks for it
  bool colour_stale = true;
  GLuint vbo = 0, ibo = 0;
  std::vector<std::pair<GLsizei, size_t>> draws;  // per tile: index count, byte offset
};

LodRenderer::LodRenderer(const std::string& platform, const scenes::CameraSettings& cam,
                         const HeightField& f)
    : impl_(std::make_unique<Impl>(platform, cam)) {
  Impl& m = *impl_;
  const platforms::GlApi* gl = m.gl;
  m.colour.assign(size_t(cam.width) * cam.height * 4, 0);

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
  m.vbo = m.target.new_buffer(GL_ARRAY_BUFFER, verts.data(), verts.size() * sizeof(Vertex),
                              GL_STATIC_DRAW);
  gl->GenBuffers(1, &m.ibo);
  gl->EnableClientState(GL_VERTEX_ARRAY);
  gl->EnableClientState(GL_COLOR_ARRAY);
  gl->VertexPointer(3, GL_FLOAT, sizeof(Vertex), reinterpret_cast<const void*>(0));
  gl->ColorPointer(4, GL_UNSIGNED_BYTE, sizeof(Vertex), reinterpret_cast<const void*>(3 * sizeof(float)));
  gl->Disable(GL_CULL_FACE);  // seen from below through a crack, a back face still shows
  gl->Disable(GL_LIGHTING);
  gl->ShadeModel(GL_SMOOTH);
  gl->ClearColor(0.55f, 0.70f, 0.90f, 1.0f);  // sky
  if (gl->GetError() != GL_NO_ERROR) throw std::runtime_error("GL error while setting up the terrain renderer");
}

LodRenderer::~LodRenderer() {
  if (impl_) {
    impl_->target.context().make_current();
    impl_->gl->DeleteBuffers(1, &impl_->vbo);
    impl_->gl->DeleteBuffers(1, &impl_->ibo);
  }
}

std::string LodRenderer::gl_renderer() const { return impl_->target.gl_string(GL_RENDERER); }
std::string LodRenderer::gl_version() const { return impl_->target.gl_string(GL_VERSION); }

void LodRenderer::set_viewpoint(const scenes::Viewpoint& vp) { impl_->target.set_viewpoint(vp); }

void LodRenderer::upload(const LodMesh& mesh) {
  Impl& m = *impl_;
  const platforms::GlApi* gl = m.gl;
  std::vector<uint32_t> indices;
  indices.reserve(mesh.strip_index_count());
  m.draws.clear();
  for (const TileMesh& t : mesh.tiles) {
    m.draws.push_back({GLsizei(t.strip.size()), indices.size() * sizeof(uint32_t)});
    indices.insert(indices.end(), t.strip.begin(), t.strip.end());
  }
  m.target.fill_buffer(GL_ELEMENT_ARRAY_BUFFER, m.ibo, indices.data(),
                       indices.size() * sizeof(uint32_t), GL_STREAM_DRAW);
  gl->Finish();
}

double LodRenderer::draw() {
  Impl& m = *impl_;
  const platforms::GlApi* gl = m.gl;
  m.colour_stale = true;
  gl->Finish();
  const auto t0 = std::chrono::steady_clock::now();
  gl->Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  for (const auto& [count, offset] : m.draws)
    gl->DrawElements(GL_TRIANGLE_STRIP, count, GL_UNSIGNED_INT, reinterpret_cast<const void*>(offset));
  gl->Finish();
  const auto t1 = std::chrono::steady_clock::now();
  if (gl->GetError() != GL_NO_ERROR) throw std::runtime_error("GL error while drawing the terrain");
  return std::chrono::duration<double, std::micro>(t1 - t0).count();
}

const std::vector<uint8_t>& LodRenderer::image() const {
  Impl& m = *impl_;
  if (m.colour_stale) {
    m.target.read_rgba(m.colour);
    m.colour_stale = false;
  }
  return m.colour;
}

}  // namespace ra::lod
