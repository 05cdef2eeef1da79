// Re-run and bisection of failing shards. See shard_recovery.h.
#include "runner/shard_recovery.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <stdexcept>

#include "rundir/records_reader.h"
#include "rundir/run_folder.h"
#include "util/atomic_file.h"
#include "rundir/shard_file.h"
#include "runner/case_measurement.h"

namespace fs = std::filesystem;

namespace ra::runner {

ShardRecovery::ShardRecovery(std::string run_dir, const rundir::Experiment& exp, double timeout_s)
    : run_dir_(std::move(run_dir)), exp_(exp), timeout_s_(timeout_s) {}

std::string ShardRecovery::records_dir(const WorkItem& item) const {
  return item.is_part() ? parts_dir(run_dir_) : rundir::run_folder::records(run_dir_);
}

std::vector<WorkItem> ShardRecovery::split(const WorkItem& item) {
  std::vector<WorkItem> out;
  const uint64_t mid = item.shard.begin + item.shard.size() / 2;
  for (auto [b, e] : {std::pair{item.shard.begin, mid}, std::pair{mid, item.shard.end}}) {
    WorkItem part = item;
    part.shard.begin = b;
    part.shard.end = e;
    part.attempt = std::max(item.attempt, 2);
    // A hang costs the whole timeout at every level, so parts get a share of it by size.
    const double share = timeout_s_ * double(e - b) / double(std::max<uint64_t>(1, exp_.shard_size));
    part.timeout_s = std::max(share, std::min(timeout_s_, kMinPartTimeout));
    out.push_back(part);
  }
  return out;
}

std::vector<WorkItem> ShardRecovery::on_finished(const WorkItem& item, WorkOutcome outcome,
                                                 const std::string& reason, bool* assembled) {
  if (assembled) *assembled = false;
  if (!item.is_part()) {
    if (outcome == WorkOutcome::kOk) return {};
    if (item.attempt == 1) {  // once more, as it was
      WorkItem again = item;
      again.attempt = 2;
      return {again};
    }
    // Failed twice: bisect.
    Bisection& b = bisections_[item.shard.id()];
    b = Bisection{item.shard, 0, {}, {}};
    fs::create_directories(parts_dir(run_dir_));
    WorkItem whole = item;
    whole.parent = item.shard.id();
    std::vector<WorkItem> halves = split(whole);
    b.pending = int(halves.size());
    return halves;
  }

  Bisection& b = bisections_.at(item.parent);
  std::vector<WorkItem> next;
  if (outcome == WorkOutcome::kOk) {
    b.parts.push_back(records_dir(item) + "/" + item.shard.id() +
                      rundir::records_extension(exp_.records_format));
    --b.pending;
  } else if (item.shard.size() == 1) {
    b.failed.push_back({item.parent, item.shard.begin,
                        outcome == WorkOutcome::kCrash ? metrics::CaseStatus::kCrash
                                                       : metrics::CaseStatus::kTimeout,
                        reason});
    --b.pending;
  } else {
    next = split(item);
    b.pending += int(next.size()) - 1;
  }
  if (b.pending == 0) {
    assemble(b);
    failed_.insert(failed_.end(), b.failed.begin(), b.failed.end());
    bisections_.erase(item.parent);
    if (assembled) *assembled = true;
  }
  return next;
}

void ShardRecovery::assemble(Bisection& b) {
  const geometry::View* view = nullptr;
  for (const geometry::View& v : exp_.views)
    if (v.id == b.shard.view) view = &v;
  if (!view) throw std::runtime_error("shard " + b.shard.id() + ": no such view");

  std::vector<metrics::Record> records;
  records.reserve(b.shard.size());
  for (const std::string& part : b.parts)
    rundir::read_records(part, [&](const metrics::Record& r) { records.push_back(r); });
  for (const FailedPrimitive& f : b.failed) {
    metrics::Record r = runner::case_identity(
        b.shard.platform, *view, geometry::make_primitive(exp_.seed, b.shard.kind, f.index));
    r.status = f.status;
    records.push_back(r);
  }
  std::sort(records.begin(), records.end(),
            [](const metrics::Record& x, const metrics::Record& y) { return x.index < y.index; });
  if (records.size() != b.shard.size())
    throw std::runtime_error("shard " + b.shard.id() + ": bisection assembled " +
                             std::to_string(records.size()) + " records, expected " +
                             std::to_string(b.shard.size()));
  // Written whole under a temporary name, then renamed: never half a shard in the records folder.
  const std::string path = b.shard.records_path(run_dir_, exp_.records_format);
  const std::string tmp = util::create_unique_temp(path);
  try {
    rundir::RecordsFileWriter out(tmp, exp_.records_format);
    for (const metrics::Record& r : records) out.write(r);
    out.finish();
  } catch (...) {
    std::remove(tmp.c_str());
    throw;
  }
  util::commit_file(tmp, path);
  for (const std::string& part : b.parts) fs::remove(part);
}

}  // namespace ra::runner
