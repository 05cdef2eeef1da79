// What the driver upgrade report (triage/upgrade_report.h) says, before it is said: for each
// platform P of a run against its build P@BUILD, the audit's comparison of the two (the changed
// primitives, audit/audit_compare.h, the flakes the audit found left out), the counts per kind and
// view group (audit/change_counts.h) as the upgrade summary (report/upgrade_summary.h), and the
// distinct findings, each with the primitive to show.
//
// The audit of P against P@BUILD is read from RUN/audit-P<SUFFIX>/audit.json (driver-upgrade.sh:
// no suffix for backports, "-source" for the source build) and must say that it compared those two
// platforms; else a UserError naming the file.
//
// Pairs of one driver whose changed primitives and their pixels after are the same (one
// fingerprint) and whose counts are equal are one finding, said once ("identical through OSMesa
// and EGL"). Of each finding, per category (most severe first) and kind, the primitive whose
// number of lit pixels changed most is shown; the first shown is the most striking of those
// breaking GL's rules (not drawn, new violation).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "audit/audit_compare.h"
#include "rundir/audit_document.h"
#include "audit/change_counts.h"
#include "report/upgrade_summary.h"

namespace ra::triage {

struct UpgradeReportOptions {
  std::string run_dir;
  std::string build;                   // "backports": the pairs are P against P@backports
  std::vector<std::string> platforms;  // the P audited
  std::string audit_suffix;            // the audits' folders: RUN/audit-P<SUFFIX>
};

// One platform against its build.
struct UpgradeSide {
  std::string platform, build_platform;
  rundir::AuditDocument audit;
  std::vector<audit::ChangedPrimitive> changed;  // as the audit counts them (no flakes)
};

// A primitive shown in pictures, with its title.
struct ShownPrimitive {
  audit::ChangeCategory category = audit::ChangeCategory::kOther;
  std::string title;  // "llvmpipe 25.0.7, through OSMesa: 53 lines not drawn; the worst, ..."
  std::size_t side = 0;  // index into UpgradeFindings::sides
  audit::ChangedPrimitive primitive;
};

struct UpgradeFindings {
  report::UpgradeSummary summary;   // what upgrade-summary-BUILD.json holds
  std::vector<UpgradeSide> sides;   // in the order of the platforms given
  std::vector<ShownPrimitive> shown;  // the first is the report's lead picture
};

// Reads the run, its audits and compares (see the header). Throws util::UserError for a run or
// an audit folder that is not what it must be.
UpgradeFindings find_upgrade_changes(const UpgradeReportOptions& options);

// The category in words, as a picture's title counts it: "not drawn", "that break GL's rules", ...
const char* category_words(audit::ChangeCategory c);

// "OSMesa" of "osmesa-llvmpipe"; a platform without a back end is named as it is.
std::string backend_label(const std::string& platform);

}  // namespace ra::triage
