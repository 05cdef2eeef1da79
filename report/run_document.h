// The document of a run's report (report.h, sections 0-8): the title page and its conclusion, the
// provenance, failures, render time, conformance, the analysis' tables and the figures, from the
// run directory's files. report.cpp lays it out as PDF and HTML.
#pragma once

#include <set>
#include <string>
#include <vector>

#include "analysis/run_completeness.h"
#include "analysis/run_tally.h"
#include "plots/plot_run.h"
#include "report/document.h"

namespace ra::report {

// A run's report, and the figures and pairs its PDF leaves out.
struct RunDocument {
  Document doc;
  std::vector<std::string> table_titles;
  std::set<std::string> html_only;  // figure ids left out of the PDF (kPdfAllPairsMax; the
                                    // overview, which page one shows)
  std::string pdf_pairs_with;       // the baseline platform when the PDF shows only its pairs
};

// The run's report, every section, from DIR's manifest, analysis and figure index.
RunDocument build_run_document(const std::string& run_dir, const plots::PlotResult& figures,
                               const analysis::RunTally& tally,
                               const analysis::RunCompleteness& completeness);

// `doc` with only the figures the PDF shows, numbered 1, 2, ... in order; with `pairs_with` set,
// the rows of pairwise tables (columns "Platform a", "Platform b") are those of its pairs.
Document pdf_document(const Document& doc, const std::set<std::string>& html_only,
                      const std::string& pairs_with);

// The list of figures, then one page per figure of the index (paths relative to DIR/report).
void add_figures(const plots::PlotResult& figures, Document& d);

}  // namespace ra::report
