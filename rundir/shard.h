// Shards: the unit of work, resume and failure. A shard is one platform x kind x view x a range of
// primitive indices; its records land in one file of the run directory, atomically. Drawing a
// shard is runner/shard_session.h.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "geometry/primitive.h"
#include "rundir/records_format.h"

namespace ra::rundir {

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
  std::string records_path(const std::string& run_dir, rundir::RecordsFormat format) const;
  uint64_t size() const { return end - begin; }
};

// Every shard of the experiment, in a stable order (platform, view, kind, begin).
std::vector<Shard> plan_shards(const Experiment& exp);

}  // namespace ra::rundir
