// Conformance verdicts on hand-made cases whose class and count are known: a sliver that 4-bit
// snapping lights, a hole and a one-pixel shift in a triangle, a Bresenham that drops one or two
// end pixels, a doubled column, a point snapped across a pixel border.
#include "metrics/conformance.h"

#include <gtest/gtest.h>

#include <cmath>

namespace ra::metrics {
namespace {

constexpr int kW = 64, kH = 64;

geometry::ClippedPolygon polygon(std::vector<geometry::Vec2> ccw) {
  geometry::ClippedPolygon p;
  p.status = geometry::ClipStatus::kVisible;
  p.vertices = std::move(ccw);
  p.area = 1;
  p.orientation = 1;
  p.on_window_border.assign(p.vertices.size(), false);
  return p;
}

geometry::ClippedSegment segment(geometry::Vec2 a, geometry::Vec2 b) {
  geometry::ClippedSegment s;
  s.status = geometry::ClipStatus::kVisible;
  s.p0 = a, s.p1 = b;
  return s;
}

// Window position (x, y) at depth 0 as clip coordinates (w = 1).
geometry::Vec4 clip_of(double x, double y) { return {2 * x / kW - 1, 2 * y / kH - 1, 0, 1}; }

const geometry::SubpixelGrid kExact{}, kFour{4, geometry::SnapRounding::kNearest};

TEST(Conformance, ASliverThatFourBitSnappingLightsIsWithinSpecOrSnapped) {
  // Exact: no centre inside (x = 10.5 lies left of the edge x = 10.51). Snapped to 1/16 px the
  // left edge moves to x = 10.5, a left edge, so the centres of column 10 on it are inside.
  const geometry::ClippedPolygon sliver = polygon({{10.51, 2}, {10.6, 2}, {10.51, 40}});
  const geometry::PixelSet exact = geometry::rasterize_polygon(sliver, kW, kH);
  const geometry::PixelSet snapped = geometry::rasterize_polygon(sliver, kW, kH, kFour);
  ASSERT_TRUE(exact.empty());
  ASSERT_EQ(snapped.size(), 38);  // rows 2..39 of column 10
  for (const geometry::Pixel& p : snapped) EXPECT_EQ(p.x, 10);
  const ConformanceVerdict v = judge_polygon(sliver, kW, kW, kH, snapped, exact, kExact);
  EXPECT_EQ(v.conformance, Conformance::kWithinSpec);
  EXPECT_EQ(v.violating_pixels, 0);
  EXPECT_EQ(judge_polygon(sliver, kW, kW, kH, snapped, exact, kFour).conformance,
            Conformance::kSnapped);
  EXPECT_EQ(judge_polygon(sliver, kW, kW, kH, exact, exact, kFour).conformance,
            Conformance::kExact);
}

TEST(Conformance, AHoleInATriangleIsAViolationOfOnePixel) {
  const geometry::ClippedPolygon t = polygon({{2, 2}, {40, 2}, {2, 40}});
  const geometry::PixelSet exact = geometry::rasterize_polygon(t, kW, kH);
  geometry::PixelSet lit = exact;
  lit.erase({12, 10});
  geometry::PixelSet where;
  const ConformanceVerdict v = judge_polygon(t, kW, kW, kH, lit, exact, kFour, &where);
  EXPECT_EQ(v.conformance, Conformance::kViolation);
  EXPECT_EQ(v.violating_pixels, 1);
  EXPECT_EQ(v.violated_rules, "polygon-edge");
  EXPECT_EQ(where, (geometry::PixelSet{{12, 10}}));
}

TEST(Conformance, ATriangleShiftedByOnePixelViolatesWhereCentresLieBeyondTheAllowance) {
  const geometry::Vec2 a{3.3, 4.1}, b{41.7, 6.2}, c{9.4, 37.9};
  const geometry::ClippedPolygon t = polygon({a, b, c});
  const geometry::PixelSet exact = geometry::rasterize_polygon(t, kW, kH);
  geometry::PixelSet lit = exact;
  lit.translate(1, 0);
  // Brute force: a differing pixel is allowed when its centre lies within sqrt(2) x the allowance
  // of one of the three edge lines' segments (distance by the area formula and the ends).
  const double allow = std::sqrt(2.0) * (0.0625 + 1e-5 * kW);
  auto dist = [](geometry::Vec2 q, geometry::Vec2 p0, geometry::Vec2 p1) {
    const double len = std::hypot(p1.x - p0.x, p1.y - p0.y);
    const double t = ((q.x - p0.x) * (p1.x - p0.x) + (q.y - p0.y) * (p1.y - p0.y)) / (len * len);
    if (t <= 0) return std::hypot(q.x - p0.x, q.y - p0.y);
    if (t >= 1) return std::hypot(q.x - p1.x, q.y - p1.y);
    return std::fabs((p1.x - p0.x) * (q.y - p0.y) - (p1.y - p0.y) * (q.x - p0.x)) / len;
  };
  int64_t expected = 0, differing = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      if (exact.contains({x, y}) == lit.contains({x, y})) continue;
      ++differing;
      const geometry::Vec2 q{x + 0.5, y + 0.5};
      if (std::min({dist(q, a, b), dist(q, b, c), dist(q, c, a)}) > allow) ++expected;
    }
  ASSERT_GT(expected, 20);  // the left side's column, at least
  ASSERT_LT(expected, differing);  // some pixels along the right side are within the allowance
  const ConformanceVerdict v = judge_polygon(t, kW, kW, kH, lit, exact, kExact);
  EXPECT_EQ(v.conformance, Conformance::kViolation);
  EXPECT_EQ(v.violating_pixels, expected);
}

TEST(Conformance, ABresenhamThatDropsItsLastPixelIsWithinSpecTwoAreNot) {
  const geometry::ClippedSegment s = segment({2.3, 3.2}, {20.7, 9.9});  // x-major
  const geometry::PixelSet exact = geometry::rasterize_segment(s, kW, kH);
  ASSERT_EQ(exact.size(), 19);  // one fragment per column 2..20 (the end's diamond holds 20.5?)
  geometry::Pixel last = exact.front();
  for (const geometry::Pixel& p : exact)
    if (p.x > last.x) last = p;
  geometry::PixelSet lit = exact;
  lit.erase(last);
  ConformanceVerdict v = judge_segment(s, 21, kW, kH, lit, exact, kExact);
  EXPECT_EQ(v.conformance, Conformance::kWithinSpec);
  EXPECT_EQ(v.violating_pixels, 0);
  geometry::Pixel second = lit.front();
  for (const geometry::Pixel& p : lit)
    if (p.x > second.x) second = p;
  lit.erase(second);
  v = judge_segment(s, 21, kW, kH, lit, exact, kExact);
  EXPECT_EQ(v.conformance, Conformance::kViolation);
  EXPECT_EQ(v.violating_pixels, 1);  // rule 2: 17 fragments where diamond-exit has 19
  EXPECT_EQ(v.violated_rules, "line-count");
}

TEST(Conformance, TwoFragmentsInAColumnOrOneTwoRowsOffAreViolations) {
  const geometry::ClippedSegment s = segment({2.3, 3.2}, {20.7, 9.9});
  const geometry::PixelSet exact = geometry::rasterize_segment(s, kW, kH);
  geometry::PixelSet lit = exact;
  const geometry::Pixel first = exact.front();
  lit.insert({first.x, first.y + 1});  // rule 1 holds (one row off), rule 2 too (one more)
  geometry::PixelSet where;
  ConformanceVerdict v = judge_segment(s, 21, kW, kH, lit, exact, kExact, &where);
  EXPECT_EQ(v.conformance, Conformance::kViolation);
  EXPECT_EQ(v.violating_pixels, 1);
  EXPECT_EQ(v.violated_rules, "line-column");
  EXPECT_EQ(where.size(), 2);  // both fragments of that column
  // A middle fragment moved two rows up: rule 1 (and rule 3 does not see it: still one a column).
  lit = exact;
  const geometry::Pixel mid = exact.pixels()[9];
  lit.erase(mid);
  lit.insert({mid.x, mid.y + 2});
  v = judge_segment(s, 21, kW, kH, lit, exact, kExact, &where);
  EXPECT_EQ(v.conformance, Conformance::kViolation);
  EXPECT_EQ(v.violating_pixels, 1);
  EXPECT_EQ(v.violated_rules, "line-deviation");
  EXPECT_EQ(where, (geometry::PixelSet{{mid.x, mid.y + 2}}));
  // The same segment one pixel to the right: rule 1 allows it.
  lit = exact;
  lit.translate(1, 0);
  EXPECT_EQ(judge_segment(s, 21, kW, kH, lit, exact, kExact).conformance,
            Conformance::kWithinSpec);
}

TEST(Conformance, PointsSnappedAcrossAPixelBorderShiftedOrMissing) {
  // x = 10.99: exact pixel 10; a 4-bit nearest snap gives 11.0, pixel 11.
  geometry::Vec4 c = clip_of(10.99, 5.3);
  const geometry::PixelSet exact = geometry::rasterize_point(c, kW, kH);
  ASSERT_EQ(exact, (geometry::PixelSet{{10, 5}}));
  const geometry::PixelSet eleven{{11, 5}};
  EXPECT_EQ(judge_point(c, kW, kH, eleven, exact, kFour).conformance, Conformance::kSnapped);
  EXPECT_EQ(judge_point(c, kW, kH, eleven, exact, kExact).conformance, Conformance::kWithinSpec);
  ConformanceVerdict v =
      judge_point(c, kW, kH, geometry::PixelSet{{10, 5}, {11, 5}}, exact, kExact);
  EXPECT_EQ(v.conformance, Conformance::kViolation);
  EXPECT_EQ(v.violated_rules, "point-count");
  // x = 10.5: pixel 11 is beyond any snap; nothing at all is not allowed either.
  c = clip_of(10.5, 5.5);
  v = judge_point(c, kW, kH, eleven, geometry::rasterize_point(c, kW, kH), kFour);
  EXPECT_EQ(v.conformance, Conformance::kViolation);
  EXPECT_EQ(v.violating_pixels, 1);
  EXPECT_EQ(v.violated_rules, "point-pixel");
  v = judge_point(c, kW, kH, geometry::PixelSet{}, geometry::rasterize_point(c, kW, kH), kFour);
  EXPECT_EQ(v.violated_rules, "point-missing");
  // Within the allowance of the window's left side, a point may be culled.
  c = clip_of(0.01, 20.5);
  EXPECT_EQ(
      judge_point(c, kW, kH, geometry::PixelSet{}, geometry::rasterize_point(c, kW, kH), kExact)
          .conformance,
      Conformance::kWithinSpec);
}

// Drawn as nothing, or as half of itself: a primitive the reference lights across the window is
// a violation when no placement of its vertices within their allowances lets it vanish. Built
// through judge_primitive, as `run` and `show` judge a record.
geometry::Primitive line_of(geometry::Vec3 a, geometry::Vec3 b) {
  geometry::Primitive p;
  p.kind = geometry::Kind::kLine;
  p.v = {a, b, geometry::Vec3{}};
  return p;
}

geometry::PixelSet columns_below(const geometry::PixelSet& s, int32_t x_end) {
  std::vector<geometry::Pixel> kept;
  for (const geometry::Pixel& p : s)
    if (p.x < x_end) kept.push_back(p);
  return geometry::PixelSet::from_pixels(kept);
}

TEST(Conformance, ASegmentCutByTwoWindowSidesDrawnAsNothingIsMissing) {
  // Both ends beyond the window's sides: rule 2 cannot count the fragments the window discards,
  // and rules 1 and 3 hold for an empty set. The count inside the window must still be there.
  const geometry::View view = geometry::make_view(30, 907, 907);
  const geometry::Primitive line = line_of({-5, 0.1, -3}, {5, 0.13, -3});
  const geometry::PixelSet exact = geometry::rasterize_reference(view, line);
  ASSERT_EQ(exact.size(), 907);  // one pixel per column, across the whole window
  const ConformanceVerdict v = judge_primitive(view, line, geometry::PixelSet{}, kExact);
  EXPECT_EQ(v.conformance, Conformance::kViolation);
  EXPECT_EQ(v.violated_rules, "line-missing");
  EXPECT_GE(v.violating_pixels, 890);  // all but the columns near the window's sides
  EXPECT_LE(v.violating_pixels, 904);
}

TEST(Conformance, ASegmentCutByTwoWindowSidesDrawnAsHalfOfItselfIsAViolation) {
  const geometry::View view = geometry::make_view(30, 907, 907);
  const geometry::Primitive line = line_of({-5, 0.1, -3}, {5, 0.13, -3});
  const geometry::PixelSet exact = geometry::rasterize_reference(view, line);
  geometry::PixelSet where;
  const ConformanceVerdict v =
      judge_primitive(view, line, columns_below(exact, 453), kExact, &where);
  EXPECT_EQ(v.conformance, Conformance::kViolation);
  EXPECT_EQ(v.violated_rules, "line-window-count");
  EXPECT_GE(v.violating_pixels, 440);
  EXPECT_LE(v.violating_pixels, 454);
  // The missing reference pixels are named, all in the right half.
  EXPECT_GE(where.size(), 440);
  for (const geometry::Pixel& p : where) EXPECT_GE(p.x, 453);
}

TEST(Conformance, ASegmentCutByTwoWindowSidesKeepsItsFreedom) {
  // What GL allows stays within spec: one row up (rule 1), two fragments fewer at the sides (the
  // window discards a fragment that a shifted end moves out).
  const geometry::View view = geometry::make_view(30, 907, 907);
  const geometry::Primitive line = line_of({-5, 0.1, -3}, {5, 0.13, -3});
  const geometry::PixelSet exact = geometry::rasterize_reference(view, line);
  std::vector<geometry::Pixel> up, trimmed;
  for (const geometry::Pixel& p : exact) {
    up.push_back({p.x, p.y + 1});
    if (p.x > 0 && p.x < 906) trimmed.push_back(p);
  }
  EXPECT_EQ(judge_primitive(view, line, geometry::PixelSet::from_pixels(up), kExact).conformance,
            Conformance::kWithinSpec);
  EXPECT_EQ(
      judge_primitive(view, line, geometry::PixelSet::from_pixels(trimmed), kExact).conformance,
      Conformance::kWithinSpec);
}

TEST(Conformance, ATriangleMissingFarFromEveryBoundaryIsAViolationWhateverItsFarVertex) {
  // A near plane at 10^-5 and a vertex just in front of it, ~4e7 px to the right. An allowance of
  // eps times that for every edge (400 px) let the whole triangle vanish; the edges near the
  // window keep their own small allowance, widening only towards the far vertex.
  const geometry::View view = geometry::make_view(30, 907, 907, 1e-5, 10.0);
  geometry::Primitive t;
  t.kind = geometry::Kind::kTriangle;
  t.v = {geometry::Vec3{-0.02, -0.02, -0.5}, geometry::Vec3{0.02, -0.02, -0.5},
         geometry::Vec3{0.5, 0.3, -2e-5}};
  const geometry::PixelSet exact = geometry::rasterize_reference(view, t);
  ASSERT_GT(exact.size(), 30000);
  const ConformanceVerdict v = judge_primitive(view, t, geometry::PixelSet{}, kExact);
  EXPECT_EQ(v.conformance, Conformance::kViolation);
  EXPECT_EQ(v.violated_rules, "polygon-missing");
  EXPECT_GT(v.violating_pixels, exact.size() * 9 / 10);
}

TEST(Conformance, APointMissingFarFromEveryBoundaryIsAViolation) {
  const geometry::View view = geometry::make_view(30, 128, 128);
  geometry::Primitive p;
  p.kind = geometry::Kind::kPoint;
  p.v = {geometry::Vec3{0.01, 0.02, -2.0}, geometry::Vec3{}, geometry::Vec3{}};
  ASSERT_EQ(geometry::rasterize_reference(view, p).size(), 1);
  const ConformanceVerdict v = judge_primitive(view, p, geometry::PixelSet{}, kExact);
  EXPECT_EQ(v.conformance, Conformance::kViolation);
  EXPECT_EQ(v.violated_rules, "point-missing");
}

}  // namespace
}  // namespace ra::metrics
