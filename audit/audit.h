// `renderaudit audit`: a run against its baseline (or two platforms of one run), and a verdict.
//
//   1. Identity: both runs must be of the same experiment (manifest.json hash and seed), else
//      ra::util::UserError (exit 2) naming both hashes. The drivers (GL_RENDERER / GL_VERSION) of both
//      sides are read from the manifests; --expect-renderer checks the current side's.
//   2. Failures: crash / timeout records, planned shards without a records file; the shard failures
//      the manifest lists are matched to those (a worker failure whose shard then completed
//      without a crash / timeout record did not recur on re-run: reported, not a failure;
//      audit/run_identity.h, audit/audit_compare.h).
//   3. Per primitive: exact pixel comparison through pixel_hash (audit/audit_compare.h).
//   4. Flakes: every changed primitive rendered once more (audit/flake_check.h).
//   5. Per distribution: Welch t and Levene, raw and Box-Cox, Holm-corrected, effect sizes; and the
//      visibility-class counts (audit/distribution_audit.h).
//   6. Drawing time, when asked (--speed): the sides drawn again, interleaved, and judged per pair,
//      kind and view group (audit/speed_audit.h).
//   7. Verdict (audit/audit_summary.h Verdict, also the exit code):
//      failed (2)    a crash / timeout record or a missing shard on either side, a manifest
//                    failure of a shard not in the plan, a re-render that crashed or hung, or a
//                    current driver not matching --expect-renderer;
//      changed (1)   otherwise, when a primitive's pixels, status or class differ and the
//                    difference did not disappear on re-render (flakes do not count; changed
//                    primitives over the re-render cap count as changed), or when a group draws
//                    `slower` (unless --speed-warn-only);
//      baseline (0)  otherwise, when the baseline and the current run are one directory (the first
//                    night of a nightly series): nothing was compared;
//      unchanged (0) otherwise. Significant distribution tests do not decide on their own: the same
//      primitives are rendered on both sides, so a distribution can only move through primitives
//      that changed; they say how much it moved (and, with only flakes, are noted as such).
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "audit/audit_compare.h"
#include "audit/audit_summary.h"
#include "audit/distribution_audit.h"
#include "audit/flake_check.h"
#include "audit/run_identity.h"
#include "audit/speed_audit.h"

namespace ra::audit {

struct AuditOptions {
  std::string baseline_dir;          // run against baseline: the baseline run
  std::string current_dir;           // the current run (the only run with --between)
  std::vector<std::string> between;  // {P1, P2}: two platforms of current_dir; else empty
  double alpha = 0.05;               // family-wise error rate of the distribution tests
  std::string out_dir;               // empty: CURRENT/audit or RUN/audit-P1-vs-P2
  std::string expect_renderer;       // ECMAScript regex searched in each current GL_RENDERER
  std::size_t max_rerenders = 2000;  // flake check cap; 0 turns the check off
  unsigned jobs = 0;                 // threads and re-render children; 0: the number of cores
  std::string program;               // runs `worker` for re-renders; empty: worker_program()
  SpeedOptions speed;                // step 6; off unless speed.enabled
  std::function<void(const std::string&)> progress;  // one line per timing process; may be empty
};

struct AuditResult {
  std::string mode;  // "runs" (run against baseline) or "between" (two platforms of one run)
  std::string date_utc;
  std::string out_dir;
  RunIdentity baseline, current;  // the same run twice with --between
  std::vector<PlatformPair> pairs;
  std::vector<DriverIdentity> baseline_drivers, current_drivers;  // per pair
  std::string expect_renderer;
  std::vector<std::string> renderer_mismatches;  // "PLATFORM: GL_RENDERER '...' does not match ..."
  std::vector<MissingShard> missing;             // both sides
  std::vector<ManifestFailure> manifest_failures;  // both sides, each with what became of it
  PrimitiveComparison primitives;
  audit::FlakeCheckSummary flakes;
  DistributionAudit distributions;
  std::vector<ClassCountChange> classes;
  SpeedAudit speed;  // performed only when asked
  Verdict verdict = Verdict::kUnchanged;
  std::vector<std::string> reasons;  // why the verdict, one line each
  AuditSummary summary;              // what goes into the history database

  std::size_t changed_count() const;  // persisting changes (flakes excluded)
  // A run against itself (mode "runs", one directory on both sides): nothing is compared.
  bool self_audit() const;
  std::size_t flake_count() const;
  std::size_t recovered_count() const;  // manifest failures that did not recur
};

// Runs the audit (steps 1-7). Throws ra::util::UserError for bad input (not run directories, different
// experiments, unknown platforms, a bad regex): nothing is written then.
AuditResult run_audit(const AuditOptions& options);

// Sets result.verdict and result.reasons from what was found (rule 7 above). `speed_warn_only`:
// a slower group is a reason, not a change.
void decide_verdict(AuditResult& result, bool speed_warn_only = false);

// The history record: identity, drivers, verdict and counts, and per current platform x kind x view
// group (1-based, 1 = A) every metric's n, median and IQR and every class count of the current
// side.
AuditSummary make_summary(const AuditResult& result, const analysis::RunRecords& current);

}  // namespace ra::audit
