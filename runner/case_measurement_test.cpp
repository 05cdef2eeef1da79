// One case end to end through the reference platform: metrics filled for the kind, NaN and
// infinite coordinates recorded as invalid (nothing drawn), never a crash or a silent number; and
// batches of primitives under one completeness proof (llvmpipe) find exactly what single ones do.
#include "runner/case_measurement.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "platforms/platform.h"

namespace ra::runner {
namespace {

TEST(CaseMeasurement, NonFiniteVerticesAreInvalidCases) {
  auto platform = platforms::create_reference_platform();
  const geometry::View view = geometry::make_view(90, 64, 64);
  platform->set_view(view);
  for (geometry::Kind kind :
       {geometry::Kind::kPoint, geometry::Kind::kLine, geometry::Kind::kTriangle}) {
    for (double bad : {std::numeric_limits<double>::quiet_NaN(),
                       std::numeric_limits<double>::infinity()}) {
      geometry::Primitive prim = geometry::make_primitive(1, kind, 0);
      prim.v[geometry::vertex_count(kind) - 1].y = bad;
      const metrics::Record r = measure_case("reference", *platform, view, prim, true);
      EXPECT_EQ(r.status, metrics::CaseStatus::kInvalid) << geometry::kind_name(kind);
      EXPECT_EQ(r.pixels, 0);
      EXPECT_TRUE(std::isnan(r.pe) && std::isnan(r.lse_u) && std::isnan(r.te_u));
    }
  }
}

// A triangle in front of the camera, filling a known part of the window: true-visible, TE metrics
// present, and on the reference itself no difference from the reference.
TEST(CaseMeasurement, VisibleTriangleAndSegmentGetTheirMetrics) {
  auto platform = platforms::create_reference_platform();
  const geometry::View view = geometry::make_view(90, 64, 64);
  platform->set_view(view);
  geometry::Primitive tri;
  tri.kind = geometry::Kind::kTriangle;
  tri.v = {geometry::Vec3{-0.5, -0.5, -1}, geometry::Vec3{0.5, -0.5, -1},
           geometry::Vec3{0, 0.5, -1}};
  const metrics::Record t = measure_case("reference", *platform, view, tri, true);
  EXPECT_EQ(t.status, metrics::CaseStatus::kOk);
  EXPECT_EQ(t.visibility, metrics::Visibility::kTrueVisible);
  EXPECT_EQ(t.ref_diff, 0);
  // Window triangle (16,16), (48,16), (32,48): area 512 px^2; TEs = |P| - area exactly.
  EXPECT_NEAR(t.te_s, double(t.pixels) - 512.0, 1e-9);
  EXPECT_GE(t.te_u, std::fabs(t.te_s));
  EXPECT_EQ(t.simply_connected, 1);
  EXPECT_EQ(t.full_window, 0);

  geometry::Primitive seg;
  seg.kind = geometry::Kind::kLine;
  seg.v = {geometry::Vec3{-0.5, -0.25, -1}, geometry::Vec3{0.5, 0.25, -1}, geometry::Vec3{}};
  const metrics::Record l = measure_case("reference", *platform, view, seg, true);
  EXPECT_EQ(l.visibility, metrics::Visibility::kTrueVisible);
  EXPECT_EQ(l.chain_8connected, 1);
  EXPECT_EQ(l.gaps, 0);
  EXPECT_LE(l.lse_s, 0.5);  // diamond-exit pixels are within half a pixel of the line
  EXPECT_NEAR(l.lse_u_norm, l.lse_u / 64.0, 1e-15);
}

}  // namespace
}  // namespace ra::runner

namespace ra::runner {
namespace {

// Small primitives are drawn in batches under one occlusion query (measure_cases); the pixel sets
// must be exactly those found one primitive at a time, each with its own proof.
TEST(CaseMeasurementBatches, FindTheSamePixelsAsSinglePrimitives) {
  auto platform = platforms::create_gl_platform(*rundir::find_platform("osmesa-llvmpipe"));
  for (double fov : {30.0, 150.0}) {
    const geometry::View view =
        geometry::make_view(fov, 128, 128, 0.01, 10.0, geometry::random_rotation(2008, 1));
    platform->set_view(view);
    for (geometry::Kind kind :
         {geometry::Kind::kPoint, geometry::Kind::kLine, geometry::Kind::kTriangle}) {
      std::vector<geometry::Primitive> prims;
      for (uint64_t i = 0; i < 300; ++i) prims.push_back(geometry::make_primitive(2008, kind, i));
      const std::vector<metrics::Record> batched = measure_cases("llvmpipe", *platform, view, prims, true);
      ASSERT_EQ(batched.size(), prims.size());
      int64_t lit = 0;
      for (size_t i = 0; i < prims.size(); ++i) {
        const metrics::Record single = measure_case("llvmpipe", *platform, view, prims[i], true);
        ASSERT_EQ(batched[i].index, prims[i].index);
        ASSERT_EQ(batched[i].pixels, single.pixels) << geometry::kind_name(kind) << " " << i;
        ASSERT_EQ(batched[i].pixel_hash, single.pixel_hash)
            << geometry::kind_name(kind) << " " << i;
        ASSERT_EQ(batched[i].visibility, single.visibility);
        lit += batched[i].pixels;
      }
      EXPECT_GT(lit, 0) << geometry::kind_name(kind) << " at FOV " << fov;  // something was drawn
    }
  }
}

// A pixel lit far from one primitive of a batch (by GL, inside the batch's query) is found and
// charged to that primitive only: the batch's count disagrees, so each is drawn again alone.
TEST(CaseMeasurementBatches, AWildPixelInABatchIsChargedToItsPrimitive) {
  const geometry::View view =
      geometry::make_view(30, 128, 128, 0.01, 10.0, geometry::random_rotation(2008, 1));
  auto clean = platforms::create_gl_platform(*rundir::find_platform("osmesa-llvmpipe"));
  auto wild = platforms::create_gl_platform(*rundir::find_platform("osmesa-llvmpipe"),
                                            platforms::ReadbackMethod::kRegionWithProof, {5, 40});
  clean->set_view(view);
  wild->set_view(view);
  std::vector<geometry::Primitive> prims;
  for (uint64_t i = 0; i < 64; ++i)
    prims.push_back(geometry::make_primitive(2008, geometry::Kind::kPoint, i));
  const std::vector<metrics::Record> c = measure_cases("llvmpipe", *clean, view, prims, true);
  const std::vector<metrics::Record> w = measure_cases("llvmpipe", *wild, view, prims, true);
  for (size_t i = 0; i < prims.size(); ++i) {
    const bool planted = i == 5 || i == 40;
    EXPECT_EQ(w[i].pixels, c[i].pixels + (planted ? 1 : 0)) << i;
    EXPECT_EQ(w[i].pixel_hash == c[i].pixel_hash, !planted) << i;
  }
}

}  // namespace
}  // namespace ra::runner
