// What one audit (a run against its baseline, or two platforms of one run) leaves in the history
// database: the identity of both runs, their drivers, the verdict, and per platform x kind x view
// group the metric distributions and visibility-class counts of the *current* run. Written by
// `renderaudit audit` (audit/), stored by audit/history_db.h, drawn by `renderaudit history`.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace ra::audit {

// Overall outcome of an audit. kBaseline: a run audited against itself (the first night of a
// nightly series): nothing was compared, and no verdict about the driver is given.
enum class Verdict { kUnchanged = 0, kChanged = 1, kFailed = 2, kBaseline = 3 };
const char* verdict_name(Verdict v);  // "unchanged", "changed", "failed", "baseline"
// In words: the name, or "baseline established: nothing compared".
std::string verdict_text(Verdict v);
// The process exit code: 0 unchanged, 1 changed, 2 failed; 0 for a baseline established (nothing
// failed, and a scheduled job's first night is not an error).
int verdict_exit_code(Verdict v);
bool parse_verdict(const std::string& s, Verdict* out);

// One metric's distribution in one platform x kind x view group of the current run. Units are the
// metric's own (docs/records.md): e.g. pe in pixels, te_u in px^2.
struct MetricSummary {
  std::string platform, kind, metric;
  int view_group = 0;     // 1..4 = groups A..D
  int64_t n = 0;          // true-visible, status-ok records the statistics are over
  double median = 0, iqr = 0;
};

// Number of records of one visibility class (or status other than ok, e.g. "crash", "timeout").
struct ClassCount {
  std::string platform, kind, visibility;
  int view_group = 0;
  int64_t count = 0;
};

struct DriverIdentity {
  std::string platform, renderer, version;  // GL_RENDERER / GL_VERSION from the manifest
};

// Drawing time of one platform pair, kind and view group (audit/speed_audit.h): current over
// baseline, the Hodges-Lehmann ratio and its 95% interval, medians in microseconds.
struct SpeedSummary {
  std::string platform, baseline_platform, kind;
  int view_group = 0;  // 1..4 = groups A..D
  int64_t n = 0;       // primitives timed on every side
  double ratio = 0, low = 0, high = 0;
  double baseline_median_us = 0, current_median_us = 0;
  std::string verdict;  // "same", "faster", "slower", "unknown"
};

struct AuditSummary {
  std::string date_utc;          // ISO 8601, e.g. "YYYY-MM-DDTHH:MM:SSZ": when the audit ran
  std::string experiment, experiment_hash;
  uint64_t seed = 0;
  std::string baseline_run, current_run;  // run directories as given (absolute paths)
  std::vector<DriverIdentity> baseline_drivers, current_drivers;
  Verdict verdict = Verdict::kUnchanged;
  int64_t changed_primitives = 0;         // exact pixel-set differences that persisted on re-render
  int64_t flaky_primitives = 0;           // differences that disappeared on re-render
  int64_t failed_primitives = 0;          // crash / timeout records
  int64_t significant_tests = 0;          // distribution tests rejected after correction
  std::vector<MetricSummary> metrics;
  std::vector<ClassCount> classes;
  std::vector<SpeedSummary> speed;  // empty unless the audit timed the drawing
};

}  // namespace ra::audit
