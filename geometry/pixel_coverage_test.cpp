// Exact pixel areas of convex polygons, against closed forms and an exact rational oracle
// (rational_oracle_test.h: clipping and shoelace in exact rational arithmetic).
#include "geometry/pixel_coverage.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "geometry/clipping.h"
#include "geometry/rational_oracle_test.h"

namespace ra::geometry {
namespace {

constexpr double kAreaTol = 1e-12;  // px^2, absolute; the requirement is 1e-9

// Every pixel of the box [x0, x1) x [y0, y1) against the exact rational area.
void expect_matches_oracle(const std::vector<Vec2>& poly, int x0, int y0, int x1, int y1,
                           double tol = kAreaTol) {
  PolygonCoverage cov;
  ASSERT_TRUE(compute_coverage(poly, &cov));
  const auto q = oracle::to_q(poly);
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      const double exact = oracle::pixel_area(q, {x, y}).convert_to<double>();
      ASSERT_NEAR(cov.area(x, y), exact, tol) << "pixel " << x << "," << y;
    }
}

// Box around a polygon, one pixel of margin.
void bbox(const std::vector<Vec2>& p, int& x0, int& y0, int& x1, int& y1) {
  double a = 1e300, b = 1e300, c = -1e300, d = -1e300;
  for (const Vec2& v : p)
    a = std::min(a, v.x), b = std::min(b, v.y), c = std::max(c, v.x), d = std::max(d, v.y);
  x0 = int(std::floor(a)) - 1, y0 = int(std::floor(b)) - 1;
  x1 = int(std::floor(c)) + 2, y1 = int(std::floor(d)) + 2;
}

// A pixel square itself: edges exactly along pixel boundaries; one pixel of area exactly 1.
TEST(PixelCoverage, PixelSquareIsExactlyOnePixel) {
  PolygonCoverage cov;
  ASSERT_TRUE(compute_coverage({{2, 4}, {3, 4}, {3, 5}, {2, 5}}, &cov));
  EXPECT_EQ(cov.pixel_count(), 1);
  EXPECT_EQ(cov.area(2, 4), 1.0);
  EXPECT_EQ(cov.area(1, 4), 0.0);
  EXPECT_EQ(cov.area(3, 4), 0.0);
  EXPECT_EQ(cov.area(2, 5), 0.0);
  EXPECT_EQ(cov.total_area(), 1.0);
}

// Right triangle (0,0), (4,0), (0,4) on the grid: closed form, pixel (i, j) is 1 when
// i + j <= 2, 1/2 when i + j == 3 (cut by its diagonal), else 0. Legs along pixel boundaries.
TEST(PixelCoverage, GridRightTriangleClosedForm) {
  PolygonCoverage cov;
  ASSERT_TRUE(compute_coverage({{0, 0}, {4, 0}, {0, 4}}, &cov));
  for (int j = -1; j < 6; ++j)
    for (int i = -1; i < 6; ++i) {
      const double expect = (i < 0 || j < 0) ? 0 : i + j <= 2 ? 1 : i + j == 3 ? 0.5 : 0;
      EXPECT_NEAR(cov.area(i, j), expect, kAreaTol) << i << "," << j;
    }
  EXPECT_NEAR(cov.total_area(), 8.0, 1e-14);
}

// A horizontal top and bottom edge inside one pixel row: the run pixels are covered by the
// polygon's height in the row (0.5), not 1; closed form.
TEST(PixelCoverage, HorizontalEdgesInsideARow) {
  PolygonCoverage cov;
  ASSERT_TRUE(compute_coverage({{0.25, 0.2}, {10.75, 0.2}, {10.75, 0.7}, {0.25, 0.7}}, &cov));
  ASSERT_EQ(cov.rows.size(), 1u);
  EXPECT_NEAR(cov.rows[0].run_area, 0.5, 1e-15);
  EXPECT_NEAR(cov.area(0, 0), 0.75 * 0.5, kAreaTol);
  EXPECT_NEAR(cov.area(5, 0), 0.5, kAreaTol);
  EXPECT_NEAR(cov.area(10, 0), 0.75 * 0.5, kAreaTol);
  EXPECT_EQ(cov.area(11, 0), 0.0);
  EXPECT_NEAR(cov.total_area(), 10.5 * 0.5, 1e-13);
}

// Vertices exactly on pixel centres and on pixel edges/corners.
TEST(PixelCoverage, VerticesOnCentresAndEdges) {
  expect_matches_oracle({{0.5, 0.5}, {3.5, 0.5}, {0.5, 3.5}}, -1, -1, 5, 5);
  expect_matches_oracle({{1, 0.5}, {4, 2}, {2, 4}}, -1, -1, 6, 6);
  expect_matches_oracle({{1, 1}, {5, 1}, {5, 3}, {1, 3}}, -1, -1, 7, 5);  // all on boundaries
  expect_matches_oracle({{0, 0}, {7, 3}, {2, 5}}, -1, -1, 9, 7);          // integer vertices
}

// Vertical edges exactly on integer x inside a long row (carry-only pieces at both ends).
TEST(PixelCoverage, VerticalEdgesOnColumnBoundaries) {
  expect_matches_oracle({{3, 0.3}, {9, 1.7}, {9, 4.2}, {3, 2.6}}, 0, -1, 12, 6);
}

// Slivers with area < 1e-6 px^2, long and thin across many pixels: every pixel right to 1e-12
// absolute, and the sum equals the exact area to 1e-12 absolute (relative accuracy on a sliver is
// limited by cancellation in double, whatever the method).
TEST(PixelCoverage, Slivers) {
  const std::vector<std::vector<Vec2>> slivers = {
      {{0.1, 0.2}, {30.3, 17.7}, {30.3 + 1e-8, 17.7}},
      {{2.5, 2.5}, {2.5 + 1e-7, 20.5}, {2.5, 20.5}},  // vertical, on centres
      {{0.5, 3.0}, {25.0, 3.0 + 1e-9}, {25.0, 3.0}},  // along a pixel boundary
  };
  for (std::vector<Vec2> s : slivers) {
    if (polygon_signed_area(s) < 0) std::reverse(s.begin(), s.end());
    const double area = polygon_signed_area(s);
    ASSERT_LT(area, 1e-6);
    int x0, y0, x1, y1;
    bbox(s, x0, y0, x1, y1);
    expect_matches_oracle(s, x0, y0, x1, y1);
    PolygonCoverage cov;
    ASSERT_TRUE(compute_coverage(s, &cov));
    const double exact = (oracle::twice_area(oracle::to_q(s)) / 2).convert_to<double>();
    EXPECT_NEAR(cov.total_area(), exact, 1e-12);
  }
}

// Random triangles with random double vertices: every pixel against the exact oracle.
TEST(PixelCoverage, RandomTrianglesMatchExactOracle) {
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> u(-2, 14);
  for (int t = 0; t < 60; ++t) {
    const std::vector<Vec2> p = convex_hull({{u(rng), u(rng)}, {u(rng), u(rng)}, {u(rng), u(rng)}});
    if (p.size() < 3) continue;
    expect_matches_oracle(p, -3, -3, 16, 16);
  }
}

// Random triangles on a 1/4 grid: many vertices and edges exactly on pixel centres/boundaries.
TEST(PixelCoverage, RandomGridTrianglesMatchExactOracle) {
  std::mt19937_64 rng(5);
  std::uniform_int_distribution<int> u(-4, 48);
  for (int t = 0; t < 80; ++t) {
    auto g = [&] { return u(rng) / 4.0; };
    const std::vector<Vec2> p = convex_hull({{g(), g()}, {g(), g()}, {g(), g()}, {g(), g()}});
    if (p.size() < 3) continue;
    expect_matches_oracle(p, -2, -2, 14, 14);
  }
}

// Large coordinates (a 16384-pixel window after clipping): the partial pixels against the exact
// oracle (to 1e-10: the crossing points themselves are rounded to ulp(16384) = 3.6e-12), run
// pixels equal to 1 spot-checked, and the sum equals the shoelace area to 1e-12 relative.
TEST(PixelCoverage, HugeCoordinates) {
  const std::vector<Vec2> p = convex_hull({{0.3, 0.1}, {16383.7, 2.9}, {5.1, 16380.35}});
  PolygonCoverage cov;
  ASSERT_TRUE(compute_coverage(p, &cov));
  const auto q = oracle::to_q(p);
  for (size_t i = 0; i < cov.partial.size(); i += 97) {  // a spread sample of boundary pixels
    const CoverageRow* row = nullptr;
    for (const CoverageRow& r : cov.rows)
      if (i >= r.partial_begin && i < r.partial_end) row = &r;
    ASSERT_NE(row, nullptr);
    const double exact = oracle::pixel_area(q, {cov.partial[i].x, row->y}).convert_to<double>();
    ASSERT_NEAR(cov.partial[i].area, exact, 1e-10);
  }
  EXPECT_EQ(cov.area(100, 100), 1.0);
  const double area = polygon_signed_area(p);
  EXPECT_NEAR(cov.total_area(), area, 1e-12 * area);
}

// Property: the sum of pixel areas equals the shoelace area, 1e-9 relative, for clipped random
// triangles of a 150-degree 907 x 907 view; and each row's run lies between its partial pixels.
TEST(PixelCoverage, SumEqualsAreaForClippedTriangles) {
  const View v = make_view(150, 907, 907);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  int tested = 0;
  PolygonCoverage cov;
  for (int t = 0; t < 300; ++t) {
    const ClippedPolygon p = clip_triangle(v, {u(rng), u(rng), u(rng)}, {u(rng), u(rng), u(rng)},
                                           {u(rng), u(rng), u(rng)});
    if (p.status != ClipStatus::kVisible) continue;
    ++tested;
    ASSERT_TRUE(compute_coverage(p.vertices, &cov));
    EXPECT_NEAR(cov.total_area(), p.area, 1e-9 * p.area);
    for (const CoverageRow& r : cov.rows) {
      for (uint32_t i = r.partial_begin; i < r.partial_end; ++i) {
        EXPECT_TRUE(cov.partial[i].x < r.run_begin || cov.partial[i].x >= r.run_end);
        EXPECT_GT(cov.partial[i].area, 0.0);
        EXPECT_LE(cov.partial[i].area, 1.0);
        if (i > r.partial_begin) {
          EXPECT_LT(cov.partial[i - 1].x, cov.partial[i].x);
        }
      }
    }
  }
  EXPECT_GT(tested, 50);
}

// The per-pixel clipping helper agrees with the row algorithm.
TEST(PixelCoverage, PerPixelHelperAgrees) {
  const std::vector<Vec2> p = {{0.3, 0.1}, {9.7, 2.2}, {4.1, 8.9}};
  PolygonCoverage cov;
  ASSERT_TRUE(compute_coverage(p, &cov));
  for (int y = -1; y < 11; ++y)
    for (int x = -1; x < 11; ++x)
      EXPECT_NEAR(pixel_area_in_convex_polygon(p, {x, y}), cov.area(x, y), kAreaTol);
}

// Unusable input is refused, not measured: NaN, infinity, clockwise, non-convex, a star.
TEST(PixelCoverage, RejectsUnusablePolygons) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  PolygonCoverage cov;
  EXPECT_FALSE(compute_coverage({{0, 0}, {nan, 0}, {0, 1}}, &cov));
  EXPECT_FALSE(compute_coverage({{0, 0}, {INFINITY, 0}, {0, 1}}, &cov));
  EXPECT_FALSE(compute_coverage({{0, 0}, {0, 1}, {1, 0}}, &cov));          // clockwise
  EXPECT_FALSE(compute_coverage({{0, 0}, {4, 0}, {1, 1}, {0, 4}}, &cov));  // reflex
  EXPECT_FALSE(compute_coverage({{0, 0}, {2, 1}, {4, 0}, {3, 2}, {4, 4}, {0, 4}, {1, 2}}, &cov));
  // Five points in pentagram order: all left turns, winding twice.
  std::vector<Vec2> star;
  for (int k = 0; k < 5; ++k) {
    const double a = 2 * M_PI * (2 * k) / 5;
    star.push_back({10 + 5 * std::cos(a), 10 + 5 * std::sin(a)});
  }
  EXPECT_FALSE(compute_coverage(star, &cov));
  EXPECT_TRUE(cov.rows.empty());
}

// Fewer than three vertices or zero area: an empty coverage, not an error.
TEST(PixelCoverage, DegenerateIsEmpty) {
  PolygonCoverage cov;
  EXPECT_TRUE(compute_coverage({{1, 1}, {5, 5}}, &cov));
  EXPECT_TRUE(cov.rows.empty());
  EXPECT_TRUE(compute_coverage({{1, 1}, {3, 1}, {5, 1}}, &cov));
  EXPECT_TRUE(cov.rows.empty());
}

}  // namespace
}  // namespace ra::geometry
