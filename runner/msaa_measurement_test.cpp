// The antialiasing condition (`osmesa-llvmpipe-msaa4`, platforms/readback_measurement.cpp) and the coverage form
// of the triangle metric (measure_triangle_coverage, triangle_metrics.h): coverage is read back as
// samples lit / 4, the metric compares it with exact pixel areas, the completeness proof still
// finds a wild pixel, and antialiasing lowers the triangle error (what it buys).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <vector>

#include "geometry/clipping.h"
#include "geometry/pixel_coverage.h"
#include "metrics/triangle_metrics.h"
#include "platforms/platform.h"
#include "runner/case_measurement.h"

namespace ra::runner {
namespace {

using namespace metrics;

rundir::PlatformSpec msaa4() { return *rundir::find_platform("osmesa-llvmpipe-msaa4"); }

// Coverage of each lit pixel of a rendering, by pixel.
std::map<geometry::Pixel, double> coverage_of(const platforms::RenderResult& r) {
  std::map<geometry::Pixel, double> out;
  size_t i = 0;
  for (geometry::Pixel p : r.lit) out[p] = double(r.samples_lit.at(i++)) / r.samples;
  EXPECT_EQ(i, r.samples_lit.size());
  return out;
}

// A view whose matrices are the identity: NDC (x, y) in [-1, 1] -> window ((x+1) W/2, (y+1) H/2),
// so window positions on pixel corners are exact.
geometry::View identity_view(int size) {
  geometry::View v = geometry::make_view(90, size, size);
  v.view_matrix = v.projection = v.view_projection = geometry::Mat4::identity();
  return v;
}

geometry::Primitive window_triangle(const geometry::View& v, geometry::Vec2 a, geometry::Vec2 b,
                                    geometry::Vec2 c) {
  geometry::Primitive p;
  p.kind = geometry::Kind::kTriangle;
  auto ndc = [&](geometry::Vec2 w) {
    return geometry::Vec3{2.0 * w.x / v.width - 1.0, 2.0 * w.y / v.height - 1.0, 0};
  };
  p.v = {ndc(a), ndc(b), ndc(c)};
  return p;
}

// The median of a non-empty sample (the mean of the middle two for an even count).
double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : (v[n / 2 - 1] + v[n / 2]) / 2;
}

TEST(OsmesaMsaa, PlatformIsInTheTableAndSoftpipeHasNone) {
  EXPECT_EQ(msaa4().samples, 4);
  EXPECT_EQ(msaa4().mesa_driver, "llvmpipe");
  EXPECT_EQ(msaa4().backend, rundir::Backend::kOsmesa);
  EXPECT_EQ(rundir::find_platform("osmesa-llvmpipe")->samples, 0);
  EXPECT_FALSE(rundir::find_platform("osmesa-softpipe-msaa4"));  // softpipe: GL_MAX_SAMPLES 1
  EXPECT_FALSE(rundir::find_platform("egl-softpipe-msaa4"));
}

// Asking for more samples than the driver has fails at creation, naming the platform and the
// driver's GL_MAX_SAMPLES (llvmpipe has 4).
TEST(OsmesaMsaa, TooManySamplesFailsWithAClearError) {
  const rundir::PlatformSpec sixteen{"osmesa-llvmpipe-msaa16", "test",
                                        rundir::Backend::kOsmesa, "llvmpipe", 16};
  try {
    platforms::create_gl_platform(sixteen);
    FAIL() << "created a 16-sample platform";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("osmesa-llvmpipe-msaa16"), std::string::npos) << what;
    EXPECT_NE(what.find("GL_MAX_SAMPLES"), std::string::npos) << what;
  }
}

