// The `reference` platform (reference_platform.cpp) through the Platform interface: its triangles
// against a brute-force top-left rule over every pixel centre, its lines against a brute-force
// diamond-exit rule, its points against floor(); exact ties (edges through pixel centres), a
// sliver, a zero-area triangle; and what it says about itself.
//
// The view maps world (x, y, -1) to window (x, y) exactly (a 16 x 16 window, dyadic coordinates),
// so the brute force below works on the very window coordinates the platform rasterizes.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>
#include <vector>

#include "geometry/pixel_region.h"
#include "geometry/pixel_set.h"
#include "platforms/platform.h"
#include "platforms/window_view_testing.h"

namespace ra::platforms {
namespace {

using geometry::Pixel;
using geometry::PixelSet;
using geometry::Vec2;

constexpr int kSize = 16;

geometry::View window_view() { return testing::window_view(kSize); }

geometry::Primitive primitive(geometry::Kind kind, std::vector<Vec2> window_points) {
  return testing::window_primitive(kind, window_points);
}

PixelSet draw(geometry::Kind kind, std::vector<Vec2> window_points) {
  auto platform = create_reference_platform();
  platform->set_view(window_view());
  const geometry::PixelRegion whole(geometry::PixelRect{0, 0, kSize, kSize});
  return platform->render(primitive(kind, std::move(window_points)), whole).lit;
}

double cross2(Vec2 a, Vec2 b) { return a.x * b.y - a.y * b.x; }

// Every pixel centre of the window inside the triangle, by the top-left rule written out: the
// triangle taken counter-clockwise (interior on the left of each directed edge), a centre on an edge
// is inside when that edge goes down (a left edge) or is horizontal going left (a top edge). With
// coordinates on a fine dyadic grid every product below is exact in doubles.
PixelSet brute_force_triangle(Vec2 a, Vec2 b, Vec2 c) {
  const double twice_area = cross2({b.x - a.x, b.y - a.y}, {c.x - a.x, c.y - a.y});
  if (twice_area == 0) return {};
  if (twice_area < 0) std::swap(b, c);
  const Vec2 v[3] = {a, b, c};
  std::vector<Pixel> lit;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const Vec2 q{x + 0.5, y + 0.5};
      bool inside = true;
      for (int e = 0; e < 3 && inside; ++e) {
        const Vec2 p0 = v[e], p1 = v[(e + 1) % 3];
        const Vec2 d{p1.x - p0.x, p1.y - p0.y};
        const double side = cross2(d, {q.x - p0.x, q.y - p0.y});
        const bool top_left = d.y < 0 || (d.y == 0 && d.x < 0);
        inside = side > 0 || (side == 0 && top_left);
      }
      if (inside) lit.push_back({x, y});
    }
  return PixelSet::from_pixels(lit);
}

double l1(Vec2 a, Vec2 b) { return std::fabs(a.x - b.x) + std::fabs(a.y - b.y); }

// The smallest L1 distance from f to the segment a -> b: a convex piecewise-linear function of the
// segment parameter, whose minimum lies at an end or where x or y crosses f's.
double l1_to_segment(Vec2 a, Vec2 b, Vec2 f) {
  std::vector<double> ts = {0, 1};
  if (b.x != a.x) ts.push_back((f.x - a.x) / (b.x - a.x));
  if (b.y != a.y) ts.push_back((f.y - a.y) / (b.y - a.y));
  double best = INFINITY;
  for (double t : ts) {
    t = std::clamp(t, 0.0, 1.0);
    best = std::min(best, l1({a.x + t * (b.x - a.x), a.y + t * (b.y - a.y)}, f));
  }
  return best;
}

// The diamond-exit rule written out for a segment that comes nowhere near a tie: pixel f is lit
// when the segment enters its open diamond |x - fx| + |y - fy| < 1/2 and does not end inside it.
// Fails the test when a distance lies within 1e-9 of 1/2 (then the spec's perturbation decides,
// which this brute force does not model).
PixelSet brute_force_segment(Vec2 a, Vec2 b) {
  std::vector<Pixel> lit;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const Vec2 f{x + 0.5, y + 0.5};
      const double meets = l1_to_segment(a, b, f), end = l1(b, f);
      EXPECT_GT(std::fabs(meets - 0.5), 1e-9) << "a tie at pixel " << x << ", " << y;
      EXPECT_GT(std::fabs(end - 0.5), 1e-9) << "a tie at pixel " << x << ", " << y;
      if (meets < 0.5 && end >= 0.5) lit.push_back({x, y});
    }
  return PixelSet::from_pixels(lit);
}

