// Shards: the unit of work, resume and failure. A shard is one platform x kind x view x a range of
// primitive indices; a worker process runs it (alone, or one after another with other shards of
// the same platform: runner/shard_server.h) and its records land in one file, atomically.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "geometry/primitive.h"
#include "metrics/effective_subpixel.h"
#include "metrics/records_format.h"
#include "platforms/platform.h"

namespace ra::runner {

struct Experiment;

struct Shard {
  std::string platform;
  geometry::Kind kind = geometry::Kind::kPoint;
  int view = 1;                // View::id
  uint64_t begin = 0, end = 0;  // primitive indices [begin, end)

  std::string id() const;  // e.g. "osmesa-llvmpipe.point.v1.0-5000"; also the records file stem
  // The shard's records file in DIR/records: <id>.csv.zst or <id>.csv, whichever exists (a run may
  // hold both formats when it was resumed with another run.records_format); <id>.csv.zst if none.
  std::string records_path(const std::string& run_dir) const;
  // DIR/records/<id> with the extension of `format`.
  std::string records_path(const std::string& run_dir, metrics::RecordsFormat format) const;
  uint64_t size() const { return end - begin; }
};

// Every shard of the experiment, in a stable order (platform, view, kind, begin).
std::vector<Shard> plan_shards(const Experiment& exp);

// What the shards of one platform share in one process: the platform (its GL context, shaders
// compiled), the effective subpixel grid it measured, the driver file written once. Made at the
// first shard; a process that runs many shards pays for them once (45-65 ms on Mesa).
class ShardSession {
 public:
  ShardSession(std::string run_dir, const Experiment& exp, std::string platform);
  ~ShardSession();
  // Renders and measures every primitive of `shard` (of this session's platform), then writes
  // its records file atomically: <records_dir>/<id>.csv.zst (or .csv, as the experiment's
  // run.records_format says), records_dir defaulting to DIR/records.
  // Throws on I/O failure (the coordinator reports it) and lets a crashing driver crash the
  // process (the coordinator reports that too).
  void run(const Shard& shard, const std::string& records_dir = "");

 private:
  std::string run_dir_;
  const Experiment& exp_;
  std::string platform_name_;
  std::unique_ptr<platforms::Platform> platform_;  // null until the first shard
  metrics::EffectiveSubpixel effective_;
};

// One shard in a session of its own (the `worker` subcommand).
void run_shard(const std::string& run_dir, const Experiment& exp, const Shard& shard,
               const std::string& records_dir = "");

}  // namespace ra::runner
