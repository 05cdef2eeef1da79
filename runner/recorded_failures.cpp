// Failed primitives read from the records (see the header).
#include "runner/recorded_failures.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "metrics/records.h"

namespace fs = std::filesystem;

namespace ra {
namespace {

// Cell `column` of a records line (cells are never quoted: no record text holds a comma), or "".
std::string_view cell(std::string_view line, std::size_t column) {
  std::size_t begin = 0;
  for (std::size_t c = 0; c < column; ++c) {
    begin = line.find(',', begin);
    if (begin == std::string_view::npos) return {};
    ++begin;
  }
  const std::size_t end = line.find(',', begin);
  return line.substr(begin, end == std::string_view::npos ? std::string_view::npos : end - begin);
}

}  // namespace

std::string failure_key(const std::string& shard, uint64_t index) {
  return shard + "#" + std::to_string(index);
}

void add_failure_reasons(const RunManifest& manifest, std::map<std::string, std::string>* reasons) {
  if (!manifest.failed_primitives) return;
  for (const ManifestFailedPrimitive& f : *manifest.failed_primitives)
    (*reasons)[failure_key(f.shard, f.index)] = f.reason;
}

std::vector<FailedPrimitive> failed_primitives_in_records(
    const std::string& dir, const std::vector<Shard>& shards,
    const std::map<std::string, std::string>& reasons) {
  // status and index sit at the same place in every schema version
  constexpr auto kStatus = static_cast<std::size_t>(RecordColumn::kStatus);
  constexpr auto kIndex = static_cast<std::size_t>(RecordColumn::kIndex);
  const std::string crash = status_name(CaseStatus::kCrash);
  const std::string timeout = status_name(CaseStatus::kTimeout);
  std::vector<FailedPrimitive> out;
  for (const Shard& s : shards) {
    const std::string path = s.records_path(dir);
    std::ifstream in(path, std::ios::binary);
    if (!in) continue;
    std::string line;
    std::getline(in, line);  // the header
    while (std::getline(in, line)) {
      if (line.empty() || line[0] == '#') continue;
      const std::string_view status = cell(line, kStatus);
      if (status != crash && status != timeout) continue;
      FailedPrimitive f;
      f.shard = s.id();
      f.index = std::strtoull(std::string(cell(line, kIndex)).c_str(), nullptr, 10);
      f.status = status == crash ? CaseStatus::kCrash : CaseStatus::kTimeout;
      const auto it = reasons.find(failure_key(f.shard, f.index));
      f.reason = it != reasons.end() ? it->second : "recorded as " + std::string(status) + " in " + path;
      out.push_back(std::move(f));
    }
  }
  return out;
}

}  // namespace ra
