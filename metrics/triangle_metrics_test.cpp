// Triangle rendering errors TEs / TEu (NIST paper, eqs. 9-12): a hand-built case, the reference
// platform property (TEu = area misclassified by centre sampling), and the odd inputs.
#include "metrics/triangle_metrics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "geometry/reference_rasterizer.h"

namespace ra::metrics {
namespace {

// Clip coordinates (w = 1) of a window point in a W x H window.
geometry::Vec4 clip_of(double x, double y, int w, int h) {
  return {2 * x / w - 1, 2 * y / h - 1, 0, 1};
}

geometry::ClippedPolygon window_triangle(geometry::Vec2 a, geometry::Vec2 b, geometry::Vec2 c,
                                         int w, int h) {
  return geometry::clip_triangle(clip_of(a.x, a.y, w, h), clip_of(b.x, b.y, w, h),
                                 clip_of(c.x, c.y, w, h), w, h);
}

geometry::View make_view(double fov, int size) {
  return ra::geometry::make_view(fov, size, size);
}

// Hand-built: triangle (0,0), (4,0), (0,4) in an 8 x 8 window. Pixels with i + j <= 2 lie inside
// (area 1), those with i + j == 3 are cut in half by the hypotenuse. Lit: the six inside pixels
// plus (3,0). Then: lit outside = 0.5 (half of (3,0)); unlit inside = 3 * 0.5 for (0,3), (1,2),
// (2,1); TEs = -1, TEu = 2; / 64. Two legs lie on the window border, so the visible edge is the
// hypotenuse alone, 4 sqrt(2).
TEST(TriangleMetrics, HandBuiltCase) {
  const geometry::ClippedPolygon p = window_triangle({0, 0}, {4, 0}, {0, 4}, 8, 8);
  ASSERT_EQ(p.status, geometry::ClipStatus::kVisible);
  const geometry::PixelSet lit = {{0, 0}, {1, 0}, {2, 0}, {3, 0}, {0, 1}, {1, 1}, {0, 2}};
  const TriangleMetrics m = measure_triangle(p, lit, 8, 8);
  ASSERT_TRUE(m.valid);
  EXPECT_NEAR(m.projected_area, 8.0, 1e-12);
  EXPECT_EQ(m.rendered, 7);
  EXPECT_NEAR(m.rendered_outside, 0.5, 1e-12);
  EXPECT_NEAR(m.unrendered_inside, 1.5, 1e-12);
  EXPECT_NEAR(m.te_signed, -1.0, 1e-12);
  EXPECT_NEAR(m.te_unsigned, 2.0, 1e-12);
  EXPECT_NEAR(m.te_signed_norm, -1.0 / 64, 1e-14);
  EXPECT_NEAR(m.te_unsigned_norm, 2.0 / 64, 1e-14);
  EXPECT_NEAR(m.visible_edge_length, 4 * std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(m.te_unsigned_edge_norm, 2.0 / (4 * std::sqrt(2.0)), 1e-12);
  EXPECT_FALSE(m.full_window);
  EXPECT_TRUE(m.simply_connected);
}

// The reference platform: lit = pixels whose centres the triangle covers. Then TEu is exactly the
// area misclassified by centre sampling, sum over every window pixel of (lit ? 1 - a : a), with a
// computed independently pixel by pixel (pixel_area_in_convex_polygon). Also TEs = |P| - area.
TEST(TriangleMetrics, ReferenceTEuIsTheSamplingMisclassification) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  for (double fov : {30.0, 150.0}) {
    const geometry::View v = make_view(fov, 128);
    int tested = 0;
    for (int t = 0; t < 150 && tested < 25; ++t) {
      const geometry::ClippedPolygon p = geometry::clip_triangle(
          v, {u(rng), u(rng), u(rng)}, {u(rng), u(rng), u(rng)}, {u(rng), u(rng), u(rng)});
      if (p.status != geometry::ClipStatus::kVisible) continue;
      ++tested;
      const geometry::PixelSet lit = geometry::rasterize_polygon(p, 128, 128);
      const TriangleMetrics m = measure_triangle(p, lit, 128, 128);
      double brute = 0;
      for (int y = 0; y < 128; ++y)
        for (int x = 0; x < 128; ++x) {
          const bool on = lit.contains({x, y});
          const double a = geometry::pixel_area_in_convex_polygon(p.vertices, {x, y});
          brute += on ? 1 - a : a;
        }
      EXPECT_NEAR(m.te_unsigned, brute, 1e-9 * std::max(1.0, brute));
      EXPECT_NEAR(m.te_signed, double(lit.size()) - p.area, 1e-9 * std::max(1.0, p.area));
    }
    EXPECT_GE(tested, 10);
  }
}

// A triangle covering the whole window, every pixel lit: no error, full window, no visible edge
// (all edges on the border), so the edge normalisation is undefined (NaN, not a number made up).
TEST(TriangleMetrics, FullWindow) {
  const geometry::ClippedPolygon p =
      window_triangle({-100, -100}, {300, -100}, {-100, 300}, 16, 16);
  ASSERT_EQ(p.status, geometry::ClipStatus::kVisible);
  geometry::PixelSet lit;
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) lit.insert({x, y});
  const TriangleMetrics m = measure_triangle(p, lit, 16, 16);
  EXPECT_TRUE(m.full_window);
  EXPECT_EQ(m.te_unsigned, 0.0);
  EXPECT_EQ(m.te_signed, 0.0);
  EXPECT_EQ(m.visible_edge_length, 0.0);
  EXPECT_TRUE(std::isnan(m.te_unsigned_edge_norm));
  EXPECT_TRUE(m.simply_connected);
  lit.erase({15, 15});
  EXPECT_FALSE(measure_triangle(p, lit, 16, 16).full_window);
}

// A triangle that is not ideally visible but was drawn (false-visible): every lit pixel is error.
// Lit pixels outside the window count wholly outside too.
TEST(TriangleMetrics, NothingToCoverMeansAllLitIsError) {
  const geometry::ClippedPolygon invisible =
      geometry::clip_triangle(geometry::Vec4{2, 0, 0, 1}, geometry::Vec4{3, 0.5, 0, 1},
                              geometry::Vec4{2.5, -0.5, 0, 1}, 10, 10);
  ASSERT_EQ(invisible.status, geometry::ClipStatus::kInvisible);
  const geometry::PixelSet lit = {{-1, 3}, {9, 4}, {9, 5}};
  const TriangleMetrics m = measure_triangle(invisible, lit, 10, 10);
  ASSERT_TRUE(m.valid);
  EXPECT_EQ(m.te_unsigned, 3.0);
  EXPECT_EQ(m.te_signed, 3.0);
  const geometry::ClippedPolygon flat =
      window_triangle({1, 1}, {5, 5}, {3, 3}, 10, 10);  // collinear
  ASSERT_EQ(flat.status, geometry::ClipStatus::kDegenerate);
  EXPECT_EQ(measure_triangle(flat, lit, 10, 10).te_unsigned, 3.0);
}

// NaN input: invalid, with NaN metrics (never a silent number).
TEST(TriangleMetrics, InvalidInput) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const geometry::ClippedPolygon p = geometry::clip_triangle(
      geometry::Vec4{nan, 0, 0, 1}, geometry::Vec4{0, 0, 0, 1}, geometry::Vec4{0, 1, 0, 1}, 8, 8);
  const TriangleMetrics m = measure_triangle(p, {{1, 1}}, 8, 8);
  EXPECT_FALSE(m.valid);
  EXPECT_TRUE(std::isnan(m.te_unsigned));
  EXPECT_TRUE(std::isnan(m.te_signed_norm));
}

