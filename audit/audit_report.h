// What `renderaudit audit` writes into its output directory, each file atomically (temp + rename,
// util/atomic_file.h):
//   audit.json              everything, machine-readable ("schema_version": 2; keys in docs/nightly-audit.md)
//   audit.md                for a person, read first: verdict, new conformance violations (first:
//                           what a driver team must see), drivers side by side, counts, the
//                           changed primitives (first 50 + total, each with its `renderaudit show`
//                           line), significant tests with effect sizes, classes, flakes, failures
//   junit.xml               one testsuite per platform (pair), one testcase per kind x view group
//                           (failure when changed or failed) and one "conformance" testcase per
//                           kind x view group (failure: new GL violations), plus `drivers` and
//                           `shards` cases
//   changed_primitives.csv  every changed primitive (flakes included, `recheck` says which)
#pragma once

#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "audit/audit.h"
#include "rundir/audit_document.h"

namespace ra::audit {

constexpr int kAuditSchemaVersion = rundir::kAuditDocumentVersion;  // its one reader's
constexpr std::size_t kMarkdownListed = 50;  // changed primitives and flakes shown in audit.md
constexpr std::size_t kJsonListed = 10000;   // ... in audit.json (all in changed_primitives.csv)

// The outcome of one pair x kind x view group: what its JUnit testcase and counts row say.
struct GroupOutcome {
  std::size_t pair = 0;
  geometry::Kind kind = geometry::Kind::kPoint;
  int view_group = 0;
  std::string label;       // "A", ...
  std::vector<int> views;  // view numbers of the group, ascending
  uint64_t compared = 0, changed = 0, flakes = 0, failed = 0, unmatched = 0;
  uint64_t new_violations = 0;  // changed primitives that now break a GL rule (not flakes)
  std::size_t missing_shards = 0, rerender_failures = 0, significant_tests = 0;
  Verdict verdict() const;  // failed > changed > unchanged, by the rule of audit/audit.h
};

// Every pair x kind x view group compared, in that order.
std::vector<GroupOutcome> group_outcomes(const AuditResult& r);

// `renderaudit show RUN --platform P --kind K --view V --index I` for the current side of `c`.
std::string show_command(const AuditResult& r, const ChangedPrimitive& c);

nlohmann::json audit_json(const AuditResult& r);
std::string audit_markdown(const AuditResult& r);
std::string audit_junit(const AuditResult& r);
std::string changed_primitives_csv(const AuditResult& r);

// Creates r.out_dir and writes the four files; returns their paths. Throws std::runtime_error
// naming the file on an I/O failure.
std::vector<std::string> write_audit_outputs(const AuditResult& r);

// Helpers shared by the writers.
std::string format_number(double v, int significant = 4);  // "n/a" when not finite

}  // namespace ra::audit
