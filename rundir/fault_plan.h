// What the `faulty` test platform injects, as read from an experiment's [faults] table
// (rundir/experiment.h parses it; platforms/faulty_platform.cpp acts on it).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "geometry/primitive.h"

namespace ra::rundir {

// Faults injected by the `faulty` test platform (the reference rasterizer plus failures), so the
// pipeline's own crash, hang and completeness handling can be tested. Indices apply to every kind
// and view.
struct FaultPlan {
  std::string base = "reference";    // the platform that draws: "reference" or an OSMesa platform
  std::vector<uint64_t> crash;       // the worker aborts on these primitive indices
  std::vector<uint64_t> hang;        // the worker sleeps forever on these
  bool hang_at_exit = false;         // ... and when its platform is torn down (a driver that hangs
                                     // in its teardown, after every record is written)
  std::vector<uint64_t> wild_pixel;  // one extra pixel lit far from the primitive
  double shift_fraction = 0;         // this fraction of primitives is drawn one pixel to the right
  double flaky_fraction = 0;         // ... shifted only on the first attempt (RA_RENDER_ATTEMPT < 2)
  // Conformance variants (outcomes known in advance, metrics/conformance.h), reference base only:
  int snap_bits = 0;                 // vertices snapped to 2^-snap_bits px first (0: exact)
  bool snap_truncate = false;        // ... truncating instead of rounding to nearest
  double drop_line_end_fraction = 0; // this fraction of lines loses its last pixel (as Bresenham)
  // A slow driver, for the speed audit's tests: each primitive's drawing takes (1 + slowdown)
  // times as long, the extra time spent inside the timed drawing (a busy wait after the base
  // platform draws), so `render_us` measures it as it would a slower driver. Only the kinds in
  // slowdown_kinds (all when empty). Without the key the reference base's render_us stays 0, which
  // keeps its records byte-identical between runs; with it (0 included) the drawing is timed.
  bool timed = false;                          // `slowdown` was given
  double slowdown = 0;                         // >= 0, dimensionless
  std::vector<geometry::Kind> slowdown_kinds;  // empty: every kind
  bool slows(geometry::Kind kind) const {
    if (slowdown_kinds.empty()) return true;
    for (geometry::Kind k : slowdown_kinds)
      if (k == kind) return true;
    return false;
  }
};

}  // namespace ra::rundir
