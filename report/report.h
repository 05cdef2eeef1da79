// `renderaudit report DIR`: one document about a run, as DIR/report/report.pdf and
// DIR/report/report.html:
//   0. on the title page, the conclusion (report/conclusion.h): per platform the conformance
//      summary, violations and agreement with the paper; for an audited run, the verdict per
//      driver against the baseline;
//   1. the experiment and its provenance (manifest.json: experiment, seed, platforms with their
//      drivers' GL_RENDERER / GL_VERSION / GL_VENDOR, host, project commit, times; the
//      experiment file itself);
//   2. failures: crashed or timed-out shards (manifest.json "failures"), records whose status is
//      not ok (counts and the first cases), figures skipped for lack of data;
//   3. time per primitive: median render_us per platform and kind;
//   4. conformance with the reference rasterizer per platform, kind and view group (ref_diff);
//   5. the equivalence tests behind pooling views into view groups (analysis/view_equivalence.md);
//   6. beside the paper: analysis/paper_comparison.md and paper_differences.md;
//   7. every other table of DIR/analysis/ (in the order of its README.md);
//   8. the list of figures with their pages, then every figure, one page each (DIR/figures/).
//
// PDF route: the text and table pages are drawn with cairo's PDF surface (Debian libcairo2: text
// as real, searchable text with embedded DejaVu fonts); each figure is the vector PDF that VTK's
// vtkPDFExporter wrote in `renderaudit plot`; `pdfunite` (poppler-utils) joins them. All pages
// are 1123 x 794 pt (pdf_writer.h).
//
// Sections 0-4 show what analyze counted (DIR/analysis/tally.json, analysis/run_tally.h); the
// report does not tally the records itself. Stages: the report reads only files, and only what the
// stages before it wrote. When DIR/analysis/figures.json or DIR/figures/index.json is missing, or
// older than what it was made from (records, manifest), or tally.json is missing or of another
// schema version, it stops and names the command to run (missing_steps); the command
// `renderaudit report` (app/report_command.cpp) runs those stages first unless told not to.
// A run that is not whole (analysis/run_completeness.h) is refused unless allow_incomplete; then
// its first page says what is missing.
#pragma once

#include <string>
#include <vector>

namespace ra::report {

struct ReportOptions {
  std::string run_dir;
  bool allow_incomplete = false;  // report a run with missing or damaged shards (and say so)
};

// A stage that must run before the report, and why.
struct Step {
  std::string stage;    // "analyze" or "plot"
  std::string command;  // e.g. "renderaudit analyze outputs/quick"
  std::string reason;   // e.g. "outputs/quick/analysis/figures.json is missing"
};

// The stages whose output is missing, older than their input or of another schema version, in
// order.
std::vector<Step> missing_steps(const std::string& run_dir);

struct ReportResult {
  std::string pdf, html;                  // paths written
  int pages = 0;                          // pages of report.pdf
  int text_pages = 0;                     // of them, text and table pages
  int figure_pages = 0;                   // of them, figures (one each)
  std::vector<std::string> table_titles;  // titles of the tables the report shows
  std::string completeness;               // the run's completeness headline (run_completeness.h)
  double seconds = 0;                     // wall-clock
};

// Writes DIR/report/report.pdf and report.html. Throws ra::util::UserError when the run directory is not
// one, a stage's output is missing or stale (naming the command), or a tool fails (pdfunite:
// "install poppler-utils"); analysis::IncompleteRunError when the run is not whole and
// allow_incomplete is false.
ReportResult write_report(const ReportOptions& options);

}  // namespace ra::report
