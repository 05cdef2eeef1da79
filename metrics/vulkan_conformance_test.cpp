// Vulkan's strict lines on hand-made cases: the reference rectangle against brute force at pixel
// centres, and the verdicts judge_rectangle_segment gives a rectangle drawn exactly, snapped,
// nudged at a side, with a wild pixel, as nothing, and cut by a window side.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "geometry/reference_rasterizer.h"
#include "metrics/conformance.h"

namespace ra::metrics {
namespace {

constexpr int kW = 64, kH = 64;

geometry::ClippedSegment segment(geometry::Vec2 a, geometry::Vec2 b) {
  geometry::ClippedSegment s;
  s.status = geometry::ClipStatus::kVisible;
  s.p0 = a, s.p1 = b;
  return s;
}

// The pixels whose centres lie strictly inside the 1 px wide rectangle from a to b, each centre
// tested on its own: distance along the segment in (0, length), across it below 1/2.
geometry::PixelSet brute_rectangle(geometry::Vec2 a, geometry::Vec2 b, int w, int h) {
  const geometry::Vec2 d = b - a;
  const double len = geometry::length(d);
  geometry::PixelSet out;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const geometry::Vec2 q = geometry::Vec2{x + 0.5, y + 0.5} - a;
      const double along = (q.x * d.x + q.y * d.y) / len, across = (q.x * d.y - q.y * d.x) / len;
      if (along > 0 && along < len && std::fabs(across) < 0.5) out.append_run(y, x, x + 1);
    }
  return out;
}

TEST(VulkanRectangleLines, TheReferenceIsThePixelCentresInsideTheRectangle) {
  // 200 segments of every slope and length (0.3 to 60 px), ends at irrational-looking places so
  // that no centre lies on a side.
  int compared = 0;
  for (int i = 0; i < 200; ++i) {
    const double t = 0.7 + i * 0.61803398875;
    const geometry::Vec2 a{5 + std::fmod(t * 37.1, 54.0), 5 + std::fmod(t * 23.3, 54.0)};
    const double len = 0.3 + std::fmod(t * 13.7, 60.0), ang = t * 2.39996;
    const geometry::Vec2 b{a.x + len * std::cos(ang), a.y + len * std::sin(ang)};
    EXPECT_EQ(geometry::rasterize_rectangle_segment(a, b, kW, kH), brute_rectangle(a, b, kW, kH))
        << i;
    ++compared;
  }
  EXPECT_EQ(compared, 200);
  // a horizontal segment of length 10 along y = 20.3: row 20 (centre 20.5 is 0.2 away), columns
  // whose centres lie in (3.2, 13.2): 3..12
  geometry::PixelSet row;
  row.append_run(20, 3, 13);
  EXPECT_EQ(geometry::rasterize_rectangle_segment({3.2, 20.3}, {13.2, 20.3}, kW, kH), row);
  EXPECT_TRUE(geometry::rasterize_rectangle_segment({3.2, 20.3}, {3.2, 20.3}, kW, kH).empty());
}

TEST(VulkanRectangleLines, VerdictsOnHandMadeRenderings) {
  const geometry::Vec2 a{5.37, 7.13}, b{50.63, 30.26};
  const geometry::ClippedSegment s = segment(a, b);
  const std::vector<AllowedVertex> ends = uniform_allowance({a, b}, kW, kH);
  const geometry::PixelSet exact = geometry::rasterize_rectangle_segment(a, b, kW, kH);
  EXPECT_EQ(judge_rectangle_segment(s, ends, kW, kH, exact, exact, {}).conformance,
            Conformance::kExact);
  // drawn on lavapipe's 8-bit grid
  const geometry::SubpixelGrid eight{8, geometry::SnapRounding::kNearest};
  const geometry::PixelSet snapped = geometry::rasterize_rectangle_segment(a, b, kW, kH, eight);
  if (snapped != exact) {
    EXPECT_EQ(judge_rectangle_segment(s, ends, kW, kH, snapped, exact, eight).conformance,
              Conformance::kSnapped);
  }
  // the rectangle moved by 0.05 px across: only centres within the allowance of a side change
  const geometry::Vec2 n{-(b.y - a.y) / geometry::length(b - a),
                         (b.x - a.x) / geometry::length(b - a)};
  const geometry::PixelSet nudged =
      geometry::rasterize_rectangle_segment(a + 0.05 * n, b + 0.05 * n, kW, kH);
  ASSERT_NE(nudged, exact);
  EXPECT_EQ(judge_rectangle_segment(s, ends, kW, kH, nudged, exact, {}).conformance,
            Conformance::kWithinSpec);
  // one pixel far from the line: a violation of one pixel
  geometry::PixelSet wild = exact;
  wild.insert({60, 2});
  const ConformanceVerdict w = judge_rectangle_segment(s, ends, kW, kH, wild, exact, {});
  EXPECT_EQ(w.conformance, Conformance::kViolation);
  EXPECT_EQ(w.violating_pixels, 1);
  EXPECT_EQ(w.violated_rules, "line-rectangle");
  // GL's diamond-exit pixels are not a strict line: those off the rectangle's sides break it
  const ConformanceVerdict diamond = judge_rectangle_segment(
      s, ends, kW, kH, geometry::rasterize_segment(a, b, kW, kH), exact, {});
  EXPECT_NE(diamond.conformance, Conformance::kExact);
  // nothing drawn: every pixel of the rectangle whose centre lies farther than the allowance
  // from each side is missing (those nearer a side may be left dark)
  const ConformanceVerdict missing = judge_rectangle_segment(s, ends, kW, kH, {}, exact, {});
  EXPECT_EQ(missing.violated_rules, "line-missing");
  const double len = geometry::length(b - a);
  const double r = std::sqrt(2.0) * ends[0].allowance + 0.5 * 2 * ends[0].allowance / len;
  int64_t deep = 0;
  for (const geometry::Pixel& px : exact) {
    const geometry::Vec2 q = geometry::Vec2{px.x + 0.5, px.y + 0.5} - a;
    const double along = (q.x * (b.x - a.x) + q.y * (b.y - a.y)) / len;
    const double across = (q.x * (b.y - a.y) - q.y * (b.x - a.x)) / len;
    deep += std::min({0.5 - std::fabs(across), along, len - along}) > r;
  }
  EXPECT_GT(deep, 30);
  EXPECT_EQ(missing.violating_pixels, deep);
}

// A segment whose far end lies outside the window, cut by the right side: the rectangle runs to
// the vertex (a guard band), and the rectangle of the cut end is allowed too.
TEST(VulkanRectangleLines, AWindowSideCutMayEndTheRectangleAtTheCut) {
  const geometry::Vec2 a{40.3, 20.2}, beyond{90.7, 23.9};
  const double t = (kW - a.x) / (beyond.x - a.x);
  const geometry::Vec2 cut{double(kW), a.y + t * (beyond.y - a.y)};
  geometry::ClippedSegment s = segment(a, cut);
  s.plane1 = geometry::kPlaneRight;
  const std::vector<AllowedVertex> ends = uniform_allowance({a, beyond}, kW, kH);
  const auto [ra, rb] = rectangle_ends(s, ends);
  EXPECT_EQ(rb.x, beyond.x);
  EXPECT_EQ(ra.x, a.x);
  const geometry::PixelSet guard = geometry::rasterize_rectangle_segment(a, beyond, kW, kH);
  const geometry::PixelSet clipped = geometry::rasterize_rectangle_segment(a, cut, kW, kH);
  EXPECT_EQ(judge_rectangle_segment(s, ends, kW, kH, guard, guard, {}).conformance,
            Conformance::kExact);
  EXPECT_NE(judge_rectangle_segment(s, ends, kW, kH, clipped, guard, {}).conformance,
            Conformance::kViolation);
}

}  // namespace
}  // namespace ra::metrics
