// Which shards a `run` holds and in which order they start: the experiment's plan, kept to the
// platforms asked for (--platform) and to one slice (--slice K/N); then, in the run directory,
// the shards an earlier invocation finished are kept as they are, a damaged records file is set
// aside and its shard redone, and the rest are queued largest expected cost first
// (rundir/shard_cost.h: every core stays busy to the end) or in plan order.
#pragma once

#include <deque>
#include <optional>
#include <string>
#include <vector>

#include "rundir/experiment.h"
#include "rundir/shard.h"
#include "runner/shard_recovery.h"
#include "rundir/slicing.h"

namespace ra::runner {

struct ShardFailure {
  std::string shard, reason;  // reason: "crashed (signal 11)", "timed out after 600 s", ...
};

// Throws UserError naming `experiment_path` when a platform of `only_platforms` is not the
// experiment's.
void require_experiment_platforms(const rundir::Experiment& exp, const std::string& experiment_path,
                                  const std::vector<std::string>& only_platforms);

// The shards of `exp`'s plan that this run holds, in plan order (platform, view, kind, begin):
// those of `only_platforms` (all when empty), of `slice` (all when none). Throws UserError when
// `slice` has more slices than the run has shards (an empty slice would be a "complete" run of
// nothing).
std::vector<rundir::Shard> shards_of_run(const rundir::Experiment& exp,
                                 const std::vector<std::string>& only_platforms,
                                 const std::optional<rundir::Slice>& slice);

struct RunQueue {
  std::deque<WorkItem> todo;             // shards to run, in start order, at their first attempt
  std::size_t done_before = 0;           // whole in DIR already: kept as they are
  std::vector<ShardFailure> damaged;     // records files found incomplete or damaged, set aside
};

// The shards of `shards` that DIR still needs. A records file that fails the seal rule
// (rundir/shard_records.h) is renamed to FILE.damaged, or FILE.damaged.2, ... when an earlier
// copy holds that name (not deleted, never over an earlier copy: it is evidence), said on
// stderr, and its shard queued; both formats of one shard are refused (util::UserError). Each
// item gets `timeout_s`.
RunQueue queue_shards(const std::vector<rundir::Shard>& shards, const rundir::Experiment& exp,
                      const std::string& dir, bool largest_cost_first, double timeout_s);

// The expected cost of `s` (rundir/shard_cost.h, microseconds); its size for a view `exp` lacks.
double expected_cost_of(const rundir::Shard& s, const rundir::Experiment& exp);

}  // namespace ra::runner
