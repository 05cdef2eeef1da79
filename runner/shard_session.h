// Drawing shards: a worker process runs a shard (alone, or one after another with other shards of
// the same platform: runner/shard_server.h) through its platform, and writes its records file
// atomically.
#pragma once

#include <memory>
#include <string>

#include "platforms/platform.h"
#include "rundir/shard.h"
#include "runner/effective_subpixel.h"

namespace ra::runner {

// What the shards of one platform share in one process: the platform (its GL context, shaders
// compiled), the effective subpixel grid it measured, the driver file written once. Made at the
// first shard; a process that runs many shards pays for them once (45-65 ms on Mesa).
class ShardSession {
 public:
  ShardSession(std::string run_dir, const rundir::Experiment& exp, std::string platform);
  ~ShardSession();
  // Renders and measures every primitive of `shard` (of this session's platform), then writes
  // its records file atomically: <records_dir>/<id>.csv.zst (or .csv, as the experiment's
  // run.records_format says), records_dir defaulting to DIR/records.
  // Throws on I/O failure (the coordinator reports it) and lets a crashing driver crash the
  // process (the coordinator reports that too).
  void run(const rundir::Shard& shard, const std::string& records_dir = "");
  // Every primitive drawn alone (a batch of one): what a timing comparison draws, so that
  // render_us means the same on both sides (runner/case_measurement.h measure_cases).
  void draw_alone() { max_batch_ = 1; }

 private:
  std::string run_dir_;
  const rundir::Experiment& exp_;
  std::string platform_name_;
  std::unique_ptr<platforms::Platform> platform_;  // null until the first shard
  runner::EffectiveSubpixel effective_;
  size_t max_batch_ = 0;  // 0: measure_cases' default
};

// One shard in a session of its own (the `worker` subcommand).
void run_shard(const std::string& run_dir, const rundir::Experiment& exp, const rundir::Shard& shard,
               const std::string& records_dir = "");

}  // namespace ra::runner
