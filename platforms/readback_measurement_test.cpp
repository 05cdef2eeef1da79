// The readback measurement (readback_measurement.cpp) on OSMesa llvmpipe: reading only the expected
// region finds what reading the whole window finds; a region that misses pixels, or a wild pixel
// outside it, is caught by the occlusion count and the window scanned; a batch shares one proof and
// falls back to single draws when its count disagrees; draw-only reads nothing; the multisample
// platform reports each pixel's covered samples.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "geometry/clipping.h"
#include "geometry/pixel_region.h"
#include "geometry/pixel_set.h"
#include "platforms/platform.h"
#include "platforms/window_view_testing.h"

namespace ra::platforms {
namespace {

using geometry::Pixel;
using geometry::PixelRect;
using geometry::PixelRegion;
using geometry::PixelSet;
using geometry::Vec2;

rundir::PlatformSpec llvmpipe() { return *rundir::find_platform("osmesa-llvmpipe"); }

using testing::window_view;

geometry::Primitive triangle(Vec2 a, Vec2 b, Vec2 c, uint64_t index = 0) {
  return testing::window_primitive(geometry::Kind::kTriangle, {a, b, c}, index);
}

// The clipped primitive's window bounding box grown by two pixels (what the runner reads).
PixelRegion expected_region(const geometry::View& view, const geometry::Primitive& prim) {
  switch (prim.kind) {
    case geometry::Kind::kPoint: {
      const geometry::Vec4 c = view.to_clip(prim.v[0]);
      if (!(c.w > 0)) return {};
      const Vec2 w = view.clip_to_window(c);
      const PixelRect r{int(std::floor(w.x)) - 2, int(std::floor(w.y)) - 2,
                        int(std::floor(w.x)) + 3, int(std::floor(w.y)) + 3};
      return PixelRect{std::max(r.x0, 0), std::max(r.y0, 0), std::min(r.x1, view.width),
                       std::min(r.y1, view.height)};
    }
    case geometry::Kind::kLine:
      return geometry::bounding_rect(geometry::clip_segment(view, prim.v[0], prim.v[1]),
                                     view.width, view.height, 2);
    case geometry::Kind::kTriangle:
      return geometry::bounding_rect(geometry::clip_triangle(view, prim.v[0], prim.v[1], prim.v[2]),
                                     view.width, view.height, 2);
  }
  return {};
}

// Random primitives of every kind through a rotated 150-degree view: the region with its proof
// finds exactly what clearing and reading the whole window finds, and never needs the window.
TEST(ReadbackMeasurement, TheProvenRegionFindsWhatTheWholeWindowFinds) {
  auto region = create_gl_platform(llvmpipe(), ReadbackMethod::kRegionWithProof);
  auto window = create_gl_platform(llvmpipe(), ReadbackMethod::kFullWindow);
  const geometry::View view =
      geometry::make_view(150, 96, 96, 0.01, 10.0, geometry::random_rotation(2008, 1));
  region->set_view(view);
  window->set_view(view);
  int64_t pixels = 0;
  for (geometry::Kind kind :
       {geometry::Kind::kPoint, geometry::Kind::kLine, geometry::Kind::kTriangle})
    for (uint64_t i = 0; i < 60; ++i) {
      const geometry::Primitive prim = geometry::make_primitive(2008, kind, i);
      const PixelRegion expected = expected_region(view, prim);
      const RenderResult r = region->render(prim, expected);
      const RenderResult w = window->render(prim, PixelRegion());
      ASSERT_EQ(r.lit, w.lit) << geometry::kind_name(kind) << " " << i;
      EXPECT_FALSE(r.full_scan) << geometry::kind_name(kind) << " " << i;
      EXPECT_TRUE(w.full_scan);
      EXPECT_EQ(r.batch_size, 1);
      pixels += r.lit.size();
    }
  EXPECT_GT(pixels, 1000);  // the comparison saw real drawings
}

// A region that misses the primitive (empty, or one corner pixel): the count of fragments exceeds
// what the region holds, so the window is scanned, and nothing is missed.
TEST(ReadbackMeasurement, ARegionThatMissesPixelsIsCaughtAndTheWindowScanned) {
  auto platform = create_gl_platform(llvmpipe());
  const geometry::View view = window_view(32);
  platform->set_view(view);
  const geometry::Primitive t = triangle({3.25, 2.75}, {28.5, 9.125}, {11.75, 29.5});
  const RenderResult proven = platform->render(t, expected_region(view, t));
  ASSERT_FALSE(proven.full_scan);
  ASSERT_GT(proven.lit.size(), 200);
  for (const PixelRegion& wrong : {PixelRegion(), PixelRegion(PixelRect{0, 0, 1, 1}),
                                   PixelRegion(PixelRect{3, 3, 20, 20})}) {
    const RenderResult r = platform->render(t, wrong);
    EXPECT_TRUE(r.full_scan);
    EXPECT_EQ(r.lit, proven.lit);
  }
}

// A test fault lights one more pixel, in the quadrant opposite the region's centre, inside the
// same occlusion query: the proof fails, the window is scanned and the pixel charged to that
// primitive only. Region [4, 20) x [2, 18): centre (12, 10), wild pixel (12 + 16, 10 + 16).
TEST(ReadbackMeasurement, AWildPixelOutsideTheRegionIsFoundByTheCount) {
  auto clean = create_gl_platform(llvmpipe());
  auto wild = create_gl_platform(llvmpipe(), ReadbackMethod::kRegionWithProof, {7});
  const geometry::View view = window_view(32);
  clean->set_view(view);
  wild->set_view(view);
  const PixelRegion region(PixelRect{4, 2, 20, 18});
  const geometry::Primitive planted = triangle({5.5, 3.25}, {18.75, 4.5}, {9.125, 16.5}, 7);
  geometry::Primitive unplanted = planted;
  unplanted.index = 8;
  const PixelSet drawn = clean->render(planted, region).lit;
  ASSERT_GT(drawn.size(), 50);
  const RenderResult r = wild->render(planted, region);
  EXPECT_TRUE(r.full_scan);
  PixelSet want = drawn;
  want.insert({28, 26});
  EXPECT_EQ(r.lit, want);
  const RenderResult other = wild->render(unplanted, region);
  EXPECT_FALSE(other.full_scan);
  EXPECT_EQ(other.lit, drawn);
}

// Small triangles with disjoint regions, drawn as one batch under one count: each finds what it
// finds alone, each carries the batch's size and an equal share of its time. Two that overlap
// (the second covers pixels of the first) make the count disagree: the batch is drawn again one
// primitive at a time.
TEST(ReadbackMeasurement, ABatchSharesOneProofAndFallsBackWhenItsPrimitivesOverlap) {
  auto platform = create_gl_platform(llvmpipe());
  const geometry::View view = window_view(64);
  platform->set_view(view);
  std::vector<geometry::Primitive> prims;
  std::vector<PixelRegion> regions;
  for (int k = 0; k < 6; ++k) {
    const double x = 2 + 10 * k, y = 3 + 9 * k;
    prims.push_back(triangle({x + 0.25, y + 0.5}, {x + 6.75, y + 1.25}, {x + 2.5, y + 6.125},
                             uint64_t(k)));
    regions.push_back(expected_region(view, prims.back()));
  }
  std::vector<PixelSet> single;
  for (size_t i = 0; i < prims.size(); ++i) single.push_back(platform->render(prims[i], regions[i]).lit);
  const std::vector<RenderResult> batch = platform->render_batch(prims, regions);
  ASSERT_EQ(batch.size(), prims.size());
  for (size_t i = 0; i < prims.size(); ++i) {
    EXPECT_GT(single[i].size(), 5) << i;
    EXPECT_EQ(batch[i].lit, single[i]) << i;
    EXPECT_EQ(batch[i].batch_size, 6) << i;
    EXPECT_EQ(batch[i].render_us, batch[0].render_us) << i;
    EXPECT_FALSE(batch[i].full_scan) << i;
  }

  const std::vector<geometry::Primitive> overlapping = {prims[0], prims[0]};
  const std::vector<RenderResult> again =
      platform->render_batch(overlapping, {regions[0], regions[0]});
  ASSERT_EQ(again.size(), 2u);
  for (const RenderResult& r : again) {
    EXPECT_EQ(r.lit, single[0]);
    EXPECT_EQ(r.batch_size, 1);
  }
}

// Draw only (the benchmark's floor): nothing is read, one by one or in a batch (whose time is
// shared); the whole-window method reads everything and says so.
TEST(ReadbackMeasurement, DrawOnlyReadsNothingAndTheWholeWindowMethodReadsEverything) {
  auto floor = create_gl_platform(llvmpipe(), ReadbackMethod::kDrawOnly);
  auto window = create_gl_platform(llvmpipe(), ReadbackMethod::kFullWindow);
  auto proven = create_gl_platform(llvmpipe());
  const geometry::View view = window_view(32);
  floor->set_view(view);
  window->set_view(view);
  proven->set_view(view);
  const geometry::Primitive t = triangle({3.25, 2.75}, {28.5, 9.125}, {11.75, 29.5});
  const RenderResult f = floor->render(t, expected_region(view, t));
  EXPECT_TRUE(f.lit.empty());
  EXPECT_FALSE(f.full_scan);
  EXPECT_GE(f.render_us, 0.0);
  const std::vector<RenderResult> fb =
      floor->render_batch({t, t, t}, {expected_region(view, t), PixelRegion(), PixelRegion()});
  ASSERT_EQ(fb.size(), 3u);
  for (const RenderResult& r : fb) {
    EXPECT_TRUE(r.lit.empty());
    EXPECT_EQ(r.batch_size, 3);
    EXPECT_EQ(r.render_us, fb[0].render_us);
  }
  const RenderResult w = window->render(t, PixelRegion());
  EXPECT_TRUE(w.full_scan);
  EXPECT_EQ(w.lit, proven->render(t, expected_region(view, t)).lit);
  // The whole window is cleared for each: a second, smaller primitive finds only its own pixels.
  const geometry::Primitive small = triangle({1.5, 1.5}, {4.5, 1.5}, {1.5, 4.5});
  EXPECT_EQ(window->render(small, PixelRegion()).lit,
            proven->render(small, expected_region(view, small)).lit);
}

// What the driver says about itself: llvmpipe, snapping to a subpixel grid, no samples.
TEST(ReadbackMeasurement, ReportsTheDriverItDrawsWith) {
  auto platform = create_gl_platform(llvmpipe());
  const DriverInfo info = platform->driver_info();
  EXPECT_NE(info.renderer.find("llvmpipe"), std::string::npos) << info.renderer;
  EXPECT_GT(info.subpixel_bits, 0);
  EXPECT_NE(info.backend.find("OSMesa"), std::string::npos) << info.backend;
}

// 4x multisampling: a right triangle with its legs on pixel borders, (2, 2) (10, 2) (2, 10), covers
// the 28 pixels below its hypotenuse wholly (4 samples each) and cuts the 8 pixels x + y = 11 (x, y
// >= 2) through their corners: each has some but not all samples. Pixels are reported in (y, x)
// order with their counts; region and whole-window methods agree.
TEST(ReadbackMeasurement, TheMultisamplePlatformReportsTheSamplesEachPixelCovers) {
  const rundir::PlatformSpec msaa4 = *rundir::find_platform("osmesa-llvmpipe-msaa4");
  auto region = create_gl_platform(msaa4);
  auto window = create_gl_platform(msaa4, ReadbackMethod::kFullWindow);
  const geometry::View view = window_view(16);
  region->set_view(view);
  window->set_view(view);
  const geometry::Primitive t = triangle({2, 2}, {10, 2}, {2, 10});
  const RenderResult r = region->render(t, expected_region(view, t));
  EXPECT_EQ(r.samples, 4);
  ASSERT_EQ(r.samples_lit.size(), size_t(r.lit.size()));
  size_t i = 0, full = 0, cut = 0;
  for (Pixel p : r.lit) {
    const int k = r.samples_lit[i++];
    ASSERT_TRUE(p.x >= 2 && p.y >= 2 && p.x + p.y <= 11) << p.x << ", " << p.y;
    if (p.x + p.y <= 10) {
      EXPECT_EQ(k, 4) << p.x << ", " << p.y;
      ++full;
    } else {
      EXPECT_TRUE(k >= 1 && k <= 3) << p.x << ", " << p.y << ": " << k;
      ++cut;
    }
  }
  EXPECT_EQ(full, 28u);
  EXPECT_EQ(cut, 8u);
  const RenderResult w = window->render(t, PixelRegion());
  EXPECT_TRUE(w.full_scan);
  EXPECT_EQ(w.lit, r.lit);
  EXPECT_EQ(w.samples_lit, r.samples_lit);
}

}  // namespace
}  // namespace ra::platforms
