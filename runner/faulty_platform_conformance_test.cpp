// The faulty platform's conformance variants (snap, shift, dropped line end) measured end to end,
// as `run` measures them: the effective subpixel grid, then each case judged against it.
#include <gtest/gtest.h>

#include <cmath>

#include "metrics/conformance.h"
#include "platforms/platform.h"
#include "runner/case_measurement.h"
#include "runner/effective_subpixel.h"

namespace ra::runner {
namespace {

using namespace metrics;

// The faulty platform's conformance variants, each measured as `run` measures it. FOV 150: most
// primitives are visible.
geometry::View faulty_view() { return geometry::make_view(150, 128, 128); }

std::vector<Record> faulty_records(const rundir::FaultPlan& plan, geometry::Kind kind,
                                   geometry::SubpixelGrid* measured) {
  auto platform = platforms::create_faulty_platform(plan);
  *measured = runner::measure_effective_subpixel(*platform).grid;
  const geometry::View view = faulty_view();
  platform->set_view(view);
  std::vector<geometry::Primitive> prims;
  for (uint64_t i = 0; i < 1500; ++i) prims.push_back(geometry::make_primitive(7, kind, i));
  return runner::measure_cases("faulty", *platform, view, prims, runner::CaseComparison(true, *measured));
}

TEST(Conformance, FaultyPlatformSnappingToSixBitsIsMeasuredAndNeverAViolation) {
  rundir::FaultPlan plan;
  plan.snap_bits = 6;
  plan.snap_truncate = true;
  for (geometry::Kind kind :
       {geometry::Kind::kPoint, geometry::Kind::kLine, geometry::Kind::kTriangle}) {
    geometry::SubpixelGrid grid;
    int snapped = 0;
    for (const Record& r : faulty_records(plan, kind, &grid)) {
      if (r.status != CaseStatus::kOk) continue;
      EXPECT_TRUE(r.conformance == Conformance::kExact || r.conformance == Conformance::kSnapped)
          << geometry::kind_name(kind) << " " << r.index << " " << conformance_name(r.conformance);
      snapped += r.conformance == Conformance::kSnapped;
    }
    EXPECT_EQ(grid, geometry::SubpixelGrid(6, geometry::SnapRounding::kTruncate));
    // Truncating to a grid never moves a point across a pixel border (floor of the snapped value
    // is the floor of the value): points stay exact; lines and triangles do change.
    if (kind == geometry::Kind::kPoint)
      EXPECT_EQ(snapped, 0);
    else
      EXPECT_GT(snapped, 0) << geometry::kind_name(kind);
  }
  geometry::SubpixelGrid grid;
  faulty_records(rundir::FaultPlan{}, geometry::Kind::kPoint, &grid);
  EXPECT_TRUE(grid.exact());
}

TEST(Conformance, FaultyPlatformDroppingLineEndsIsWithinSpecShiftedPointsAreCountedExactly) {
  rundir::FaultPlan drop;
  drop.drop_line_end_fraction = 1;
  geometry::SubpixelGrid grid;
  int within = 0;
  for (const Record& r : faulty_records(drop, geometry::Kind::kLine, &grid)) {
    if (r.status != CaseStatus::kOk || r.pixels + r.ref_diff == 0) continue;
    EXPECT_EQ(r.conformance, Conformance::kWithinSpec) << r.index;
    EXPECT_EQ(r.ref_diff, 1) << r.index;
    ++within;
  }
  EXPECT_GT(within, 300);

  // Points one pixel to the right: a violation of one pixel unless the position lies within the
  // allowance of the pixel's right border (then the shifted pixel is one a snap could give).
  rundir::FaultPlan shift;
  shift.shift_fraction = 1;
  const geometry::View view = faulty_view();
  int violations = 0;
  for (const Record& r : faulty_records(shift, geometry::Kind::kPoint, &grid)) {
    if (r.visibility != Visibility::kTrueVisible) continue;
    const geometry::Vec4 c =
        view.to_clip(geometry::make_primitive(7, geometry::Kind::kPoint, r.index).v[0]);
    const double x = view.clip_to_window(c).x;
    const bool near_border = x - std::floor(x) > 1 - (0.0625 + 1e-5 * 128);
    const bool off_window = std::floor(x) + 1 >= 128;  // shifted out: nothing lit
    if (off_window) continue;
    EXPECT_EQ(r.conformance, near_border ? Conformance::kWithinSpec : Conformance::kViolation)
        << r.index;
    EXPECT_EQ(r.violating_pixels, near_border ? 0 : 1) << r.index;
    violations += r.conformance == Conformance::kViolation;
  }
  EXPECT_GT(violations, 100);
}

}  // namespace
}  // namespace ra::runner
