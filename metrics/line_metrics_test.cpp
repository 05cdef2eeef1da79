// Line segment rendering errors LSEs / LSEu with extent errors (NIST paper, eqs. 3-7):
// hand-computed cases, short and zero-length projections, and the shape of the lit set.
#include "metrics/line_metrics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "geometry/reference_rasterizer.h"

namespace ra::metrics {
namespace {

// A visible segment between two window points (as clip_segment would give it).
geometry::ClippedSegment window_segment(geometry::Vec2 a, geometry::Vec2 b) {
  geometry::ClippedSegment s;
  s.status = (a.x == b.x && a.y == b.y) ? geometry::ClipStatus::kDegenerate
                                        : geometry::ClipStatus::kVisible;
  s.t1 = 1;
  s.p0 = a;
  s.p1 = b;
  return s;
}

// Hand-computed: e1 = (1, 1), e2 = (4, 5), so L = 5 and u = (0.6, 0.8). Lit: (1,1), (2,2), (3,3)
// with centre offsets r = (0.5, 0.5) k for k = 1, 3, 5. ds = u x r = (0.6 - 0.8) r = -0.1, -0.3,
// -0.5; mean -0.3, LSEs = 0.3. s = u . r = 1.4 r = 0.7, 2.1, 3.5: first (1,1), last (3,3);
// extent error = |0.7| + |3.5 - 5| = 2.2 (undershoot at both ends); LSEu = (0.9 + 2.2) / 5 = 0.62.
TEST(LineMetrics, HandComputedDiagonal) {
  const geometry::PixelSet lit = {{1, 1}, {2, 2}, {3, 3}};
  const LineMetrics m = measure_line(window_segment({1, 1}, {4, 5}), lit, 100, 400);
  ASSERT_TRUE(m.valid);
  EXPECT_FALSE(m.degenerate);
  EXPECT_NEAR(m.projected_length, 5, 1e-15);
  EXPECT_NEAR(m.mean_signed_offset, -0.3, 1e-14);
  EXPECT_NEAR(m.lse_signed, 0.3, 1e-14);
  EXPECT_NEAR(m.sum_abs_offset, 0.9, 1e-14);
  EXPECT_NEAR(m.start_extent, -0.7, 1e-14);
  EXPECT_NEAR(m.end_extent, -1.5, 1e-14);
  EXPECT_NEAR(m.extent_error, 2.2, 1e-14);
  EXPECT_NEAR(m.lse_unsigned, 0.62, 1e-14);
  EXPECT_NEAR(m.lse_signed_norm, 0.3 / 200, 1e-16);  // sqrt(100 * 400) = 200
  EXPECT_NEAR(m.lse_unsigned_norm, 0.62 / 200, 1e-16);
  EXPECT_EQ(m.first, (geometry::Pixel{1, 1}));
  EXPECT_EQ(m.last, (geometry::Pixel{3, 3}));
  EXPECT_TRUE(m.chain);
  EXPECT_EQ(m.gaps, 0);
}

// Hand-computed, the reference's own output: e1 = (0.5, 0.75) to e2 = (4.5, 0.75) lights
// (0..3, 0) (diamond exit: the start pixel is lit, the end one is not). ds = 0.5 - 0.75 = -0.25
// each: LSEs = 0.25; s = 0, 1, 2, 3: extent error = 0 + |3 - 4| = 1 (undershoot 1 at the end);
// LSEu = (4 * 0.25 + 1) / 6 = 1/3.
TEST(LineMetrics, HandComputedHorizontalReference) {
  const geometry::ClippedSegment s = window_segment({0.5, 0.75}, {4.5, 0.75});
  const geometry::PixelSet lit = geometry::rasterize_segment(s, 10, 10);
  ASSERT_EQ(lit, (geometry::PixelSet{{0, 0}, {1, 0}, {2, 0}, {3, 0}}));
  const LineMetrics m = measure_line(s, lit, 10, 10);
  EXPECT_NEAR(m.lse_signed, 0.25, 1e-15);
  EXPECT_NEAR(m.start_extent, 0.0, 1e-15);
  EXPECT_NEAR(m.end_extent, -1.0, 1e-15);
  EXPECT_NEAR(m.extent_error, 1.0, 1e-15);
  EXPECT_NEAR(m.lse_unsigned, 1.0 / 3, 1e-15);
}

// The direction e1 -> e2 matters: reversing it flips the sign of the mean offset and swaps the
// extents; the unsigned metrics stay.
TEST(LineMetrics, ReversingTheDirection) {
  const geometry::PixelSet lit = {{1, 1}, {2, 2}, {3, 3}};
  const LineMetrics f = measure_line(window_segment({1, 1}, {4, 5}), lit, 10, 10);
  const LineMetrics b = measure_line(window_segment({4, 5}, {1, 1}), lit, 10, 10);
  EXPECT_NEAR(b.mean_signed_offset, -f.mean_signed_offset, 1e-14);
  EXPECT_NEAR(b.start_extent, f.end_extent, 1e-14);
  EXPECT_NEAR(b.end_extent, f.start_extent, 1e-14);
  EXPECT_NEAR(b.lse_unsigned, f.lse_unsigned, 1e-14);
  EXPECT_EQ(b.first, f.last);
}

// Projected length under one pixel: the line through the ends is still well defined. Hand: e1 =
// (10.2, 10.3), e2 = (10.6, 10.6), L = 0.5, u = (0.8, 0.6); pixel (10, 10), r = (0.3, 0.2):
// ds = 0.8 * 0.2 - 0.6 * 0.3 = -0.02, s = 0.24 + 0.12 = 0.36; extent = 0.36 + |0.36 - 0.5|
// = 0.5; LSEu = (0.02 + 0.5) / 3.
TEST(LineMetrics, ShorterThanOnePixel) {
  const LineMetrics m =
      measure_line(window_segment({10.2, 10.3}, {10.6, 10.6}), {{10, 10}}, 20, 20);
  EXPECT_NEAR(m.projected_length, 0.5, 1e-13);
  EXPECT_NEAR(m.mean_signed_offset, -0.02, 1e-13);
  EXPECT_NEAR(m.extent_error, 0.5, 1e-13);
  EXPECT_NEAR(m.lse_unsigned, 0.52 / 3, 1e-13);
}

// Zero length (seen end-on): the point rule. Offsets are distances to the point: pixel (2, 3)
// with centre (2.5, 3.5) from (2.25, 3.75) is sqrt(0.125); LSEs = |mean offset vector| = the same;
// extent 0; LSEu = sqrt(0.125) / 3.
TEST(LineMetrics, ZeroLengthUsesThePoint) {
  const LineMetrics m = measure_line(window_segment({2.25, 3.75}, {2.25, 3.75}), {{2, 3}}, 8, 8);
  ASSERT_TRUE(m.valid);
  EXPECT_TRUE(m.degenerate);
  EXPECT_NEAR(m.lse_signed, std::sqrt(0.125), 1e-15);
  EXPECT_EQ(m.extent_error, 0.0);
  EXPECT_NEAR(m.lse_unsigned, std::sqrt(0.125) / 3, 1e-15);
  EXPECT_TRUE(std::isnan(m.mean_signed_offset));
  // Two pixels on opposite sides: the bias vectors cancel, the unsigned error does not.
  const LineMetrics two =
      measure_line(window_segment({2.5, 3.0}, {2.5, 3.0}), {{2, 2}, {2, 3}}, 8, 8);
  EXPECT_NEAR(two.lse_signed, 0.0, 1e-15);
  EXPECT_NEAR(two.lse_unsigned, 1.0 / 4, 1e-15);
}

// A segment nearly along the view direction, through a real 150-degree view: projected length
// under a pixel; the metrics are finite numbers (or NaN with no pixel), never garbage.
TEST(LineMetrics, NearlyAlongTheViewDirection) {
  const geometry::View v = geometry::make_view(150, 907, 907);
  const geometry::Vec3 dir{0.31, -0.17, -0.9};
  const geometry::ClippedSegment s =
      geometry::clip_segment(v, 0.2 * dir, 0.9 * dir + geometry::Vec3{1e-4, 0, 0});
  ASSERT_TRUE(geometry::ideally_visible(s));
  EXPECT_LT(s.window_length(), 1.0);
  const geometry::PixelSet lit = geometry::rasterize_segment(s, 907, 907);
  EXPECT_LE(lit.size(), 1u);
  const LineMetrics m = measure_line(s, {geometry::Pixel{int(s.p0.x), int(s.p0.y)}}, 907, 907);
  EXPECT_TRUE(std::isfinite(m.lse_unsigned));
  EXPECT_LT(m.lse_unsigned, 1.0);
}

// No lit pixel: valid geometry but undefined metrics (NaN); invisible or invalid: not valid.
TEST(LineMetrics, UndefinedCases) {
  const LineMetrics none = measure_line(window_segment({1, 1}, {5, 2}), {}, 8, 8);
  EXPECT_TRUE(none.valid);
  EXPECT_TRUE(std::isnan(none.lse_unsigned));
  EXPECT_EQ(none.components, 0);
  geometry::ClippedSegment invisible;
  EXPECT_FALSE(measure_line(invisible, {{1, 1}}, 8, 8).valid);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const geometry::ClippedSegment bad =
      geometry::clip_segment(geometry::Vec4{nan, 0, 0, 1}, geometry::Vec4{0, 0, 0, 1}, 8, 8);
  const LineMetrics m = measure_line(bad, {{1, 1}}, 8, 8);
  EXPECT_FALSE(m.valid);
  EXPECT_TRUE(std::isnan(m.lse_signed));
}

// Gaps and chains: a missing pixel breaks the chain (2 components, 1 gap); a thick corner is
// connected but not a chain.
TEST(LineMetrics, GapsAndChains) {
  const geometry::ClippedSegment s = window_segment({0.5, 0.5}, {6.5, 0.5});
  const LineMetrics gap = measure_line(s, {{0, 0}, {1, 0}, {3, 0}, {4, 0}, {5, 0}}, 10, 10);
  EXPECT_EQ(gap.components, 2);
  EXPECT_EQ(gap.gaps, 1);
  EXPECT_FALSE(gap.chain);
  const LineMetrics thick = measure_line(s, {{0, 0}, {1, 0}, {1, 1}, {2, 1}}, 10, 10);
  EXPECT_EQ(thick.gaps, 0);
  EXPECT_FALSE(thick.chain);
}

// Property of the reference: for random visible segments in a 907 x 907 150-degree view, the lit
// pixels form one chain, every offset is under half a pixel, and the ordering along the line
// starts and ends at the metric's first and last pixels.
TEST(LineMetrics, ReferenceLinesAreChainsWithSmallOffsets) {
  const geometry::View v = geometry::make_view(150, 907, 907);
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> u(-1, 1);
  int tested = 0;
  for (int t = 0; t < 400; ++t) {
    const geometry::ClippedSegment s =
        geometry::clip_segment(v, {u(rng), u(rng), u(rng)}, {u(rng), u(rng), u(rng)});
    if (s.status != geometry::ClipStatus::kVisible || s.window_length() < 2) continue;
    const geometry::PixelSet lit = geometry::rasterize_segment(s, 907, 907);
    if (lit.empty()) continue;
    ++tested;
    const LineMetrics m = measure_line(s, lit, 907, 907);
    EXPECT_TRUE(m.chain);
    EXPECT_EQ(m.gaps, 0);
    for (const geometry::Pixel& p : lit)
      EXPECT_LE(std::fabs(signed_distance_to_line({p.x + 0.5, p.y + 0.5}, s.p0, s.p1)),
                0.5 + 1e-12);
    EXPECT_LE(m.extent_error, 2 * std::sqrt(2.0) + 1e-9);  // each end within a diagonal pixel
    const std::vector<geometry::Pixel> order = order_along_line(lit, s.p0, s.p1);
    EXPECT_EQ(order.front(), m.first);
    EXPECT_EQ(order.back(), m.last);
  }
  EXPECT_GT(tested, 100);
}

// The View + Primitive entry point is clip_segment followed by the segment version.
TEST(LineMetrics, PrimitiveEntryPoint) {
  const geometry::View v = geometry::make_view(30, 128, 128);
  geometry::Primitive prim;
  prim.kind = geometry::Kind::kLine;
  prim.v = {geometry::Vec3{0.05, 0.02, -0.5}, geometry::Vec3{-0.04, 0.03, -0.6}, geometry::Vec3{}};
  const geometry::PixelSet lit = geometry::rasterize_reference(v, prim);
  const LineMetrics a = measure_line(v, prim, lit);
  const LineMetrics b =
      measure_line(geometry::clip_segment(v, prim.v[0], prim.v[1]), lit, 128, 128);
  EXPECT_EQ(a.lse_unsigned, b.lse_unsigned);
  EXPECT_EQ(a.lse_signed, b.lse_signed);
  EXPECT_TRUE(a.chain);
}

}  // namespace
}  // namespace ra::metrics
