// Slices: a run cut into N disjoint parts that any scheduler can run on N machines
// (`run --slice K/N`), then gathered with `renderaudit merge`. The cut is deterministic (every
// machine computes the same one from the experiment alone) and balanced by expected cost
// (rundir/shard_cost.h), not by count: a 907 x 907 softpipe triangle shard costs hundreds of times
// a 128 x 128 point shard.
#pragma once

#include <string>
#include <vector>

#include "rundir/experiment.h"
#include "rundir/shard.h"

namespace ra::rundir {

struct Slice {
  int index = 1;  // 1-based
  int count = 1;
};

// Parses "K/N" (1 <= K <= N <= 100000). Throws ra::util::UserError "--slice 'TEXT': ..." otherwise.
Slice parse_slice(const std::string& text);

// The shards of slice K of N: shards assigned largest expected cost first, each to the slice with
// the least expected cost so far (ties: the lower slice), then returned in plan order. Every shard
// of `shards` is in exactly one slice.
std::vector<Shard> shards_of_slice(const std::vector<Shard>& shards, const Experiment& exp,
                                   const Slice& slice);

// The expected cost of each slice, microseconds (rundir/shard_cost.h), for messages and checks.
// Used by tests as an independent check that slices balance their cost.
std::vector<double> slice_costs(const std::vector<Shard>& shards, const Experiment& exp, int count);

}  // namespace ra::rundir
