// One case end to end through the reference platform: metrics filled for the kind, NaN and
// infinite coordinates recorded as invalid (nothing drawn), never a crash or a silent number.
#include "runner/case_measurement.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace ra {
namespace {

TEST(CaseMeasurement, NonFiniteVerticesAreInvalidCases) {
  auto platform = create_reference_platform();
  const View view = make_view(90, 64, 64);
  platform->set_view(view);
  for (Kind kind : {Kind::kPoint, Kind::kLine, Kind::kTriangle}) {
    for (double bad : {std::numeric_limits<double>::quiet_NaN(),
                       std::numeric_limits<double>::infinity()}) {
      Primitive prim = make_primitive(1, kind, 0);
      prim.v[vertex_count(kind) - 1].y = bad;
      const Record r = measure_case("reference", *platform, view, prim, true);
      EXPECT_EQ(r.status, CaseStatus::kInvalid) << kind_name(kind);
      EXPECT_EQ(r.pixels, 0);
      EXPECT_TRUE(std::isnan(r.pe) && std::isnan(r.lse_u) && std::isnan(r.te_u));
    }
  }
}

// A triangle in front of the camera, filling a known part of the window: true-visible, TE metrics
// present, and on the reference itself no difference from the reference.
TEST(CaseMeasurement, VisibleTriangleAndSegmentGetTheirMetrics) {
  auto platform = create_reference_platform();
  const View view = make_view(90, 64, 64);
  platform->set_view(view);
  Primitive tri;
  tri.kind = Kind::kTriangle;
  tri.v = {Vec3{-0.5, -0.5, -1}, Vec3{0.5, -0.5, -1}, Vec3{0, 0.5, -1}};
  const Record t = measure_case("reference", *platform, view, tri, true);
  EXPECT_EQ(t.status, CaseStatus::kOk);
  EXPECT_EQ(t.visibility, Visibility::kTrueVisible);
  EXPECT_EQ(t.ref_diff, 0);
  // Window triangle (16,16), (48,16), (32,48): area 512 px^2; TEs = |P| - area exactly.
  EXPECT_NEAR(t.te_s, double(t.pixels) - 512.0, 1e-9);
  EXPECT_GE(t.te_u, std::fabs(t.te_s));
  EXPECT_EQ(t.simply_connected, 1);
  EXPECT_EQ(t.full_window, 0);

  Primitive seg;
  seg.kind = Kind::kLine;
  seg.v = {Vec3{-0.5, -0.25, -1}, Vec3{0.5, 0.25, -1}, Vec3{}};
  const Record l = measure_case("reference", *platform, view, seg, true);
  EXPECT_EQ(l.visibility, Visibility::kTrueVisible);
  EXPECT_EQ(l.chain_8connected, 1);
  EXPECT_EQ(l.gaps, 0);
  EXPECT_LE(l.lse_s, 0.5);  // diamond-exit pixels are within half a pixel of the line
  EXPECT_NEAR(l.lse_u_norm, l.lse_u / 64.0, 1e-15);
}

}  // namespace
}  // namespace ra
