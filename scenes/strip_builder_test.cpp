// The generators' building blocks and the StripMesh / Scene helpers of scene.h.
#include "scenes/strip_builder.h"

#include <gtest/gtest.h>

#include "scenes/scene.h"
#include "scenes/scene_test_util.h"

namespace ra::scenes {
namespace {

using scene_test::cross3;
using scene_test::for_each_triangle;

// A 3 x 2 cell grid: 4 x 3 vertices, corners exactly where asked, two strips of 8 indices,
// every triangle counter-clockwise seen from du x dv (here +z).
TEST(SceneStripBuilder, GridLayoutAndWinding) {
  StripMesh m;
  const uint32_t first = add_grid(m, {1, 2, 3}, {3, 0, 0}, {0, 2, 0}, 3, 2, 5, 0, 1, 0, 1);
  EXPECT_EQ(first, 0u);
  ASSERT_EQ(m.vertex_count(), 12u);
  EXPECT_EQ(m.triangle_count(), 12u);
  EXPECT_EQ(m.index_count(), 16u);
  ASSERT_EQ(m.strips.size(), 2u);
  EXPECT_EQ(m.strips[0].texture, 5);
  EXPECT_EQ(m.vertex(0).x, 1);
  EXPECT_EQ(m.vertex(11).x, 4);
  EXPECT_EQ(m.vertex(11).y, 4);
  EXPECT_EQ(m.vertex(11).z, 3);
  EXPECT_EQ(m.texcoords[2 * 11], 3.0f);  // s counts columns, t rows
  EXPECT_EQ(m.texcoords[2 * 11 + 1], 2.0f);
  int n = 0;
  for_each_triangle(m, [&](geometry::Vec3 a, geometry::Vec3 b, geometry::Vec3 c, size_t) {
    EXPECT_GT(cross3(b - a, c - a).z, 0);
    ++n;
  });
  EXPECT_EQ(n, 12);
}

// A polygon of n vertices: one strip of n indices, n - 2 triangles, none degenerate, all facing
// the same way (up for a counter-clockwise ring, down reversed).
TEST(SceneStripBuilder, PolygonStripZigZag) {
  for (int n : {3, 4, 5, 8, 33}) {
    for (bool reverse : {false, true}) {
      StripMesh m;
      std::vector<uint32_t> ring;
      for (int k = 0; k < n; ++k) {
        const double a = 2 * 3.14159265358979 * k / n;
        ring.push_back(add_vertex(m, {std::cos(a), std::sin(a), 0}, 0, 0));
      }
      add_polygon_strip(m, ring.data(), n, 0, reverse);
      ASSERT_EQ(m.strips.size(), 1u);
      EXPECT_EQ(m.strips[0].indices.size(), static_cast<size_t>(n));
      EXPECT_EQ(m.triangle_count(), static_cast<size_t>(n - 2));
      double area = 0;
      for_each_triangle(m, [&](geometry::Vec3 a, geometry::Vec3 b, geometry::Vec3 c, size_t) {
        const double z = cross3(b - a, c - a).z;
        EXPECT_GT(reverse ? -z : z, 1e-9) << n;
        area += std::fabs(z) / 2;
      });
      // the triangles tile the polygon: their areas add up to its area
      EXPECT_NEAR(area, 0.5 * n * std::sin(2 * 3.14159265358979 / n), 1e-6);  // float vertices
    }
  }
  StripMesh m;
  const uint32_t r[5] = {0, 1, 2, 3, 4};
  add_polygon_strip(m, r, 5, 0, false);
  add_polygon_strip(m, r, 5, 0, true);
  EXPECT_EQ(m.strips[0].indices, (std::vector<uint32_t>{0, 1, 4, 2, 3}));
  EXPECT_EQ(m.strips[1].indices, (std::vector<uint32_t>{0, 4, 1, 3, 2}));
}

TEST(SceneStripBuilder, EnclosingSphereHoldsEveryVertex) {
  StripMesh m;
  add_vertex(m, {0, 0, 0}, 0, 0);
  add_vertex(m, {2, 0, 0}, 0, 0);
  add_vertex(m, {0, 4, 0}, 0, 0);
  const BoundingSphere s = enclosing_sphere(m);
  EXPECT_DOUBLE_EQ(s.centre.x, 1);  // the box's centre
  EXPECT_DOUBLE_EQ(s.centre.y, 2);
  EXPECT_DOUBLE_EQ(s.radius, std::sqrt(5.0));
  EXPECT_EQ(enclosing_sphere(StripMesh{}).radius, 0);
}

// The ground ceiling is the highest corner of the cell; outside the grid it clamps to the border.
TEST(SceneStripBuilder, GroundCeilingOfAGrid) {
  SceneLayout l;
  EXPECT_EQ(l.ground_ceiling(5, 5), 0);  // no grid: flat ground
  l.ground_nx = 3;
  l.ground_ny = 2;
  l.ground_spacing = 10;
  l.ground_x0 = 100;
  l.ground_z = {0, 1, 2,   //
                3, 9, 4};
  EXPECT_EQ(l.ground_ceiling(105, 5), 9);
  EXPECT_EQ(l.ground_ceiling(115, 5), 9);
  EXPECT_EQ(l.ground_ceiling(125, 5), 9);  // past the last column: its cell
  EXPECT_EQ(l.ground_ceiling(50, -50), 9);
  l.ground_z = {0, 1, 2, 3, 0, 4};
  EXPECT_EQ(l.ground_ceiling(101, 1), 3);
  EXPECT_EQ(l.ground_ceiling(119, 1), 4);
}

TEST(SceneStripBuilder, SceneHashSeesEveryPart) {
  Scene a;
  a.kind = "city";
  a.objects.push_back({});
  add_grid(a.objects[0].mesh, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 2, 2, 0, 0, 1, 0, 1);
  a.textures.push_back({1, 1, {1, 2, 3, 4}});
  const uint64_t h = scene_hash(a);
  EXPECT_EQ(scene_hash(a), h);
  Scene b = a;
  b.objects[0].mesh.positions[4] += 1e-3f;
  EXPECT_NE(scene_hash(b), h);
  b = a;
  b.objects[0].mesh.strips[1].texture = 1;
  EXPECT_NE(scene_hash(b), h);
  b = a;
  b.objects[0].mesh.strips[0].indices[0] = 1;
  EXPECT_NE(scene_hash(b), h);
  b = a;
  b.textures[0].rgba[3] = 0;
  EXPECT_NE(scene_hash(b), h);
  b = a;
  b.kind = "forest";
  EXPECT_NE(scene_hash(b), h);
}

}  // namespace
}  // namespace ra::scenes
