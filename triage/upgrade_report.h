// The driver upgrade report (`renderaudit report RUN --upgrade BUILD --platforms P...`, run by
// scripts/driver-upgrade.sh): what changed between each platform P and its build P@BUILD in one
// run, in Markdown, in one process from the audit's own comparison (triage/upgrade_findings.h).
//
// It writes RUN/upgrade-summary-BUILD.json (report/upgrade_summary.h) and opens the Markdown with
// the sentences report/upgrade_sentences.h makes of it, then the worst primitive's before and after
// side by side, a table of contents ([TOC]), one picture set per other finding, a table per
// platform (the audit's counts and tests) and one section per pair: the changed primitives per
// kind and view group, their class and visibility transitions.
//
// A picture pair shows the primitive drawn by both sides, each `show --against` the other (the
// same window pixels at the same scale), drawn into RUN/upgrade-pictures/ in a child process per
// picture (Mesa picks its driver once per process), with the `renderaudit show` line that draws it
// again and a C program that draws it (audit/reproducer.h). A picture or program that cannot be
// made is left out of the folder; the report still names it.
#pragma once

#include <string>

#include "triage/upgrade_findings.h"

namespace ra::triage {

// The report's Markdown; writes the summary, the pictures and the C programs beside the run.
// Throws util::UserError as find_upgrade_changes does.
std::string upgrade_report_markdown(const UpgradeReportOptions& options);

}  // namespace ra::triage
