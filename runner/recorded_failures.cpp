// Failed primitives read from the records (see the header).
#include "runner/recorded_failures.h"

#include <filesystem>

#include "metrics/records.h"
#include "rundir/records_reader.h"
#include "util/errors.h"

namespace fs = std::filesystem;

namespace ra::runner {
std::string failure_key(const std::string& shard, uint64_t index) {
  return shard + "#" + std::to_string(index);
}

void add_failure_reasons(const rundir::RunManifest& manifest, std::map<std::string, std::string>* reasons) {
  if (!manifest.failed_primitives) return;
  for (const rundir::ManifestFailedPrimitive& f : *manifest.failed_primitives)
    (*reasons)[failure_key(f.shard, f.index)] = f.reason;
}

std::vector<FailedPrimitive> failed_primitives_in_records(
    const std::string& dir, const std::vector<rundir::Shard>& shards,
    const std::map<std::string, std::string>& reasons) {
  const std::string crash = metrics::status_name(metrics::CaseStatus::kCrash);
  const std::string timeout = metrics::status_name(metrics::CaseStatus::kTimeout);
  std::vector<FailedPrimitive> out;
  for (const rundir::Shard& s : shards) {
    const std::string path = s.records_path(dir);
    if (!fs::exists(path)) continue;
    try {
      rundir::for_each_record_row(path, [&](const rundir::RecordRow& row) {
        const std::string_view status = row.cell(metrics::RecordColumn::kStatus);
        if (status != crash && status != timeout) return;
        FailedPrimitive f;
        f.shard = s.id();
        f.index = row.integer<uint64_t>(metrics::RecordColumn::kIndex);
        f.status = status == crash ? metrics::CaseStatus::kCrash : metrics::CaseStatus::kTimeout;
        const auto it = reasons.find(failure_key(f.shard, f.index));
        f.reason = it != reasons.end() ? it->second
                                       : "recorded as " + std::string(status) + " in " + path;
        out.push_back(std::move(f));
      });
    } catch (const util::UserError&) {
      // a damaged file: the completeness check reports it; its failures are not listed here
    }
  }
  return out;
}

}  // namespace ra::runner
