#include "audit/audit_compare.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "analysis/run_records.h"
#include "metrics/headline_metric.h"
#include "rundir/records_reader.h"
#include "util/errors.h"
#include "rundir/experiment.h"
#include "rundir/run_experiment.h"
#include "rundir/shard.h"
#include "rundir/shard_records.h"

namespace fs = std::filesystem;

namespace ra::audit {
namespace {

struct Row {
  uint64_t index = 0;
  PrimitiveState state;
};

// The records of one platform, kind and view of a run, ascending by index.
std::vector<Row> read_view(const std::string& dir, const std::vector<rundir::Shard>& plan,
                           const std::string& platform, geometry::Kind kind, int view) {
  std::vector<Row> rows;
  for (const rundir::Shard& s : plan) {
    if (s.platform != platform || s.kind != kind || s.view != view) continue;
    // a damaged file stops the audit (the seal rule, rundir/shard_records.h); a missing one is
    // reported by missing_shards()
    const std::string path = rundir::trusted_records_path(dir, s);
    if (path.empty()) continue;
    rundir::read_records(path, [&](const metrics::Record& r) {
      if (r.platform != platform || r.kind != geometry::kind_name(kind) || r.view != view ||
          r.index < s.begin || r.index >= s.end)
        throw util::UserError(path + ": holds a record of " + r.platform + " " + r.kind + " view " +
                              std::to_string(r.view) + " index " + std::to_string(r.index) +
                              ", outside its shard");
      rows.push_back(
          {r.index,
           {r.status, r.visibility, r.pixels, r.pixel_hash, metrics::headline_value(r, kind), r.ref_diff,
            r.conformance, r.violating_pixels}});
    });
  }
  std::sort(rows.begin(), rows.end(), [](const Row& a, const Row& b) { return a.index < b.index; });
  return rows;
}

bool failed_status(metrics::CaseStatus s) {
  return s == metrics::CaseStatus::kCrash || s == metrics::CaseStatus::kTimeout;
}

struct Task {
  std::size_t pair;
  geometry::Kind kind;
  int view, view_group;
};

struct TaskResult {
  ViewCounts counts;
  std::vector<ChangedPrimitive> changed;
  std::vector<FailedPrimitive> failed;
};

TaskResult compare_view(const std::string& baseline_dir,
                        const std::vector<rundir::Shard>& baseline_plan,
                        const std::string& current_dir,
                        const std::vector<rundir::Shard>& current_plan, const PlatformPair& pair,
                        const Task& t, bool compare_verdicts) {
  TaskResult out;
  out.counts = {t.pair, t.kind, t.view, t.view_group, 0, 0, 0, 0};
  std::vector<Row> before = read_view(baseline_dir, baseline_plan, pair.baseline, t.kind, t.view);
  if (!compare_verdicts)  // judged by other rules: only pixels, visibility and status compare
    for (Row& r : before) r.state.conformance = metrics::Conformance::kNotCompared;
  const std::vector<Row> after = read_view(current_dir, current_plan, pair.current, t.kind, t.view);
  auto note_failure = [&](const Row& r, const char* side, const std::string& platform) {
    if (failed_status(r.state.status))
      out.failed.push_back(
          {t.pair, side, platform, t.kind, t.view, t.view_group, r.index, r.state.status});
  };
  // Merge-join on the index: both are ascending.
  std::size_t i = 0, j = 0;
  while (i < before.size() || j < after.size()) {
    if (j == after.size() || (i < before.size() && before[i].index < after[j].index)) {
      ++out.counts.unmatched;
      note_failure(before[i++], "baseline", pair.baseline);
      continue;
    }
    if (i == before.size() || after[j].index < before[i].index) {
      ++out.counts.unmatched;
      note_failure(after[j++], "current", pair.current);
      continue;
    }
    const Row& b = before[i++];
    const Row& a = after[j++];
    ++out.counts.compared;
    if (failed_status(b.state.status) || failed_status(a.state.status)) {
      ++out.counts.failed;
      note_failure(b, "baseline", pair.baseline);
      note_failure(a, "current", pair.current);
      continue;
    }
    if (!states_differ(b.state, a.state)) continue;
    ++out.counts.changed;
    out.changed.push_back({t.pair, t.kind, t.view, t.view_group, a.index, b.state, a.state,
                           Recheck::kNotRerendered, 0});
  }
  return out;
}

}  // namespace

std::string PlatformPair::label() const {
  return baseline == current ? current : baseline + " vs " + current;
}

const char* headline_metric(geometry::Kind kind) { return metrics::headline_column(kind); }

const char* recheck_name(Recheck r) {
  switch (r) {
    case Recheck::kNotRerendered:
      return "not re-rendered";
    case Recheck::kStillDifferent:
      return "still different";
    case Recheck::kFlake:
      return "flake";
    case Recheck::kRerenderFailed:
      return "re-render failed";
  }
  return "";
}

bool states_differ(const PrimitiveState& a, const PrimitiveState& b) {
  const bool both_judged = a.conformance != metrics::Conformance::kNotCompared &&
                           b.conformance != metrics::Conformance::kNotCompared;
  return a.status != b.status || a.visibility != b.visibility || a.pixel_hash != b.pixel_hash ||
         (both_judged && a.conformance != b.conformance);
}

bool new_violation(const ChangedPrimitive& c) {
  return c.after.conformance == metrics::Conformance::kViolation &&
         c.before.conformance != metrics::Conformance::kViolation;
}

PrimitiveComparison compare_primitives(const std::string& baseline_dir,
                                       const std::string& current_dir,
                                       const std::vector<PlatformPair>& pairs, unsigned jobs,
                                       bool compare_verdicts) {
  const rundir::Experiment baseline_exp =
      rundir::load_run_experiment(baseline_dir);
  const rundir::Experiment current_exp = rundir::load_run_experiment(current_dir);
  const std::vector<rundir::Shard> baseline_plan = rundir::plan_shards(baseline_exp);
  const std::vector<rundir::Shard> current_plan = rundir::plan_shards(current_exp);

  // One task per pair, kind and view (the experiments agree on views and counts: same hash).
  std::vector<Task> tasks;
  for (std::size_t p = 0; p < pairs.size(); ++p)
    for (geometry::Kind k :
         {geometry::Kind::kPoint, geometry::Kind::kLine, geometry::Kind::kTriangle})
      for (const geometry::View& v : current_exp.views)
        if (current_exp.counts[int(k)] > 0) tasks.push_back({p, k, v.id, v.group});

  std::vector<TaskResult> results(tasks.size());
  util::run_in_parallel(tasks.size(), jobs, [&](std::size_t i) {
    results[i] = compare_view(baseline_dir, baseline_plan, current_dir, current_plan,
                              pairs[tasks[i].pair], tasks[i], compare_verdicts);
  });

  PrimitiveComparison out;
  for (TaskResult& r : results) {
    out.views.push_back(r.counts);
    out.changed.insert(out.changed.end(), r.changed.begin(), r.changed.end());
    out.failed.insert(out.failed.end(), r.failed.begin(), r.failed.end());
  }
  return out;
}

}  // namespace ra::audit
