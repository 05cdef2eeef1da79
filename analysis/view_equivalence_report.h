// The view-equivalence results (analysis/view_equivalence.h) written out for the reader and for
// scripts: view_equivalence.csv and view_equivalence.md.
#pragma once

#include <string>
#include <vector>

#include "analysis/run_records.h"
#include "analysis/view_equivalence.h"
#include "stats/table_writer.h"

namespace ra::analysis {

// The results as one long table (a row per comparison, every statistic): view_equivalence.csv.
stats::Table view_equivalence_table(const RunRecords& run, const std::vector<ViewEquivalence>& results,
                             const EquivalenceOptions& options);

// The report for reading: the rule, the verdicts, every pair not equivalent said explicitly, the
// pooling note, and a table of p-values per platform and kind: view_equivalence.md.
std::string view_equivalence_markdown(const RunRecords& run,
                                      const std::vector<ViewEquivalence>& results,
                                      const EquivalenceOptions& options);

// Cells for reports: the p-value (3 significant digits) or statistic (4), "undefined" otherwise.
stats::TableCell p_value_cell(const TestOutcome& outcome);
stats::TableCell statistic_cell(const TestOutcome& outcome);

}  // namespace ra::analysis
