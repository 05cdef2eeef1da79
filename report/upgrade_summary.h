// The driver upgrade's summary, RUN/upgrade-summary-BUILD.json (schema "renderaudit-upgrade-summary"
// version 1): the run, the build's name, the view groups and, per pair of platforms (a platform
// against its build), the counts of what changed per kind and view group (audit/change_counts.h
// counts them) and, where its audit judged drawing time, the verdicts (`speed`). Written and read
// here only; `renderaudit report RUN --upgrade BUILD` writes it (triage/upgrade_report.h) and
// report/upgrade_sentences.h says it in words.
//
// `speed` and a stratum's `not_drawn_violations` are optional keys of version 1, not a version 2:
// no key that was there changed meaning, this reader takes summaries with and without them, and an
// older one, which checks the keys it reads and ignores others, reads a summary with them as
// before. The file is read field by field: a missing or mistyped field, counts that do not add up
// (more not drawn than changed, more changed than compared, more not drawn and breaking the rules
// than either), a total past 2^62, or a time ratio that contradicts its verdict (a faster group
// whose interval reaches 1) is a UserError naming the file and the key.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace ra::report {

constexpr int kUpgradeSummaryVersion = 1;

// The changed primitives of one kind in one view group of one pair, counted by what changed.
struct UpgradeStratum {
  std::string kind;   // "point", "line", "triangle"
  std::string group;  // view group label, "A".."D"
  std::int64_t compared = 0;          // primitives drawn on both sides
  std::int64_t changed = 0;           // pixels, status or visibility differ
  std::int64_t not_drawn = 0;         // true-visible -> false-invisible
  std::int64_t newly_drawn = 0;       // false-invisible -> true-visible
  std::int64_t new_violations = 0;    // after a GL violation, before none
  std::int64_t fixed_violations = 0;  // before a violation, after none
  std::int64_t allowed = 0;           // before and after drawn as GL allows, other pixels
  // not drawn and a new violation (of both counts above); -1: the summary does not say (written
  // before its optional key `not_drawn_violations`)
  std::int64_t not_drawn_violations = -1;
};

// A view group: its label and what its views share (degrees, pixels).
struct UpgradeViewGroup {
  std::string label;  // "A"
  int fov_deg = 0;    // vertical field of view
  int window = 0;     // square window side
};

// The drawing time of one kind in one view group of one pair, as its audit judged it
// (audit/speed_audit.h): ratio = upgraded / installed time, dimensionless, with its 95% interval.
struct UpgradeTime {
  std::string kind;                     // "point", "line", "triangle"
  std::string group;                    // view group label, "A".."D"
  double ratio = 0, low = 0, high = 0;  // > 0; NaN where no interval could be formed (unknown)
  std::string verdict;  // "faster" (high < 1), "slower" (low > 1), "same", "unknown"
};

// One platform against its build: "osmesa-llvmpipe" against "osmesa-llvmpipe@backports".
struct UpgradePair {
  std::string platform, build_platform;
  std::string installed_version, build_version;  // GL_VERSION of each side
  std::string fingerprint;  // of the changed primitives and their pixels after (equal: identical)
  std::vector<UpgradeStratum> strata;
  bool timed = false;              // its audit judged drawing time (the summary has `speed`)
  std::vector<UpgradeTime> speed;  // per kind and view group, in the audit's order
};

struct UpgradeSummary {
  std::string run_dir;  // the run the audits read
  std::string build;    // "backports"
  std::vector<UpgradeViewGroup> groups;
  std::vector<UpgradePair> pairs;
};

// The summary as its document; read_upgrade_summary reads it back as it was.
nlohmann::json upgrade_summary_json(const UpgradeSummary& summary);

// Writes the document to `path` atomically. Throws std::runtime_error naming the file.
void write_upgrade_summary(const UpgradeSummary& summary, const std::string& path);

// The summary in `path`. Throws util::UserError naming the file and the key of what is wrong.
UpgradeSummary read_upgrade_summary(const std::string& path);

}  // namespace ra::report
