// The point audit on hand-placed points with analytic answers.
#include "metrics/point_metrics.h"

#include <gtest/gtest.h>

#include <cmath>

#include "geometry/reference_rasterizer.h"

namespace ra::metrics {
namespace {

// Camera looking down -Z, 90-degree FOV, 128x128: a point (x, y, -1) projects to
// ((x + 1) * 64, (y + 1) * 64) exactly, since tan(45 deg) = 1.
geometry::View simple_view(int size = 128, double fov = 90) { return geometry::make_view(fov, size, size); }

TEST(PointMetrics, ProjectionMatchesTheAnalyticPosition) {
  const IdealPoint p = project_point(simple_view(), {0.1, 0.2, -1.0});
  ASSERT_TRUE(p.visible);
  EXPECT_NEAR(p.window.x, 70.4, 1e-12);
  EXPECT_NEAR(p.window.y, 76.8, 1e-12);
}

TEST(PointMetrics, PeOfAHandPlacedPointIsTheAnalyticDistance) {
  const geometry::View v = simple_view();
  const IdealPoint p = project_point(v, {0.1, 0.2, -1.0});
  Record rec;
  measure_point(v, p, {{70, 76}}, rec);
  EXPECT_EQ(rec.visibility, Visibility::kTrueVisible);
  // Pixel (70, 76) has its centre at (70.5, 76.5): distance hypot(0.1, 0.3).
  EXPECT_NEAR(rec.pe, std::sqrt(0.1 * 0.1 + 0.3 * 0.3), 1e-12);
  EXPECT_NEAR(rec.pe_norm, rec.pe / 128.0, 1e-15);
}

TEST(PointMetrics, VisibilityClasses) {
  EXPECT_EQ(classify_point(true, 1), Visibility::kTrueVisible);
  EXPECT_EQ(classify_point(false, 0), Visibility::kTrueInvisible);
  EXPECT_EQ(classify_point(false, 1), Visibility::kFalseVisible);
  EXPECT_EQ(classify_point(true, 0), Visibility::kFalseInvisible);
  EXPECT_EQ(classify_point(true, 2), Visibility::kMultipleVisible);
  EXPECT_EQ(classify_point(false, 3), Visibility::kMultipleVisible);
}

TEST(PointMetrics, PointsBehindTheCameraOrOutsideThePlanesAreInvisible) {
  const geometry::View v = simple_view();
  EXPECT_FALSE(project_point(v, {0, 0, 1}).visible);        // behind the camera
  EXPECT_FALSE(project_point(v, {0, 0, -0.005}).visible);   // nearer than the near plane
  EXPECT_FALSE(project_point(v, {0, 0, -11}).visible);      // beyond the far plane
  EXPECT_FALSE(project_point(v, {1.5, 0, -1}).visible);     // right of the frustum
  EXPECT_TRUE(project_point(v, {0, 0, -0.02}).visible);
}

// The paper's margin convention on hand-placed points: in simple_view a point (x, y, -1) projects
// to ((x + 1) * 64, (y + 1) * 64), so x = 1 + d / 64 lies d pixels right of the window.
TEST(PointMetrics, WindowMarginCountsPointsJustOutsideTheWindow) {
  const geometry::View v = simple_view();
  auto right_of_window = [](double d_px) { return geometry::Vec3{1 + d_px / 64, 0, -1}; };
  EXPECT_TRUE(inside_window_margin(v, {0, 0, -1}, 0));
  EXPECT_FALSE(inside_window_margin(v, right_of_window(0.49), 0));
  EXPECT_TRUE(inside_window_margin(v, right_of_window(0.49), 0.5));
  EXPECT_FALSE(inside_window_margin(v, right_of_window(0.51), 0.5));
  EXPECT_TRUE(inside_window_margin(v, {-1 - 0.25 / 64, 1 + 0.25 / 64, -1}, 0.5));  // a corner
  // Margin 0 is project_point's visibility, also exactly on the border (open on both sides).
  EXPECT_FALSE(inside_window_margin(v, {1, 0, -1}, 0));
  EXPECT_FALSE(project_point(v, {1, 0, -1}).visible);
  // Depth is not widened: behind the camera, nearer than near or beyond far stays outside.
  EXPECT_FALSE(inside_window_margin(v, {0, 0, 1}, 0.5));
  EXPECT_FALSE(inside_window_margin(v, {0, 0, -0.005}, 0.5));
  EXPECT_FALSE(inside_window_margin(v, {0, 0, -11}, 0.5));
  for (int i = 0; i < 5000; ++i) {  // margin 0 agrees with project_point everywhere
    const geometry::Vec3 q = geometry::make_primitive(5, geometry::Kind::kPoint, i).v[0];
    const geometry::View w = simple_view(128, 150);
    EXPECT_EQ(inside_window_margin(w, q, 0), project_point(w, q).visible) << i;
  }
}

// The reference rasterizer lights the pixel containing the projection, so its PE is at most
// sqrt(2)/2 and it is the distance to the nearest pixel centre.
TEST(PointMetrics, ReferencePeIsAtMostHalfADiagonal) {
  const geometry::View v = simple_view(907, 150);
  for (int i = 0; i < 2000; ++i) {
    const geometry::Primitive prim = geometry::make_primitive(11, geometry::Kind::kPoint, i);
    const IdealPoint p = project_point(v, prim.v[0]);
    Record rec;
    measure_point(v, p, geometry::rasterize_reference(v, prim), rec);
    if (rec.visibility == Visibility::kTrueVisible) {
      EXPECT_LE(rec.pe, std::sqrt(0.5) + 1e-12);
    } else {
      EXPECT_EQ(rec.visibility, Visibility::kTrueInvisible);
    }
  }
}

TEST(PointMetrics, RegionHoldsThePixelAndIsClampedToTheWindow) {
  const geometry::View v = simple_view();
  const geometry::PixelRect r = point_region(v, project_point(v, {0.1, 0.2, -1.0}));
  EXPECT_EQ(r.x0, 68);
  EXPECT_EQ(r.x1, 73);
  const geometry::PixelRect corner = point_region(v, project_point(v, {-0.999, -0.999, -1.0}));
  EXPECT_EQ(corner.x0, 0);
  EXPECT_EQ(corner.y0, 0);
  EXPECT_TRUE(point_region(v, project_point(v, {0, 0, 1})).empty());
}

}  // namespace
}  // namespace ra::metrics