// (1) A right triangle with its vertices on pixel corners, legs along the axes, hypotenuse along
// pixel diagonals: pixels inside have coverage exactly 1, outside 0, and those the hypotenuse
// halves get 2 of the 4 samples (sample offsets x + y = 0.5, 0.75 below the diagonal, 1.25, 1.5
// above it), exactly their area: TEu_cov = 0, where the aliased rendering is off by half a pixel
// on each of the 48 diagonal pixels (TEu = 24 px^2).
TEST(OsmesaMsaa, PixelCornerTriangleIsCoveredExactly) {
  const geometry::View view = identity_view(64);
  const geometry::Primitive tri = window_triangle(view, {8, 8}, {56, 8}, {8, 56});
  const geometry::ClippedPolygon poly = geometry::clip_triangle(view, tri.v[0], tri.v[1], tri.v[2]);
  ASSERT_EQ(poly.status, geometry::ClipStatus::kVisible);
  ASSERT_NEAR(poly.area, 48.0 * 48.0 / 2, 1e-9);

  auto platform = platforms::create_gl_platform(msaa4());
  platform->set_view(view);
  const platforms::RenderResult r = platform->render(tri, geometry::PixelRect{0, 0, 64, 64});
  ASSERT_EQ(r.samples, 4);
  ASSERT_EQ(r.samples_lit.size(), size_t(r.lit.size()));
  const std::map<geometry::Pixel, double> cov = coverage_of(r);
  int interior = 0, diagonal = 0;
  for (int y = 0; y < 64; ++y) {
    for (int x = 0; x < 64; ++x) {
      const auto it = cov.find({x, y});
      const double c = it == cov.end() ? 0.0 : it->second;
      const double a = geometry::pixel_area_in_convex_polygon(poly.vertices, {x, y});
      if (a == 1.0) ++interior;
      if (a == 0.5) ++diagonal;
      ASSERT_EQ(c, a) << "pixel " << x << ", " << y;
    }
  }
  EXPECT_EQ(interior, 47 * 48 / 2);
  EXPECT_EQ(diagonal, 48);

  const TriangleMetrics m =
      measure_triangle_coverage(poly, r.lit, r.samples_lit, r.samples, view.width, view.height);
  EXPECT_NEAR(m.te_unsigned, 0.0, 1e-9);
  EXPECT_NEAR(m.te_signed, 0.0, 1e-9);
  EXPECT_EQ(m.rendered, interior + diagonal);

  auto aliased = platforms::create_gl_platform(*rundir::find_platform("osmesa-llvmpipe"));
  aliased->set_view(view);
  const platforms::RenderResult ra = aliased->render(tri, geometry::PixelRect{0, 0, 64, 64});
  EXPECT_EQ(ra.samples, 0);
  EXPECT_TRUE(ra.samples_lit.empty());
  EXPECT_NEAR(measure_triangle(poly, ra.lit, 64, 64).te_unsigned, 24.0, 1e-9);
}

// (2) TEu_cov and TEs_cov of random triangles on the 4x platform against a brute-force sum over
// every window pixel of |c - a| and c - a, with a from pixel_area_in_convex_polygon (clipping the
// polygon to each pixel square: independent of the row walk of compute_coverage); and the record
// measure_cases writes carries the same numbers.
TEST(OsmesaMsaa, CoverageMetricMatchesBruteForceOnRandomTriangles) {
  auto platform = platforms::create_gl_platform(msaa4());
  int checked = 0, partial_pixels = 0;
  for (double fov : {30.0, 150.0}) {
    const geometry::View view =
        geometry::make_view(fov, 64, 64, 0.01, 10.0, geometry::random_rotation(77, 1));
    platform->set_view(view);
    for (uint64_t i = 0; i < 80; ++i) {
      const geometry::Primitive prim = geometry::make_primitive(77, geometry::Kind::kTriangle, i);
      const geometry::ClippedPolygon poly =
          geometry::clip_triangle(view, prim.v[0], prim.v[1], prim.v[2]);
      if (poly.status != geometry::ClipStatus::kVisible) continue;
      const platforms::RenderResult r =
          platform->render(prim, geometry::bounding_rect(poly, 64, 64, runner::kRegionMargin));
      if (r.lit.empty()) continue;
      // The region's count proves completeness: nothing was left lit by the previous triangle
      // (the erase by redrawing in black) and nothing lies outside.
      ASSERT_FALSE(r.full_scan) << "triangle " << i << " at FOV " << fov;
      const std::map<geometry::Pixel, double> cov = coverage_of(r);
      double te_u = 0, te_s = 0;
      for (int y = 0; y < 64; ++y) {
        for (int x = 0; x < 64; ++x) {
          const auto it = cov.find({x, y});
          const double c = it == cov.end() ? 0.0 : it->second;
          if (c > 0 && c < 1) ++partial_pixels;
          const double a = geometry::pixel_area_in_convex_polygon(poly.vertices, {x, y});
          te_u += std::fabs(c - a);
          te_s += c - a;
        }
      }
      const TriangleMetrics m =
          measure_triangle_coverage(poly, r.lit, r.samples_lit, r.samples, 64, 64);
      ASSERT_NEAR(m.te_unsigned, te_u, 1e-9) << "triangle " << i << " at FOV " << fov;
      ASSERT_NEAR(m.te_signed, te_s, 1e-9) << "triangle " << i << " at FOV " << fov;
      ASSERT_NEAR(m.te_unsigned_norm, te_u / (64.0 * 64.0), 1e-12);

      const Record rec = runner::measure_case("osmesa-llvmpipe-msaa4", *platform, view, prim, true);
      ASSERT_EQ(rec.visibility, Visibility::kTrueVisible);
      ASSERT_EQ(rec.pixels, r.lit.size());
      ASSERT_NEAR(rec.te_u, te_u, 1e-9);
      ASSERT_EQ(rec.pixel_hash, runner::rendered_pixel_hash(r));  // the same rendering twice
      ++checked;
    }
  }
  EXPECT_GE(checked, 40);
  EXPECT_GT(partial_pixels, 1000);  // the renderings really are antialiased
}

