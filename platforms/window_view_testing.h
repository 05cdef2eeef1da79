// Test support for the platform tests (included by platforms/*_test.cpp only): a view whose world
// coordinates are window coordinates, so that a test places vertices at exact pixel positions.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "geometry/primitive.h"
#include "geometry/view.h"

namespace ra::platforms::testing {

// A size x size window; world (x, y, z) -> clip (2x/size - 1, 2y/size - 1, 0, 1): window (x, y),
// exactly for dyadic x and y. The modelview is the identity, so a vertex at z = -1 lies between
// the near (0.01) and far (10) planes.
inline geometry::View window_view(int size) {
  geometry::View v;
  v.width = v.height = size;
  v.view_matrix = geometry::Mat4::identity();
  v.projection = geometry::Mat4::identity();
  v.projection.at(0, 0) = 2.0 / size;
  v.projection.at(0, 3) = -1;
  v.projection.at(1, 1) = 2.0 / size;
  v.projection.at(1, 3) = -1;
  v.projection.at(2, 2) = 0;
  v.view_projection = v.projection;
  return v;
}

// A primitive with its vertices at these window positions (under window_view), at z = -1.
inline geometry::Primitive window_primitive(geometry::Kind kind,
                                            const std::vector<geometry::Vec2>& window_points,
                                            uint64_t index = 0) {
  geometry::Primitive p;
  p.kind = kind;
  p.index = index;
  for (size_t i = 0; i < window_points.size(); ++i)
    p.v[i] = geometry::Vec3{window_points[i].x, window_points[i].y, -1};
  return p;
}

}  // namespace ra::platforms::testing