// Lit pixels far from the polygon and pixels inside a run are all accounted for (rows of the lit
// set before, between and after the polygon's rows).
TEST(TriangleMetrics, StrayPixelsAndRunsAreCounted) {
  const geometry::ClippedPolygon p = window_triangle({2, 2}, {30, 2}, {2, 30}, 40, 40);
  geometry::PixelSet lit = geometry::rasterize_polygon(p, 40, 40);
  const TriangleMetrics clean = measure_triangle(p, lit, 40, 40);
  lit.insert({0, 0});    // below the polygon's rows
  lit.insert({35, 10});  // in a polygon row, right of it
  lit.insert({39, 39});  // above
  const TriangleMetrics m = measure_triangle(p, lit, 40, 40);
  EXPECT_NEAR(m.rendered_outside, clean.rendered_outside + 3, 1e-12);
  EXPECT_NEAR(m.unrendered_inside, clean.unrendered_inside, 1e-12);
  EXPECT_EQ(m.components, 4);
  EXPECT_FALSE(m.simply_connected);
  // Removing an interior pixel: its whole area (1) goes missing, and it makes a hole.
  geometry::PixelSet holed = geometry::rasterize_polygon(p, 40, 40);
  holed.erase({8, 8});
  const TriangleMetrics h = measure_triangle(p, holed, 40, 40);
  EXPECT_NEAR(h.unrendered_inside, clean.unrendered_inside + 1, 1e-12);
  EXPECT_EQ(h.holes, 1);
  EXPECT_FALSE(h.simply_connected);
}

// The window-area normalisation has no integer overflow for the largest windows.
TEST(TriangleMetrics, LargestWindowNormalisation) {
  const int size = 16384;
  const geometry::ClippedPolygon p =
      window_triangle({0.5, 0.5}, {3.5, 0.5}, {0.5, 3.5}, size, size);
  const TriangleMetrics m = measure_triangle(p, {{0, 0}}, size, size);
  EXPECT_NEAR(m.te_unsigned_norm, m.te_unsigned / (double(size) * size), 1e-25);
  EXPECT_GT(m.te_unsigned_norm, 0);
}

// Edges created by the near plane are visible edges; edges created by the window sides are not.
TEST(TriangleMetrics, VisibleEdgesExcludeOnlyTheWindowBorder) {
  geometry::ClippedPolygon p;
  p.status = geometry::ClipStatus::kVisible;
  p.vertices = {{0, 0}, {10, 0}, {10, 5}, {3, 8}};
  p.on_window_border = {true, false, false, false};
  EXPECT_NEAR(visible_edge_length(p), 5 + std::hypot(7, 3) + std::hypot(3, 8), 1e-12);
}

// The View + Primitive entry point is clip_triangle followed by the polygon version.
TEST(TriangleMetrics, PrimitiveEntryPoint) {
  const geometry::View v = make_view(30, 128);
  geometry::Primitive prim;
  prim.kind = geometry::Kind::kTriangle;
  prim.v = {geometry::Vec3{0.05, 0.02, -0.5}, geometry::Vec3{-0.04, 0.03, -0.6},
            geometry::Vec3{0.01, -0.05, -0.4}};
  const geometry::PixelSet lit = geometry::rasterize_reference(v, prim);
  const TriangleMetrics a = measure_triangle(v, prim, lit);
  const TriangleMetrics b =
      measure_triangle(geometry::clip_triangle(v, prim.v[0], prim.v[1], prim.v[2]), lit, 128, 128);
  EXPECT_EQ(a.te_unsigned, b.te_unsigned);
  EXPECT_EQ(a.te_signed, b.te_signed);
  EXPECT_TRUE(a.simply_connected);
}

}  // namespace
}  // namespace ra::metrics
