// `renderaudit run`: plans the shards of an experiment, runs them in worker processes (at most
// `jobs` at once), resumes an interrupted run, enforces the per-shard timeout, shows progress and
// writes the run directory's manifest.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "runner/run_plan.h"
#include "runner/shard_recovery.h"
#include "rundir/slicing.h"

namespace ra::runner {

struct RunOptions {
  std::string experiment_path;
  std::string out_dir;          // empty: outputs/<experiment name>
  int jobs = 0;                 // 0: the number of cores
  double timeout_s = 0;         // 0: the experiment's run.shard_timeout_s
  bool progress = true;         // progress on stderr: a line rewritten on a terminal, else a
                                // whole line now and then (ProgressMeter::show)
  std::vector<std::string> only_platforms;  // non-empty: run only these platforms' shards
  std::string worker_program;   // the executable that runs `worker` (default: this one)
  std::string expect_renderer;  // non-empty: ECMAScript regex every driver's GL_RENDERER must match
  // Which shards start first: the largest expected cost (rundir/shard_cost.h; keeps every core
  // busy to the end), or plan order (platform, view, kind, begin).
  enum class ShardOrder { kLargestCostFirst, kPlan } shard_order = ShardOrder::kLargestCostFirst;
  // Run only slice K of N (rundir/slicing.h); none: the whole run.
  std::optional<rundir::Slice> slice;
  // Whole shards at their first attempt go to worker processes that serve one platform's shards
  // one after another (runner/shard_server.h); false: one process per shard
  // (re-runs and bisection parts always get a process of their own).
  bool serve_shards = true;
};


struct RunResult {
  std::string run_dir;
  size_t shards_total = 0, shards_done_before = 0, shards_run = 0;
  size_t worker_processes = 0;           // processes started (servers count once)
  size_t shards_complete = 0;            // with a records file, this or an earlier invocation
  unsigned long long primitives_total = 0;  // of every shard of the run (of its slice)
  double seconds = 0;                    // wall time of this invocation's shards
  std::vector<ShardFailure> failures;    // every worker that crashed, hung or failed (events)
  std::vector<ShardFailure> damaged;     // shard files found incomplete or damaged, then redone
  std::vector<FailedPrimitive> failed_primitives;  // recorded as crash / timeout by this invocation
  std::vector<FailedPrimitive> failed_primitives_held;  // ... in the directory's records, by anyone
  std::string wrong_renderer;            // why --expect-renderer stopped the run, or empty
  bool interrupted = false;
};

// Runs the experiment. Bad input throws UserError before anything is written.
RunResult run_experiment(const RunOptions& options);

}  // namespace ra::runner
