// The report of a run or a study folder (see report.h): which stages must run first, and the
// document (a run's: run_document.h; a study's: its Markdown and figures) laid out as PDF (cairo +
// VTK figure PDFs + pdfunite) and HTML.
#include "report/report.h"

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <sstream>

#include "analysis/run_completeness.h"
#include "analysis/run_records.h"
#include "analysis/run_tally.h"
#include "plots/plot_run.h"
#include "report/document.h"
#include "report/conclusion.h"
#include "report/html_writer.h"
#include "report/pdf_writer.h"
#include "report/run_document.h"
#include "analysis/run_completeness.h"
#include "analysis/run_records.h"
#include "analysis/run_tally.h"
#include "rundir/manifest.h"
#include "rundir/records_format.h"
#include "rundir/run_folder.h"
#include "rundir/study_dir.h"
#include "util/atomic_file.h"
#include "util/child_process.h"
#include "util/errors.h"
#include "util/path_search.h"
#include "util/program_name.h"
#include "util/shell_quote.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace ra::report {
namespace {

fs::file_time_type newest_input(const std::string& run_dir) {
  fs::file_time_type t = fs::file_time_type::min();
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(rundir::run_folder::records(run_dir), ec))
    if (ra::rundir::is_records_file_name(e.path().filename().string()))
      t = std::max(t, fs::last_write_time(e.path(), ec));
  const fs::path manifest = rundir::run_folder::manifest(run_dir);
  if (fs::exists(manifest)) t = std::max(t, fs::last_write_time(manifest, ec));
  return t;
}

// Why DIR/analysis/tally.json cannot be read (missing, another schema version), or "".
std::string tally_problem(const std::string& run_dir) {
  try {
    analysis::read_tally(run_dir);
    return "";
  } catch (const util::UserError& e) {
    return e.what();
  }
}

// Lays out the text pages, joins them with the figures' PDFs into DIR/report/report.pdf and writes
// report.html; fills the paths and page counts of `result`.
void assemble(const Document& doc, const Document& html_doc, const std::string& run_dir,
              const std::string& pdfunite, ReportResult& result) {
  const fs::path out_dir = rundir::run_folder::report(run_dir);
  fs::create_directories(out_dir);
  result.pdf = rundir::run_folder::report_pdf(run_dir);
  result.html = rundir::run_folder::report_html(run_dir);

  // Text pages: lay out until the page numbers they print are the ones they get.
  PageNumbers numbers;
  PdfLayoutResult layout = write_text_pdf(doc, "", numbers);
  for (int pass = 0; pass < 3; ++pass) {
    numbers.first_figure_page = doc.figures.empty() ? 0 : layout.pages + 1;
    numbers.total = layout.pages + int(doc.figures.size());
    numbers.heading_pages = layout.heading_pages;
    const PdfLayoutResult again = write_text_pdf(doc, "", numbers);
    const bool stable = again.pages == layout.pages && again.heading_pages == layout.heading_pages;
    layout = again;
    if (stable) break;
  }
  const std::string text_pdf = (out_dir / "report-text.pdf.tmp").string();
  layout = write_text_pdf(doc, text_pdf, numbers);

  // Assemble: text pages, then one page per figure.
  std::vector<std::string> args = {pdfunite, text_pdf};
  for (const auto& f : doc.figures) args.push_back(f.pdf_path);
  const std::string tmp = result.pdf + ".tmp";
  args.push_back(tmp);
  const std::string log = (out_dir / "pdfunite.log").string();
  util::ChildSpec pdfunite_run;
  pdfunite_run.argv = args;
  pdfunite_run.log_to(log);
  pdfunite_run.stdin_null = true;
  const util::ProgramResult done{util::wait_child(util::start_child(pdfunite_run).pid), ""};
  const int rc = done.exit_code();
  fs::remove(text_pdf);
  if (rc != 0) {
    std::string why;
    try {
      why = util::read_file(log);
    } catch (...) {
    }
    fs::remove(tmp);
    throw util::UserError("pdfunite failed (exit " + std::to_string(rc) + ") assembling " +
                          result.pdf + (why.empty() ? "" : ": " + why));
  }
  fs::remove(log);
  fs::rename(tmp, result.pdf);
  util::write_file_atomic(result.html, render_html(html_doc));

  result.text_pages = layout.pages;
  result.figure_pages = int(doc.figures.size());
  result.pages = result.text_pages + result.figure_pages;
}

// The report of a study folder (rundir/study_dir.h): its title and subtitle from study.json, its
// markdown document, then its figures (DIR/figures/index.json).
Document study_document(const std::string& dir, const rundir::StudyInfo& info) {
  Document d;
  d.title = info.title;
  d.footer = info.title + " (" + dir + ")";
  if (!info.subtitle.empty()) d.subtitle = {info.subtitle};
  for (Block& b : parse_markdown(util::read_file(dir + "/" + info.document)))
    d.blocks.push_back(std::move(b));
  if (!fs::exists(rundir::run_folder::figure_index(dir))) return d;
  const plots::PlotResult figures = plots::read_figure_index(dir);
  Block heading_block;
  heading_block.kind = Block::Kind::kHeading;
  heading_block.level = 1;
  heading_block.text = "Figures";
  heading_block.anchor = "figures";
  d.blocks.push_back(heading_block);
  add_figures(figures, d);
  return d;
}

