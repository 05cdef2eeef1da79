#include "rundir/shard.h"

#include <unistd.h>

#include <algorithm>

#include "rundir/experiment.h"
#include "rundir/run_folder.h"

namespace ra::rundir {

std::string Shard::id() const {
  return platform + "." + geometry::kind_name(kind) + ".v" + std::to_string(view) + "." +
         std::to_string(begin) + "-" + std::to_string(end);
}

std::string Shard::records_path(const std::string& run_dir, rundir::RecordsFormat format) const {
  return run_folder::records(run_dir) + "/" + id() + rundir::records_extension(format);
}

std::string Shard::records_path(const std::string& run_dir) const {
  const std::string compressed = records_path(run_dir, rundir::RecordsFormat::kCsvZst);
  if (::access(compressed.c_str(), F_OK) == 0) return compressed;
  const std::string plain = records_path(run_dir, rundir::RecordsFormat::kCsv);
  return ::access(plain.c_str(), F_OK) == 0 ? plain : compressed;
}

std::vector<Shard> plan_shards(const Experiment& exp) {
  std::vector<Shard> out;
  for (const auto& platform : exp.platforms)
    for (const geometry::View& v : exp.views)
      for (geometry::Kind k :
           {geometry::Kind::kPoint, geometry::Kind::kLine, geometry::Kind::kTriangle})
        for (uint64_t b = 0; b < exp.counts[int(k)]; b += exp.shard_size)
          out.push_back({platform, k, v.id, b, std::min(b + exp.shard_size, exp.counts[int(k)])});
  return out;
}

}  // namespace ra::rundir
