#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "geometry/vector_math.h"
#include "scenes/scene.h"

namespace ra::scenes {

size_t StripMesh::triangle_count() const {
  size_t n = 0;
  for (const TriangleStrip& s : strips)
    if (s.indices.size() > 2) n += s.indices.size() - 2;
  return n;
}

size_t StripMesh::index_count() const {
  size_t n = 0;
  for (const TriangleStrip& s : strips) n += s.indices.size();
  return n;
}

BoundingSphere enclosing_sphere(const StripMesh& mesh) {
  const size_t n = mesh.vertex_count();
  if (n == 0) return {};
  geometry::Vec3 lo = mesh.vertex(0), hi = lo;
  for (size_t i = 1; i < n; ++i) {
    const geometry::Vec3 v = mesh.vertex(i);
    lo = {std::min(lo.x, v.x), std::min(lo.y, v.y), std::min(lo.z, v.z)};
    hi = {std::max(hi.x, v.x), std::max(hi.y, v.y), std::max(hi.z, v.z)};
  }
  BoundingSphere s;
  s.centre = 0.5 * (lo + hi);
  double r2 = 0;
  for (size_t i = 0; i < n; ++i) {
    const geometry::Vec3 d = mesh.vertex(i) - s.centre;
    r2 = std::max(r2, geometry::dot(d, d));
  }
  // note: the vertices are floats and the centre a double; the radius is exact in double.
  s.radius = std::sqrt(r2);
  return s;
}

double SceneLayout::ground_ceiling(double x, double y) const {
  if (ground_z.empty() || ground_nx < 1 || ground_ny < 1 || ground_spacing <= 0) return 0;
  auto cell = [&](double v, double v0, int n) {
    const double c = std::floor((v - v0) / ground_spacing);
    return static_cast<int>(std::clamp(c, 0.0, static_cast<double>(std::max(0, n - 2))));
  };
  const int i = cell(x, ground_x0, ground_nx), j = cell(y, ground_y0, ground_ny);
  double top = -std::numeric_limits<double>::infinity();
  for (int dj = 0; dj <= 1; ++dj)
    for (int di = 0; di <= 1; ++di) {
      const int ii = std::min(i + di, ground_nx - 1), jj = std::min(j + dj, ground_ny - 1);
      top = std::max(top, static_cast<double>(ground_z[static_cast<size_t>(jj) * ground_nx + ii]));
    }
  return top;
}

namespace {

struct Fnv1a {
  uint64_t h = 0xcbf29ce484222325ull;
  void bytes(const void* p, size_t n) {
    const auto* b = static_cast<const unsigned char*>(p);
    for (size_t i = 0; i < n; ++i) h = (h ^ b[i]) * 0x100000001b3ull;
  }
  template <typename T>
  void value(const T& v) { bytes(&v, sizeof v); }
  template <typename T>
  void vec(const std::vector<T>& v) {
    value(static_cast<uint64_t>(v.size()));
    bytes(v.data(), v.size() * sizeof(T));
  }
  void str(const std::string& s) {
    value(static_cast<uint64_t>(s.size()));
    bytes(s.data(), s.size());
  }
};

}  // namespace

uint64_t scene_hash(const Scene& scene) {
  Fnv1a f;
  f.str(scene.kind);
  f.value(static_cast<uint64_t>(scene.objects.size()));
  for (const SceneObject& o : scene.objects) {
    f.str(o.name);
    f.vec(o.mesh.positions);
    f.vec(o.mesh.texcoords);
    f.value(static_cast<uint64_t>(o.mesh.strips.size()));
    for (const TriangleStrip& s : o.mesh.strips) {
      f.vec(s.indices);
      f.value(static_cast<int64_t>(s.texture));
    }
    f.value(o.bounds.centre.x);
    f.value(o.bounds.centre.y);
    f.value(o.bounds.centre.z);
    f.value(o.bounds.radius);
  }
  f.value(static_cast<uint64_t>(scene.textures.size()));
  for (const Texture& t : scene.textures) {
    f.value(static_cast<int64_t>(t.width));
    f.value(static_cast<int64_t>(t.height));
    f.vec(t.rgba);
  }
  f.vec(scene.layout.ground_z);
  return f.h;
}

}  // namespace ra::scenes
