// The report's first page: its conclusion, before any detail. Per platform, what the run found:
// how many of its primitives are drawn as GL allows (the conformance classes that analyze counted,
// analysis/run_tally.h), the violations, and how many of the paper's cells agree
// (analysis/paper_comparison.csv, paper_differences.csv); for a run with an audit
// (DIR/audit/audit.json, as `make nightly` writes it), the verdict per driver, PASS or FAIL,
// against the baseline it names; for a night whose audit refused to compare (DIR/audit/refused.txt),
// the refusal, the experiment files' difference set as a block of its own, a line each.
#pragma once

#include <string>
#include <vector>

#include "analysis/run_tally.h"
#include "report/document.h"

namespace ra::report {

// Blocks of the conclusion (a heading "Conclusion", anchor "conclusion", a sentence per platform,
// then the tables).
// `tally` is the run's, from DIR/analysis/tally.json; reads DIR/analysis/ and
// DIR/audit/audit.json; what is missing is left out and said. Throws ra::util::UserError on unreadable
// files.
std::vector<Block> conclusion_blocks(const std::string& run_dir, const analysis::RunTally& tally);

}  // namespace ra::report
