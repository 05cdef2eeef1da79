#include "scenes/strip_builder.h"

#include <cassert>

namespace ra::scenes {

uint32_t add_vertex(StripMesh& mesh, geometry::Vec3 p, double s, double t) {
  const auto n = static_cast<uint32_t>(mesh.vertex_count());
  mesh.positions.insert(mesh.positions.end(),
                        {static_cast<float>(p.x), static_cast<float>(p.y), static_cast<float>(p.z)});
  mesh.texcoords.insert(mesh.texcoords.end(), {static_cast<float>(s), static_cast<float>(t)});
  return n;
}

uint32_t add_grid(StripMesh& mesh, geometry::Vec3 origin, geometry::Vec3 du, geometry::Vec3 dv,
                  int cols, int rows, int texture, double s0, double s_step, double t0,
                  double t_step) {
  assert(cols >= 1 && rows >= 1);
  const uint32_t first = static_cast<uint32_t>(mesh.vertex_count());
  for (int v = 0; v <= rows; ++v)
    for (int u = 0; u <= cols; ++u) {
      // the last row and column land exactly on origin + du (+ dv): neighbouring grids meet
      const double fu = u == cols ? 1.0 : double(u) / cols, fv = v == rows ? 1.0 : double(v) / rows;
      add_vertex(mesh, origin + fu * du + fv * dv, s0 + u * s_step, t0 + v * t_step);
    }
  const uint32_t row = static_cast<uint32_t>(cols) + 1;
  for (int v = 0; v < rows; ++v) {
    TriangleStrip strip;
    strip.texture = texture;
    strip.indices.reserve(2 * row);
    for (uint32_t u = 0; u < row; ++u) {
      strip.indices.push_back(first + (v + 1) * row + u);  // upper row first: counter-clockwise
      strip.indices.push_back(first + v * row + u);
    }
    mesh.strips.push_back(std::move(strip));
  }
  return first;
}

void add_polygon_strip(StripMesh& mesh, const uint32_t* ring, int n, int texture, bool reverse) {
  assert(n >= 3);
  TriangleStrip strip;
  strip.texture = texture;
  strip.indices.reserve(n);
  // walk inwards from both ends: lo climbs from ring[1], hi descends from ring[n-1]
  int lo = 1, hi = n - 1;
  strip.indices.push_back(ring[0]);
  bool take_lo = !reverse;
  while (lo <= hi) {
    strip.indices.push_back(take_lo ? ring[lo++] : ring[hi--]);
    take_lo = !take_lo;
  }
  mesh.strips.push_back(std::move(strip));
}

}  // namespace ra::scenes
