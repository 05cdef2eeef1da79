// Shards: the unit of work, resume and failure. A shard is one platform x kind x view x a range of
// primitive indices; it runs in its own process and its records land in one file, atomically.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "geometry/primitive.h"

namespace ra {

struct Experiment;

struct Shard {
  std::string platform;
  Kind kind = Kind::kPoint;
  int view = 1;                // View::id
  uint64_t begin = 0, end = 0;  // primitive indices [begin, end)

  std::string id() const;  // e.g. "osmesa-llvmpipe.point.v1.0-5000"; also the records file stem
  std::string records_path(const std::string& run_dir) const;  // DIR/records/<id>.csv
  uint64_t size() const { return end - begin; }
};

// Every shard of the experiment, in a stable order (platform, view, kind, begin).
std::vector<Shard> plan_shards(const Experiment& exp);

// Renders and measures every primitive of the shard in this process, then writes its records
// file atomically: <records_dir>/<id>.csv, records_dir defaulting to DIR/records. Throws on I/O
// failure (the coordinator reports it) and lets a crashing driver crash the process (the
// coordinator reports that too).
void run_shard(const std::string& run_dir, const Experiment& exp, const Shard& shard,
               const std::string& records_dir = "");

}  // namespace ra
