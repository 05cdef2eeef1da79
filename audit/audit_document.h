// audit.json read back (audit/audit_report.h writes it): the parts a later reader of a finished
// audit needs, each field checked, a damaged or foreign file a UserError naming the file and the
// key. The driver upgrade report (triage/upgrade_report.h) reads its counts, tests, drawing-time
// verdicts and flakes here rather than parsing the file itself.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace ra::audit {

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
  std::vector<AuditedPair> pairs;
  uint64_t compared = 0, changed = 0, new_violations = 0;  // `counts` (flakes excluded)
  uint64_t significant_tests = 0, family_size = 0;         // `distribution_tests`
  bool timed = false;                // `speed_measurement.performed`: drawing time was judged
  std::vector<AuditedTime> speed;    // per pair, kind and view group, in the file's order
  std::vector<AuditedFlake> flakes;  // those listed (the file lists up to kJsonListed)
  uint64_t flakes_total = 0;         // all of them, listed or not

  // Whether it compared `baseline` with `current`.
  bool compares(const std::string& baseline, const std::string& current) const;
};

// AUDIT_DIR/audit.json. Throws util::UserError naming the file: unreadable, another schema or
// version, or a field missing or of another type.
AuditDocument read_audit_document(const std::string& audit_dir);

}  // namespace ra::audit
