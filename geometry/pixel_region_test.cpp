#include "geometry/pixel_region.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <random>

#include "geometry/reference_rasterizer.h"

namespace ra::geometry {
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

bool same_rect(const PixelRect& a, const PixelRect& b) {
  return a.x0 == b.x0 && a.y0 == b.y0 && a.x1 == b.x1 && a.y1 == b.y1;
}

// A triangle given in window coordinates (w = 1 clip coordinates), clipped to the window.
ClippedPolygon window_triangle(Vec2 a, Vec2 b, Vec2 c, int w, int h) {
  auto clip = [&](Vec2 p) { return Vec4{2 * p.x / w - 1, 2 * p.y / h - 1, 0, 1}; };
  return clip_triangle(clip(a), clip(b), clip(c), w, h);
}

// Every pixel within `margin` rows and columns of a pixel the reference lights, and of each
// vertex's pixel, lies in the bands (checked row by row: a convex polygon lights one run a row); the bands lie in the bounding rectangle with the same
// margin, are disjoint, and for a large triangle read much less than it.
TEST(BandRegion, HoldsTheDilatedReferenceTriangleOnRandomTriangles) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> coord(-300.0, 1200.0);
  const int w = 907, h = 907, margin = 2;
  int checked = 0;
  int64_t band_area = 0, box_area = 0;
  for (int trial = 0; trial < 120; ++trial) {
    const ClippedPolygon p = window_triangle({coord(rng), coord(rng)}, {coord(rng), coord(rng)},
                                             {coord(rng), coord(rng)}, w, h);
    if (!ideally_visible(p)) continue;
    const PixelRegion bands = band_region(p, w, h, margin, 32);
    expect_disjoint(bands);
    const PixelRect box = bounding_rect(p, w, h, margin);
    for (const PixelRect& r : bands.rects) {
      EXPECT_TRUE(box.x0 <= r.x0 && r.x1 <= box.x1 && box.y0 <= r.y0 && r.y1 <= box.y1);
      EXPECT_LE(r.y1 - r.y0, 32);
    }
    PixelSet lit = rasterize_polygon(p, w, h);
    for (const Vec2& v : p.vertices)  // the vertices' pixels too (a sliver may light none)
      lit.insert({std::min(w - 1, int(std::floor(v.x))), std::min(h - 1, int(std::floor(v.y)))});
    // Per row, the columns that must be read: the lit columns of rows within `margin`, widened by
    // `margin`; each row's band must hold them.
    std::vector<int> lo(h, w), hi(h, -1);
    for (const PixelRun& run : lit.runs())
      for (int y = std::max(0, run.y - margin); y <= std::min(h - 1, run.y + margin); ++y) {
        lo[y] = std::min(lo[y], std::max(0, run.x_begin - margin));
        hi[y] = std::max(hi[y], std::min(w - 1, run.x_end - 1 + margin));
      }
    for (int y = 0; y < h; ++y) {
      if (hi[y] < 0) continue;
      ASSERT_TRUE(bands.contains({lo[y], y}) && bands.contains({hi[y], y}))
          << "trial " << trial << " row " << y << " columns " << lo[y] << "-" << hi[y];
      for (const PixelRect& r : bands.rects)  // one band per row: the ends' band holds the row
        if (r.y0 <= y && y < r.y1) {
          EXPECT_TRUE(r.x0 <= lo[y] && hi[y] < r.x1);
        }
    }
    band_area += bands.area();
    box_area += box.area();
    ++checked;
  }
  EXPECT_GT(checked, 50);
  EXPECT_LT(double(band_area), 0.8 * double(box_area));  // triangles fill at most half their box
}

TEST(BandRegion, OneBandIsTheBoundingRectangleAndDegenerateCasesStayBounded) {
  const int w = 128, h = 128;
  const ClippedPolygon p = window_triangle({10.3, 20.7}, {100.2, 30.1}, {40.5, 90.9}, w, h);
  const PixelRegion one = band_region(p, w, h, 2, 1000);
  ASSERT_EQ(one.rects.size(), 1u);
  const PixelRect box = bounding_rect(p, w, h, 2);
  EXPECT_TRUE(same_rect(one.rects[0], box));
  // A right triangle with legs along the box: bands of 8 rows follow the hypotenuse exactly.
  const ClippedPolygon right = window_triangle({0, 0}, {128, 0}, {0, 128}, w, h);
  const PixelRegion bands = band_region(right, w, h, 0, 8);
  ASSERT_EQ(bands.rects.size(), 16u);
  EXPECT_TRUE(same_rect(bands.rects[0], {0, 0, 128, 8}));
  EXPECT_TRUE(same_rect(bands.rects[15], {0, 120, 9, 128}));  // x <= 128 - 120 = 8 at y = 120
  // A degenerate triangle (a segment) and an invisible one.
  const ClippedPolygon flat = window_triangle({10, 10}, {50, 50}, {90, 90}, w, h);
  ASSERT_EQ(flat.status, ClipStatus::kDegenerate);
  const PixelRegion seg = band_region(flat, w, h, 1, 16);
  EXPECT_TRUE(seg.contains({30, 30}));
  EXPECT_FALSE(seg.contains({80, 10}));
  EXPECT_TRUE(band_region(window_triangle({200, 200}, {300, 200}, {250, 300}, w, h), w, h, 2, 8)
                  .empty());
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
}  // namespace ra::geometry