// (4) A pixel GL lights far from the primitive (inside the same occlusion query) is found on the
// 4x platform too: the samples it adds make the count disagree with the region's, and the whole
// window is read. Also: a coverage change alone changes the pixel hash.
TEST(CompletenessMsaa, AWildPixelIsFoundUnderMultisampling) {
  const geometry::View view =
      geometry::make_view(30, 128, 128, 0.01, 10.0, geometry::random_rotation(2008, 1));
  auto clean = platforms::create_gl_platform(msaa4());
  auto wild =
      platforms::create_gl_platform(msaa4(), platforms::ReadbackMethod::kRegionWithProof, {5, 40});
  clean->set_view(view);
  wild->set_view(view);
  for (geometry::Kind kind : {geometry::Kind::kPoint, geometry::Kind::kLine}) {
    std::vector<geometry::Primitive> prims;
    for (uint64_t i = 0; i < 64; ++i) prims.push_back(geometry::make_primitive(2008, kind, i));
    const std::vector<Record> c = runner::measure_cases("msaa4", *clean, view, prims, true);
    const std::vector<Record> w = runner::measure_cases("msaa4", *wild, view, prims, true);
    for (size_t i = 0; i < prims.size(); ++i) {
      const bool planted = i == 5 || i == 40;
      if (planted && c[i].pixels == 128 * 128) continue;  // no room for a wild pixel
      EXPECT_EQ(w[i].pixels, c[i].pixels + (planted ? 1 : 0))
          << geometry::kind_name(kind) << " " << i;
      EXPECT_EQ(w[i].pixel_hash == c[i].pixel_hash, !planted)
          << geometry::kind_name(kind) << " " << i;
      EXPECT_EQ(w[i].batch_size, 1);  // no batching under multisampling
    }
  }
  // A small triangle in a corner (primitive index 5: planted), the wild pixel in the opposite
  // quadrant: exactly one more pixel, wholly covered, found by the whole-window read.
  const geometry::View corner = identity_view(64);
  clean->set_view(corner);
  wild->set_view(corner);
  geometry::Primitive tri = window_triangle(corner, {4.3, 5.1}, {17.7, 6.2}, {6.1, 15.9});
  tri.index = 5;
  const geometry::PixelRegion region = geometry::PixelRect{2, 3, 20, 18};
  const platforms::RenderResult rc = clean->render(tri, region), rw = wild->render(tri, region);
  EXPECT_FALSE(rc.full_scan);
  EXPECT_TRUE(rw.full_scan);
  ASSERT_EQ(rw.lit.size(), rc.lit.size() + 1);
  const std::map<geometry::Pixel, double> cc = coverage_of(rc), cw = coverage_of(rw);
  int extra = 0;
  for (const auto& [p, c] : cw) {
    if (cc.count(p)) {
      EXPECT_EQ(c, cc.at(p));
    } else {
      ++extra;
      EXPECT_EQ(c, 1.0);  // the wild point covers all 4 samples of its pixel
      EXPECT_GE(p.x, 32);
      EXPECT_GE(p.y, 32);
    }
  }
  EXPECT_EQ(extra, 1);
  // Drawn again on the clean platform after the wild one: the erase left nothing behind.
  const platforms::RenderResult again = wild->render(
      geometry::make_primitive(1, geometry::Kind::kPoint, 0), geometry::PixelRect{0, 0, 64, 64});
  EXPECT_FALSE(again.full_scan);

  platforms::RenderResult a;
  a.samples = 4;
  a.lit = geometry::PixelSet{{1, 1}, {2, 1}};
  a.samples_lit = {4, 2};
  platforms::RenderResult b = a;
  b.samples_lit = {4, 3};
  EXPECT_NE(runner::rendered_pixel_hash(a), runner::rendered_pixel_hash(b));
  platforms::RenderResult aliased = a;
  aliased.samples = 0;
  aliased.samples_lit.clear();
  EXPECT_EQ(runner::rendered_pixel_hash(aliased), geometry::pixel_set_hash(a.lit));
}