// Triangles of both windings with vertices on a quarter- and eighth-pixel grid: many centres fall
// exactly on edges, and the platform lights exactly the centres the written-out rule lights.
TEST(ReferencePlatform, LightsTheTriangleCentresTheTopLeftRuleLightsByBruteForce) {
  const std::vector<std::array<Vec2, 3>> triangles = {
      {{{1.5, 1.5}, {12.5, 3.5}, {5.5, 13.5}}},            // vertices on centres, counter-clockwise
      {{{1.5, 1.5}, {5.5, 13.5}, {12.5, 3.5}}},            // the same, clockwise
      {{{0.25, 0.75}, {15.75, 8.5}, {3.125, 15.875}}},     // a large one, general position
      {{{2.5, 9.5}, {10.5, 9.5}, {6.5, 1.5}}},             // a horizontal top edge through centres
      {{{2.5, 1.5}, {10.5, 1.5}, {6.5, 9.5}}},             // a horizontal bottom edge through centres
      {{{3.5, 0.5}, {3.5, 12.5}, {11.25, 6.375}}},         // a vertical left edge through centres
      {{{11.5, 0.5}, {11.5, 12.5}, {2.75, 6.625}}},        // a vertical right edge through centres
      {{{0.5, 0.5}, {8.5, 4.5}, {4.5, 8.5}}},              // slopes 1/2 and 2 through centres
  };
  for (const auto& t : triangles) {
    const PixelSet want = brute_force_triangle(t[0], t[1], t[2]);
    EXPECT_FALSE(want.empty());
    EXPECT_EQ(draw(geometry::Kind::kTriangle, {t[0], t[1], t[2]}), want)
        << "(" << t[0].x << ", " << t[0].y << ") (" << t[1].x << ", " << t[1].y << ") ("
        << t[2].x << ", " << t[2].y << ")";
  }
}

// The square of centres [0.5, 4.5]^2 cut along its diagonal, by hand: the lower triangle keeps its
// left edge (x = 0.5) and drops its bottom edge and the diagonal, the upper one keeps its top edge
// (y = 4.5) and the diagonal (a left edge for it) and drops its right edge. Together they light
// the 4 x 4 pixels of the half-open square once each.
TEST(ReferencePlatform, ADiagonalThroughPixelCentresLightsEachCentreOnce) {
  const PixelSet lower = draw(geometry::Kind::kTriangle, {{0.5, 0.5}, {4.5, 0.5}, {0.5, 4.5}});
  const PixelSet upper = draw(geometry::Kind::kTriangle, {{4.5, 0.5}, {4.5, 4.5}, {0.5, 4.5}});
  EXPECT_EQ(lower, (PixelSet{{0, 1}, {1, 1}, {2, 1}, {0, 2}, {1, 2}, {0, 3}}));
  EXPECT_EQ(upper, (PixelSet{{3, 1}, {2, 2}, {3, 2}, {1, 3}, {2, 3}, {3, 3},
                             {0, 4}, {1, 4}, {2, 4}, {3, 4}}));
  EXPECT_EQ(geometry::symmetric_difference_size(lower, upper), lower.size() + upper.size());
  std::vector<Pixel> square;
  for (int y = 1; y <= 4; ++y)
    for (int x = 0; x <= 3; ++x) square.push_back({x, y});
  std::vector<Pixel> both = lower.pixels();
  for (Pixel p : upper) both.push_back(p);
  EXPECT_EQ(PixelSet::from_pixels(both), PixelSet::from_pixels(square));
}

