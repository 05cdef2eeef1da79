// `renderaudit analyze DIR`: the paper's whole section-4 procedure from the records of a run
// directory alone, written under DIR/analysis/ (the command line is registered by
// ra::app::register_analyze_command, app/commands.h).
//
// Stages, timed separately (the benchmark bench/analysis_bench.cpp reports them):
//   load         DIR/records/*.csv -> samples per platform, kind, view (run_records.h)
//   equivalence  orientation views compared per platform, kind, metric, view group
//                (view_equivalence.h), then pooled into view groups A, B, C, ...
//   tables       Tables 2-11, supplements, speed, cross-platform comparison (paper_tables.h)
//   conformance  the conformance classes and violations (conformance_summary.h)
//   figures      figures.json for the plots stage (figure_data.h)
//   write        every file rendered and written atomically
// Files (README.md in DIR/analysis lists them with one line each): view_equivalence.{csv,md};
// each table as .csv, .md and .tex (conformance.* first); violations.md; figures.json; report.md (every table in Markdown). Files of
// earlier analyses with the same names are replaced; those of tables this run has no data for are
// removed, so the directory always describes the last analysis.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "stats/descriptive.h"

namespace ra::analysis {

struct AnalyzeOptions {
  std::string run_dir;
  double alpha = 0.05;                             // significance level, 0 < alpha < 1
  std::vector<double> pixel_pitches_mm = {0.255};  // Table 11; the paper's LCD
  stats::QuantileDefinition quantiles = stats::QuantileDefinition::kHyndmanFan6;
  std::size_t box_cox_subsample = 10000;  // order statistics choosing lambda
  unsigned jobs = 0;                      // threads; 0: the number of cores
  bool allow_incomplete = false;  // analyse a run with missing or damaged shards (and say so)
  int bootstrap_resamples = 2000;  // of every median and IQR (uncertainty.md); 0: none
  std::uint64_t bootstrap_seed = 2008;
  // The paper's published values (analysis/paper_values.h); "" = default_paper_values_path();
  // "none": no comparison.
  std::string paper_values;
  // The paper's point convention (docs/method.md, "Where we differ from the paper"): true-invisible
  // points within this many pixels outside the window count as false-invisible; 0 to 16 px,
  // default 0 (the records' classes). 0.5 reproduces the paper's Table 2.
  double point_margin_px = 0;
};

// Stages in order: load (completeness check, records and conformance verdicts), equivalence,
// tables and figures (run at once, each with its own wall time), statistics (the three together),
// write.
struct StageTime {
  std::string stage;
  double seconds = 0;  // wall-clock
};

struct AnalyzeResult {
  std::string out_dir;             // DIR/analysis
  std::vector<std::string> files;  // written, names relative to out_dir, in README order
  std::string summary;             // what the command prints: the main tables in Markdown
  std::vector<StageTime> timings;
  std::uint64_t records = 0;
  std::size_t comparisons = 0;     // view-equivalence comparisons
  std::size_t not_equivalent = 0;  // of them NOT equivalent
  std::string completeness;        // the run's completeness headline (run_completeness.h)
};

// Runs the whole analysis and writes DIR/analysis/. First compares the records with the run's plan
// (run_completeness.h): a run that is not whole throws IncompleteRunError, naming what is missing,
// unless allow_incomplete (then README.md and the summary start with what is missing). Throws
// ra::util::UserError on bad options or input (a missing directory, no records, a malformed record:
// located messages).
AnalyzeResult analyze_run(const AnalyzeOptions& options);

}  // namespace ra::analysis