// A study folder's description; a timing folder written before study.json existed gets one.
std::optional<rundir::StudyInfo> study_of(const std::string& dir) {
  std::optional<rundir::StudyInfo> info = rundir::read_study_info(dir);
  if (info || !fs::exists(rundir::run_folder::timing(dir)) ||
      fs::is_directory(rundir::run_folder::records(dir)))
    return info;
  rundir::StudyInfo t;
  t.kind = rundir::StudyKind::kTiming;
  t.name = fs::path(dir).filename().string();
  t.title = "renderaudit timing report: " + t.name;
  t.document = "timing.md";
  t.analysed = true;
  return t;
}

}  // namespace

std::vector<Step> missing_steps(const std::string& run_dir) {
  std::vector<Step> steps;
  // Commands as the user pastes them: this program's path as invoked (util/program_name.h).
  const std::string analyze_line =
      util::program_for_commands() + " analyze " + util::shell_quote(run_dir);
  const std::string plot_line = util::program_for_commands() + " plot " + util::shell_quote(run_dir);
  const fs::path dir(run_dir);
  const fs::path figures_json = rundir::run_folder::figure_data(dir.string());
  const fs::path index = rundir::run_folder::figure_index(dir.string());
  std::error_code ec;
  bool analyze = false;
  if (!fs::exists(figures_json)) {
    steps.push_back({"analyze", analyze_line, figures_json.string() + " is missing"});
    analyze = true;
  } else if (fs::last_write_time(figures_json, ec) < newest_input(run_dir)) {
    steps.push_back({"analyze", analyze_line,
                     figures_json.string() + " is older than the records"});
    analyze = true;
  } else if (const fs::path tally = rundir::run_folder::tally(dir.string()); !fs::exists(tally)) {
    steps.push_back({"analyze", analyze_line, tally.string() + " is missing"});
    analyze = true;
  } else if (const std::string problem = tally_problem(run_dir); !problem.empty()) {
    // "PATH: expected schema ... version 1 (run `renderaudit analyze DIR` again)": the reason only
    steps.push_back({"analyze", analyze_line,
                     problem.substr(0, problem.find(" (run `"))});
    analyze = true;
  }
  if (analyze || !fs::exists(index)) {
    steps.push_back({"plot", plot_line,
                     analyze ? "the figures follow the analysis" : index.string() + " is missing"});
  } else if (fs::last_write_time(index, ec) < fs::last_write_time(figures_json, ec)) {
    steps.push_back({"plot", plot_line, index.string() + " is older than the analysis"});
  }
  return steps;
}

ReportResult write_report(const ReportOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  const std::string& run_dir = options.run_dir;
  if (!fs::is_directory(run_dir)) throw util::UserError(run_dir + ": no such run directory");
  const std::optional<rundir::StudyInfo> study = study_of(run_dir);
  if (!study && !fs::is_directory(rundir::run_folder::records(run_dir)))
    throw util::UserError(run_dir +
                          " is not a run directory (no records/ and no study.json): run "
                          "`renderaudit run EXPERIMENT.toml --out " +
                          util::shell_quote(run_dir) + "` first");
  const std::string pdfunite = util::find_on_path("pdfunite");
  if (pdfunite.empty())
    throw util::UserError(
        "pdfunite not found: install poppler-utils (apt-get install poppler-utils)");

  ReportResult result;
  if (study) {
    if (!study->analysed || study->document.empty() || !fs::exists(fs::path(run_dir) / study->document))
      throw util::UserError(run_dir + " has not been analysed yet: run `renderaudit analyze " +
                            run_dir + "` and `renderaudit plot " + util::shell_quote(run_dir) + "` first");
    // (a timing study run with --no-figures has none, and says so in its text)
    if (study->kind != rundir::StudyKind::kTiming &&
        !fs::exists(rundir::run_folder::figure_index(run_dir)))
      throw util::UserError(rundir::run_folder::figure_index(run_dir) +
                            " is missing: run `renderaudit plot " + run_dir + "` first");
    const Document doc = study_document(run_dir, *study);
    assemble(doc, doc, run_dir, pdfunite, result);
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return result;
  }
  const std::vector<Step> steps = missing_steps(run_dir);
  if (!steps.empty()) {
    std::string msg = "the report needs what these commands write; run them first:";
    for (const auto& s : steps) msg += "\n  " + s.command + "    (" + s.reason + ")";
    throw util::UserError(msg);
  }
  const analysis::RunCompleteness completeness = analysis::check_run_completeness(run_dir);
  if (completeness.has_plan && !completeness.complete() && !options.allow_incomplete)
    throw analysis::IncompleteRunError(run_dir + ": " + completeness.markdown() +
                                       completeness.remedy("report"));
  result.completeness = completeness.one_line();

  const plots::PlotResult figures = plots::read_figure_index(run_dir);
  const analysis::RunTally tally = analysis::read_tally(run_dir);
  RunDocument content = build_run_document(run_dir, figures, tally, completeness);
  Document& doc = content.doc;
  for (const auto& f : doc.figures)
    if (!fs::exists(f.pdf_path))
      throw util::UserError(f.pdf_path + " is missing: run `renderaudit plot " + util::shell_quote(run_dir) +
                            "` again");

  assemble(pdf_document(doc, content.html_only, content.pdf_pairs_with), doc, run_dir, pdfunite,
           result);
  result.table_titles = content.table_titles;
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return result;
}

}  // namespace ra::report
