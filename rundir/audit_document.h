// audit.json read back: the one reader of the document audit/ writes (audit_json.cpp; keys in
// docs/nightly-audit.md), for every later reader of a finished audit: the report's first page
// (report/conclusion), the night of `watch`, the driver upgrade report (triage/upgrade_report.h).
// Each field is checked; a damaged or foreign file is a UserError naming the file and the key.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace ra::rundir {

// audit.json's document name and version (2 added `speed` and `speed_measurement`).
inline constexpr const char* kAuditDocument = "audit";
inline constexpr int kAuditDocumentVersion = 2;

// One pair the audit compared: `baseline` of the baseline side against `current`.
struct AuditedPair {
  std::string baseline, current;
};

// One group's drawing time (audit.json `speed`): ratio = current / baseline time with its 95%
// interval, NaN where the audit formed none (null in the file).
struct AuditedTime {
  std::string baseline_platform, platform, kind, group, verdict;
  double ratio = 0, low = 0, high = 0;
};

// A flake (audit.json `flakes.items`): a primitive whose difference disappeared on re-render.
struct AuditedFlake {
  std::string baseline_platform, platform, kind;
  int view = 0;
  uint64_t index = 0;
};

struct AuditDocument {
  std::string path;
  std::string verdict;       // "PASS", "FAIL", "baseline", ...
  std::string baseline_dir;  // the baseline run it was compared with
  // One row per platform pair, kind and view: primitives compared, changed, flaky, failed.
  struct ViewRow {
    std::string platform, baseline_platform;
    std::int64_t compared = 0, changed = 0, flakes = 0, failed = 0;
  };
  std::vector<ViewRow> views;
  std::vector<std::string> missing_shard_platforms;  // one entry per missing shard
  // Shard failures the manifest lists, with whether a re-run recovered them.
  struct ShardFailure {
    std::string platform, outcome;
  };
  std::vector<ShardFailure> manifest_failures;
  std::vector<std::string> renderer_mismatches;  // "PLATFORM: why"
  std::vector<std::string> reasons;              // why the verdict is what it is
  bool speed_warn_only = false;  // a slower group warns instead of failing its driver
  std::vector<AuditedPair> pairs;
  uint64_t compared = 0, changed = 0, new_violations = 0;  // `counts` (flakes excluded)
  uint64_t significant_tests = 0, family_size = 0;         // `distribution_tests`
  bool timed = false;                // `speed_measurement.performed`: drawing time was judged
  std::vector<AuditedTime> speed;    // per pair, kind and view group, in the file's order
  std::vector<AuditedFlake> flakes;  // those listed (the file lists up to kJsonListed)
  uint64_t flakes_total = 0;         // all of them, listed or not

  // The groups whose drawing time moved (faster or slower).
  std::size_t time_moved() const;
  // Whether it compared `baseline` with `current`.
  bool compares(const std::string& baseline, const std::string& current) const;
};

// AUDIT_DIR/audit.json. Throws util::UserError naming the file: unreadable, another schema or
// version, or a field missing or of another type.
AuditDocument read_audit_document(const std::string& audit_dir);

}  // namespace ra::rundir