// (5) What antialiasing buys: on the same 300 random triangles of a nist-like view (FOV 30 and
// 150, 128 x 128), the median TEu_cov-norm of the 4x platform is strictly below the median
// aliased TEu-norm.
TEST(OsmesaMsaa, MultisamplingLowersTheMedianTriangleError) {
  auto aliased = platforms::create_gl_platform(*rundir::find_platform("osmesa-llvmpipe"));
  auto msaa = platforms::create_gl_platform(msaa4());
  for (double fov : {30.0, 150.0}) {
    const geometry::View view =
        geometry::make_view(fov, 128, 128, 0.01, 10.0, geometry::random_rotation(2008, 1));
    aliased->set_view(view);
    msaa->set_view(view);
    std::vector<geometry::Primitive> prims;
    for (uint64_t i = 0; i < 300; ++i)
      prims.push_back(geometry::make_primitive(2008, geometry::Kind::kTriangle, i));
    const std::vector<Record> a = runner::measure_cases("osmesa-llvmpipe", *aliased, view, prims, true);
    const std::vector<Record> m = runner::measure_cases("osmesa-llvmpipe-msaa4", *msaa, view, prims, true);
    std::vector<double> te_a, te_m;
    for (size_t i = 0; i < prims.size(); ++i) {
      if (a[i].visibility != Visibility::kTrueVisible ||
          m[i].visibility != Visibility::kTrueVisible)
        continue;
      te_a.push_back(a[i].te_u_norm);
      te_m.push_back(m[i].te_u_norm);
    }
    ASSERT_GE(te_a.size(), 50u) << "FOV " << fov;  // 69 at FOV 30, 229 at 150
    const double med_a = median(te_a), med_m = median(te_m);
    EXPECT_LT(med_m, med_a) << "FOV " << fov;
    std::printf("FOV %g: %zu triangles, median TEu-norm aliased %.3g, 4x MSAA %.3g (%.2fx)\n", fov,
                te_a.size(), med_a, med_m, med_a / med_m);
  }
}

}  // namespace
}  // namespace ra::runner

