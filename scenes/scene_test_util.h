// Helpers shared by the scenes/ tests (header only; not part of the library).
// Units: metres, world coordinates, +Z up.
#pragma once

#include <cmath>
#include <functional>

#include "scenes/scene.h"

namespace ra::scenes::scene_test {

inline geometry::Vec3 cross3(geometry::Vec3 a, geometry::Vec3 b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double norm3(geometry::Vec3 a) { return std::sqrt(geometry::dot(a, a)); }

// Calls fn(a, b, c, strip index) for every triangle of the mesh in GL_TRIANGLE_STRIP order and
// winding (odd triangles swap their first two vertices), so cross3(b - a, c - a) is the front
// normal of a counter-clockwise front face.
inline void for_each_triangle(
    const StripMesh& m,
    const std::function<void(geometry::Vec3, geometry::Vec3, geometry::Vec3, size_t)>& fn) {
  for (size_t s = 0; s < m.strips.size(); ++s) {
    const auto& idx = m.strips[s].indices;
    for (size_t k = 0; k + 2 < idx.size(); ++k) {
      uint32_t a = idx[k], b = idx[k + 1];
      if (k % 2 == 1) std::swap(a, b);
      fn(m.vertex(a), m.vertex(b), m.vertex(idx[k + 2]), s);
    }
  }
}

}  // namespace ra::scenes::scene_test