// A sliver 2^-10 px tall along row 2's centres: below the row it has a bottom edge through the
// sixteen centres and lights nothing; mirrored above the row, the same edge is a top edge and
// lights all sixteen, although the sliver's area is under 1/100 px^2.
TEST(ReferencePlatform, ASliverAlongPixelCentresLightsThemOnlyWhenTheyLieOnItsTopEdge) {
  const double e = 0x1p-10;
  const PixelSet above = draw(geometry::Kind::kTriangle, {{0.25, 2.5}, {15.75, 2.5}, {8, 2.5 + e}});
  const PixelSet below = draw(geometry::Kind::kTriangle, {{0.25, 2.5}, {8, 2.5 - e}, {15.75, 2.5}});
  EXPECT_TRUE(above.empty());
  std::vector<Pixel> row;
  for (int x = 0; x < 16; ++x) row.push_back({x, 2});
  EXPECT_EQ(below, PixelSet::from_pixels(row));
  EXPECT_EQ(below, brute_force_triangle({0.25, 2.5}, {8, 2.5 - e}, {15.75, 2.5}));
  // Off the centres, a sliver that thin covers none.
  EXPECT_TRUE(draw(geometry::Kind::kTriangle, {{0.25, 2.25}, {15.75, 2.25}, {8, 2.25 + e}}).empty());
}

// Collinear or repeated vertices: no area, nothing drawn, even along a row of centres.
TEST(ReferencePlatform, AZeroAreaTriangleDrawsNothing) {
  EXPECT_TRUE(draw(geometry::Kind::kTriangle, {{0.5, 2.5}, {8.5, 2.5}, {15.5, 2.5}}).empty());
  EXPECT_TRUE(draw(geometry::Kind::kTriangle, {{1.5, 1.5}, {7.5, 7.5}, {13.5, 13.5}}).empty());
  EXPECT_TRUE(draw(geometry::Kind::kTriangle, {{3.5, 3.5}, {3.5, 3.5}, {9.25, 12.75}}).empty());
  EXPECT_TRUE(draw(geometry::Kind::kTriangle, {{4.5, 4.5}, {4.5, 4.5}, {4.5, 4.5}}).empty());
}

// Segments in every direction, x-major and y-major, clear of ties: the pixels the written-out
// diamond-exit rule gives, one per column (x-major) or row (y-major) crossed.
TEST(ReferencePlatform, LightsThePixelsWhoseDiamondsTheSegmentLeavesByBruteForce) {
  const std::vector<std::pair<Vec2, Vec2>> segments = {
      {{1.3, 2.2}, {13.7, 6.1}},     // x-major, up and right
      {{14.3, 1.35}, {2.65, 12.7}},  // y-major, up and left
      {{3.35, 14.3}, {12.35, 3.3}},  // y-major, down and right
      {{0.7, 7.7}, {15.3, 8.35}},    // nearly horizontal
      {{9.35, 15.3}, {8.7, 0.35}},   // nearly vertical, down
      {{12.7, 12.65}, {1.3, 1.7}},   // near the diagonal, down and left
  };
  for (const auto& [a, b] : segments) {
    const PixelSet want = brute_force_segment(a, b);
    EXPECT_EQ(draw(geometry::Kind::kLine, {a, b}), want)
        << "(" << a.x << ", " << a.y << ") -> (" << b.x << ", " << b.y << ")";
    const bool x_major = std::fabs(b.x - a.x) >= std::fabs(b.y - a.y);
    std::vector<int> majors;
    for (Pixel p : want) majors.push_back(x_major ? p.x : p.y);
    std::sort(majors.begin(), majors.end());
    EXPECT_EQ(std::adjacent_find(majors.begin(), majors.end()), majors.end())
        << "two pixels in one column or row";
  }
}

