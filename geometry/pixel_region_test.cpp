#include "geometry/pixel_region.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <random>

#include "geometry/reference_rasterizer.h"

namespace ra {
namespace {

// A segment given in window coordinates: clip coordinates with w = 1 that map onto them.
ClippedSegment window_segment(Vec2 a, Vec2 b, int w, int h) {
  auto clip = [&](Vec2 p) { return Vec4{2 * p.x / w - 1, 2 * p.y / h - 1, 0, 1}; };
  return clip_segment(clip(a), clip(b), w, h);
}

void expect_disjoint(const PixelRegion& r) {
  for (size_t i = 0; i < r.rects.size(); ++i) {
    EXPECT_FALSE(r.rects[i].empty());
    for (size_t j = i + 1; j < r.rects.size(); ++j)
      EXPECT_FALSE(PixelRegion(r.rects[i]).overlaps(PixelRegion(r.rects[j])))
          << "rects " << i << " and " << j;
  }
}

// Every pixel within `margin` rows and columns of a pixel the reference lights is in the strip,
// and the strip lies inside the bounding box with the same margin.
TEST(StripRegion, HoldsTheDilatedReferenceLineOnRandomSegments) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> coord(-50.0, 957.0);
  const int w = 907, h = 907, margin = 2;
  int checked = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const ClippedSegment s = window_segment({coord(rng), coord(rng)}, {coord(rng), coord(rng)}, w, h);
    if (!ideally_visible(s)) continue;
    const PixelRegion strip = strip_region(s, w, h, margin);
    expect_disjoint(strip);
    const PixelRect box = bounding_rect(s, w, h, margin);
    for (const PixelRect& r : strip.rects) {
      EXPECT_GE(r.x0, box.x0); EXPECT_GE(r.y0, box.y0);
      EXPECT_LE(r.x1, box.x1); EXPECT_LE(r.y1, box.y1);
    }
    for (const Pixel p : rasterize_segment(s, w, h).pixels())
      for (int dy = -margin; dy <= margin; ++dy)
        for (int dx = -margin; dx <= margin; ++dx) {
          const Pixel q{p.x + dx, p.y + dy};
          if (q.x < 0 || q.y < 0 || q.x >= w || q.y >= h) continue;
          ASSERT_TRUE(strip.contains(q)) << "trial " << trial << " pixel " << q.x << "," << q.y;
          ++checked;
        }
  }
  EXPECT_GT(checked, 100000);
}

TEST(StripRegion, ADiagonalAcrossTheWindowReadsAThinStrip) {
  const int w = 907, h = 907;
  const ClippedSegment s = window_segment({0.5, 0.5}, {906.5, 906.5}, w, h);
  const PixelRegion strip = strip_region(s, w, h, 2);
  const int64_t box = bounding_rect(s, w, h, 2).area();
  EXPECT_EQ(box, int64_t(w) * h);
  // Rectangles about 32 px along each axis: about 907 x (32 + 1 + 2 x 2 + margin widening).
  EXPECT_LT(strip.area(), 907 * 42);
  EXPECT_GT(strip.area(), 907 * 5);
  EXPECT_EQ(strip.rects.size(), size_t((907 + 31) / 32));
}

TEST(StripRegion, AnAxisAlignedLineIsOneRectangle) {
  const int w = 907, h = 500;
  const PixelRegion horizontal = strip_region(window_segment({10.5, 100.5}, {890.5, 100.5}, w, h), w, h, 2);
  ASSERT_EQ(horizontal.rects.size(), 1u);
  const PixelRect r = horizontal.rects.front();
  EXPECT_EQ(r.x0, 8); EXPECT_EQ(r.x1, 893); EXPECT_EQ(r.y0, 98); EXPECT_EQ(r.y1, 103);
  const PixelRegion vertical = strip_region(window_segment({200.5, 3.5}, {200.5, 480.5}, w, h), w, h, 2);
  ASSERT_EQ(vertical.rects.size(), 1u);
  EXPECT_EQ(vertical.rects.front().x0, 198); EXPECT_EQ(vertical.rects.front().x1, 203);
  EXPECT_EQ(vertical.rects.front().y0, 1); EXPECT_EQ(vertical.rects.front().y1, 483);
}

TEST(StripRegion, ClampsToTheWindowAndHandlesPointLikeSegments) {
  const int w = 64, h = 48;
  // Along the window's corner: the margin is cut at the edges.
  const PixelRegion corner = strip_region(window_segment({0, 0}, {0.25, 0.125}, w, h), w, h, 2);
  ASSERT_EQ(corner.rects.size(), 1u);
  EXPECT_EQ(corner.rects.front().x0, 0); EXPECT_EQ(corner.rects.front().y0, 0);
  EXPECT_EQ(corner.rects.front().x1, 3); EXPECT_EQ(corner.rects.front().y1, 3);
  // Along the top edge, y = H exactly: the last row is H - 1.
  const PixelRegion top = strip_region(window_segment({5, 48}, {60, 48}, w, h), w, h, 1);
  ASSERT_EQ(top.rects.size(), 1u);
  EXPECT_EQ(top.rects.front().y1, 48);
  EXPECT_EQ(top.rects.front().y0, 47);
  // Invisible: nothing.
  EXPECT_TRUE(strip_region(window_segment({-30, -30}, {-10, -5}, w, h), w, h, 2).empty());
}

TEST(PixelRegion, OverlapAndContainment) {
  PixelRegion a;
  a.rects = {{0, 0, 4, 4}, {4, 2, 8, 6}};
  const PixelRegion touching(PixelRect{8, 0, 10, 10}), crossing(PixelRect{5, 5, 6, 9});
  EXPECT_FALSE(a.overlaps(touching));
  EXPECT_TRUE(a.overlaps(crossing));
  EXPECT_FALSE(a.overlaps(PixelRegion{}));
  EXPECT_TRUE(a.contains({7, 5})); EXPECT_FALSE(a.contains({7, 1})); EXPECT_FALSE(a.contains({8, 3}));
  EXPECT_EQ(a.area(), 32);
  const PixelRect b = a.bounds();
  EXPECT_EQ(b.x0, 0); EXPECT_EQ(b.y0, 0); EXPECT_EQ(b.x1, 8); EXPECT_EQ(b.y1, 6);
  EXPECT_TRUE(PixelRegion(PixelRect{3, 3, 3, 9}).empty());  // an empty rectangle is no region
}

}  // namespace
}  // namespace ra
