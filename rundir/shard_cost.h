// The expected cost of a shard, to start the expensive ones first. With shards run in plan order
// (platform, view, kind), a run's most expensive shards (softpipe's triangles in the 907 x 907
// windows: about 5 ms a primitive against 40 us for a point) come last and one core works alone
// at the end; largest-expected-cost-first (LPT scheduling) keeps every core busy until the last
// few shards. The model only has to rank shards, not predict seconds.
#pragma once

#include <vector>

#include "rundir/experiment.h"
#include "rundir/shard.h"

namespace ra::rundir {

// Expected microseconds of CPU for the shard: per primitive a fixed part (readback, metrics,
// reference) plus the driver's cost per pixel times the pixels a primitive of that kind lights on
// average in the view's window (points 1, lines 0.3 x the longer side, triangles 2% of the
// window). Coefficients fitted to the nist2008 views on this project's 2-core machine
// (render_us of 48,000 primitives per platform); an unknown driver is costed as
// llvmpipe.
double expected_shard_cost_us(const Shard& shard, const geometry::View& view);

// `shards` sorted by expected cost, largest first (ties keep plan order).
std::vector<Shard> largest_expected_cost_first(std::vector<Shard> shards, const Experiment& exp);

}  // namespace ra::rundir