// By hand: centre to centre, the first pixel is lit and the last is not; in reverse, the other
// way round. A zero-length segment lights nothing.
TEST(ReferencePlatform, ALineFromCentreToCentreLightsItsStartButNotItsEnd) {
  EXPECT_EQ(draw(geometry::Kind::kLine, {{0.5, 0.5}, {4.5, 0.5}}),
            (PixelSet{{0, 0}, {1, 0}, {2, 0}, {3, 0}}));
  EXPECT_EQ(draw(geometry::Kind::kLine, {{4.5, 0.5}, {0.5, 0.5}}),
            (PixelSet{{1, 0}, {2, 0}, {3, 0}, {4, 0}}));
  EXPECT_EQ(draw(geometry::Kind::kLine, {{7.5, 2.5}, {7.5, 6.5}}),
            (PixelSet{{7, 2}, {7, 3}, {7, 4}, {7, 5}}));
  EXPECT_TRUE(draw(geometry::Kind::kLine, {{6.3, 6.3}, {6.3, 6.3}}).empty());
}

// A point lights the pixel holding it (floor of its window position, a pixel border belonging to
// the pixel right of or above it); outside the window, or on its right border, nothing.
TEST(ReferencePlatform, APointLightsThePixelHoldingIt) {
  EXPECT_EQ(draw(geometry::Kind::kPoint, {{5.3, 9.7}}), (PixelSet{{5, 9}}));
  EXPECT_EQ(draw(geometry::Kind::kPoint, {{3, 0.125}}), (PixelSet{{3, 0}}));
  EXPECT_EQ(draw(geometry::Kind::kPoint, {{15.875, 15.875}}), (PixelSet{{15, 15}}));
  EXPECT_TRUE(draw(geometry::Kind::kPoint, {{16, 4.5}}).empty());
  EXPECT_TRUE(draw(geometry::Kind::kPoint, {{-0.25, 4.5}}).empty());
}

// An exact rasterizer that reads nothing back: no subpixel grid, every result complete by
// construction, aliased, one primitive per draw; a batch draws what single draws draw. The
// `reference` platform spec creates the same platform.
TEST(ReferencePlatform, SaysItIsExactAndEveryResultIsComplete) {
  auto platform = create_platform(*rundir::find_platform("reference"), rundir::FaultPlan{});
  const DriverInfo info = platform->driver_info();
  EXPECT_EQ(info.renderer, "renderaudit reference rasterizer");
  EXPECT_EQ(info.subpixel_bits, 0);
  EXPECT_FALSE(info.timer_query);
  EXPECT_TRUE(std::isnan(platform->measure_timer_over_cpu()));
  platform->set_view(window_view());
  const std::vector<geometry::Primitive> prims = {
      primitive(geometry::Kind::kTriangle, {{1.5, 1.5}, {12.5, 3.5}, {5.5, 13.5}}),
      primitive(geometry::Kind::kLine, {{1.3, 2.2}, {13.7, 6.1}}),
      primitive(geometry::Kind::kPoint, {{5.3, 9.7}})};
  // The region is a hint the reference ignores: an empty one changes nothing.
  const std::vector<geometry::PixelRegion> nowhere(prims.size());
  const std::vector<RenderResult> batch = platform->render_batch(prims, nowhere);
  ASSERT_EQ(batch.size(), 3u);
  EXPECT_EQ(batch[0].lit, brute_force_triangle({1.5, 1.5}, {12.5, 3.5}, {5.5, 13.5}));
  EXPECT_EQ(batch[1].lit, brute_force_segment({1.3, 2.2}, {13.7, 6.1}));
  EXPECT_EQ(batch[2].lit, (PixelSet{{5, 9}}));
  for (const RenderResult& r : batch) {
    EXPECT_TRUE(r.full_scan);
    EXPECT_EQ(r.samples, 0);
    EXPECT_TRUE(r.samples_lit.empty());
    EXPECT_EQ(r.batch_size, 1);
    EXPECT_GE(r.render_us, 0.0);
  }
}

}  // namespace
}  // namespace ra::platforms