namespace ra::metrics {
namespace {

// (3) A hand-made coverage pattern, no GL. proj(T) = (0,0), (2,0), (0,2) in a 4 x 4 window: pixel
// (0,0) has area 1, (1,0) and (0,1) area 1/2, the rest 0. Coverage (samples of 4): (0,0) 4/4,
// (1,0) 1/4, (0,1) 3/4, (1,1) 2/4 (area 0), (3,3) 4/4 (area 0):
//   TEs_cov = (1 + .25 + .75 + .5 + 1) - 2 = 1.5
//   TEu_cov = 0 + .25 + .25 + .5 + 1 = 2; coverage over area .25 + .5 + 1, area over coverage .25.
TEST(TriangleCoverage, HandMadePatternGivesHandComputedErrors) {
  geometry::ClippedPolygon poly;
  poly.status = geometry::ClipStatus::kVisible;
  poly.vertices = {{0, 0}, {2, 0}, {0, 2}};
  poly.area = 2;
  poly.orientation = 1;
  poly.on_window_border = {true, false, true};
  const geometry::PixelSet lit{{0, 0}, {1, 0}, {0, 1}, {1, 1}, {3, 3}};
  const std::vector<uint8_t> samples_lit = {4, 1, 3, 2, 4};  // (y, x) order
  const TriangleMetrics m = measure_triangle_coverage(poly, lit, samples_lit, 4, 4, 4);
  EXPECT_TRUE(m.valid);
  EXPECT_DOUBLE_EQ(m.te_signed, 1.5);
  EXPECT_DOUBLE_EQ(m.te_unsigned, 2.0);
  EXPECT_DOUBLE_EQ(m.rendered_outside, 1.75);
  EXPECT_DOUBLE_EQ(m.unrendered_inside, 0.25);
  EXPECT_DOUBLE_EQ(m.te_unsigned_norm, 2.0 / 16);
  EXPECT_DOUBLE_EQ(m.te_signed_norm, 1.5 / 16);
  EXPECT_DOUBLE_EQ(m.te_unsigned_edge_norm, 2.0 / std::sqrt(8.0));  // only the hypotenuse
  EXPECT_EQ(m.rendered, 5);
  EXPECT_EQ(m.components, 2);  // (3,3) is apart
  EXPECT_FALSE(m.simply_connected);

  // An inside pixel left uncovered counts its area: drop (0,1).
  const geometry::PixelSet lit2{{0, 0}, {1, 0}, {1, 1}, {3, 3}};
  const TriangleMetrics m2 = measure_triangle_coverage(poly, lit2, {4, 1, 2, 4}, 4, 4, 4);
  EXPECT_DOUBLE_EQ(m2.te_unsigned, 0 + .25 + .5 + .5 + 1);
  EXPECT_DOUBLE_EQ(m2.te_signed, (1 + .25 + .5 + 1) - 2);

  EXPECT_THROW(measure_triangle_coverage(poly, lit, {4, 4}, 4, 4, 4), std::invalid_argument);
}

// With every lit pixel fully covered the coverage form is the aliased metric (eqs. 9-10).
TEST(TriangleCoverage, FullCoverageEqualsTheAliasedMetric) {
  const geometry::View view = geometry::make_view(150, 96, 96, 0.01, 10.0, geometry::random_rotation(5, 2));
  auto platform = platforms::create_gl_platform(*rundir::find_platform("osmesa-llvmpipe"));
  platform->set_view(view);
  int checked = 0;
  for (uint64_t i = 0; i < 60; ++i) {
    const geometry::Primitive prim = geometry::make_primitive(5, geometry::Kind::kTriangle, i);
    const geometry::ClippedPolygon poly =
        geometry::clip_triangle(view, prim.v[0], prim.v[1], prim.v[2]);
    if (poly.status != geometry::ClipStatus::kVisible) continue;
    const platforms::RenderResult r =
        platform->render(prim, geometry::bounding_rect(poly, 96, 96, runner::kRegionMargin));
    const std::vector<uint8_t> full(size_t(r.lit.size()), 4);
    const TriangleMetrics a = measure_triangle(poly, r.lit, 96, 96);
    const TriangleMetrics c = measure_triangle_coverage(poly, r.lit, full, 4, 96, 96);
    ASSERT_NEAR(c.te_unsigned, a.te_unsigned, 1e-9) << i;
    ASSERT_NEAR(c.te_signed, a.te_signed, 1e-9) << i;
    ASSERT_EQ(c.simply_connected, a.simply_connected);
    ++checked;
  }
  EXPECT_GE(checked, 20);
}

}  // namespace
}  // namespace ra::runner
