// What `run` does when a shard's worker crashes or hangs (the habit of Mesa's deqp-runner and
// piglit, made to name primitives): the shard is run once more (RA_RENDER_ATTEMPT=2); if it fails
// again its index range is bisected into parts (sub-shards whose records go to DIR/parts/) down to
// the single primitives that crash or hang. Those get a record with status `crash` or `timeout`,
// every other primitive its normal record, and the shard's records file is assembled from the
// parts, so one bad primitive costs one record, not a shard.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "rundir/experiment.h"
#include "metrics/records.h"
#include "rundir/run_folder.h"
#include "rundir/shard.h"

namespace ra::runner {

// One worker process to start: a whole shard, or a part of one being bisected.
struct WorkItem {
  rundir::Shard shard;         // for a part, `begin`/`end` are the part's range
  std::string parent;  // id of the whole shard a part belongs to; empty for a whole shard
  int attempt = 1;     // 2 and above: a re-run (the worker sees RA_RENDER_ATTEMPT)
  double timeout_s = 0;
  bool is_part() const { return !parent.empty(); }
};

enum class WorkOutcome { kOk, kCrash, kTimeout };

struct FailedPrimitive {
  std::string shard;  // id of the whole shard
  uint64_t index = 0;
  metrics::CaseStatus status = metrics::CaseStatus::kCrash;  // kCrash or kTimeout
  std::string reason;                      // e.g. "crashed (signal 11, Segmentation fault)"
};

class ShardRecovery {
 public:
  // `timeout_s`: the per-shard limit; a part of n primitives of a shard of N gets
  // max(timeout_s * n / N, min(timeout_s, kMinPartTimeout)).
  ShardRecovery(std::string run_dir, const rundir::Experiment& exp, double timeout_s);
  static constexpr double kMinPartTimeout = 5.0;

  static std::string parts_dir(const std::string& run_dir) {
    return rundir::run_folder::parts(run_dir);
  }
  // Where the worker for `item` writes its records: DIR/records, or DIR/parts for a part.
  std::string records_dir(const WorkItem& item) const;

  // The work that follows `item` ending with `outcome` (`reason` says how it failed): a re-run,
  // the two halves of a failed range, or nothing. When the last part of a bisected shard is
  // done, the shard's records file is written and `*assembled` set.
  std::vector<WorkItem> on_finished(const WorkItem& item, WorkOutcome outcome,
                                    const std::string& reason, bool* assembled = nullptr);

  const std::vector<FailedPrimitive>& failed_primitives() const { return failed_; }

 private:
  struct Bisection {
    rundir::Shard shard;
    int pending = 0;                  // parts started and not yet resolved
    std::vector<std::string> parts;   // records files of parts that finished
    std::vector<FailedPrimitive> failed;
  };
  std::vector<WorkItem> split(const WorkItem& item);
  void assemble(Bisection& b);

  std::string run_dir_;
  const rundir::Experiment& exp_;
  double timeout_s_;
  std::map<std::string, Bisection> bisections_;  // by whole-shard id
  std::vector<FailedPrimitive> failed_;
};

}  // namespace ra::runner
