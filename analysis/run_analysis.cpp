// `renderaudit analyze DIR`: the paper's section-4 procedure; see run_analysis.h.
#include "analysis/run_analysis.h"
#include "analysis/run_completeness.h"

#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <future>
#include <iostream>
#include <memory>
#include <optional>
#include <regex>

#include "analysis/figure_data.h"
#include "analysis/conformance_summary.h"
#include "analysis/run_tally.h"
#include "analysis/paper_tables.h"
#include "analysis/run_records.h"
#include "analysis/view_equivalence_report.h"
#include "rundir/run_experiment.h"
#include "rundir/run_folder.h"
#include "stats/table_writer.h"
#include "util/atomic_file.h"
#include "util/errors.h"

namespace fs = std::filesystem;

namespace ra::analysis {
namespace {

class Stopwatch {
 public:
  double lap() {
    const auto now = std::chrono::steady_clock::now();
    const double s = std::chrono::duration<double>(now - last_).count();
    last_ = now;
    return s;
  }

 private:
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

void check_options(const AnalyzeOptions& o) {
  if (!(o.alpha > 0 && o.alpha < 1)) {
    throw util::UserError("--alpha " +
                          stats::format_significant(std::isfinite(o.alpha) ? o.alpha : -1, 6) +
                          ": the significance level must lie strictly between 0 and 1");
  }
  if (o.pixel_pitches_mm.empty())
    throw util::UserError("--pixel-pitch-mm: give at least one pitch");
  for (double p : o.pixel_pitches_mm) {
    if (!(p > 0) || !std::isfinite(p)) {
      throw util::UserError("--pixel-pitch-mm: " + std::to_string(p) +
                      " is not a pixel pitch (a positive number of millimetres, e.g. 0.255)");
    }
  }
  if (!(o.point_margin_px >= 0 && o.point_margin_px <= 16)) {
    throw util::UserError("--point-margin-px " + stats::format_significant(o.point_margin_px, 6) +
                    ": a margin in pixels from 0 to 16 (0.5 is the paper's convention)");
  }
  if (o.box_cox_subsample < 3) {
    throw util::UserError("--box-cox-subsample " + std::to_string(o.box_cox_subsample) +
                    ": at least 3 values are needed to choose lambda");
  }
}

// One file to write and its line in README.md.
struct Output {
  std::string name;
  std::string what;
  std::string content;
};

// Files of an earlier analysis that this one may not rewrite (a kind absent now, one platform).
bool generated_name(const std::string& name) {
  static const std::regex pattern(
      R"((table\d\d[a-z]?_[a-z_]+|speed|cross_platform|view_equivalence|conformance|uncertainty|paper_comparison|paper_differences)\.(csv|md|tex)|figures\.json|tally\.json|report\.md|violations\.md|README\.md)");
  return std::regex_match(name, pattern);
}

std::string files_readme(const std::vector<Output>& outputs, const RunRecords& run,
                         const AnalyzeOptions& o, const RunCompleteness& completeness) {
  std::string md = "# Analysis of " + run.run_dir + "\n\n" + completeness.markdown() +
                   "\nWritten by `renderaudit analyze` from the records alone (" +
                   std::to_string(run.record_count) + " records in " +
                   std::to_string(run.files.size()) +
                   " files); alpha = " + stats::format_significant(o.alpha, 3) + ", quartiles " +
                   quantile_label(o.quantiles) +
                   ". Tables come as .csv (title and notes as '# ' lines, then a header row), .md "
                   "and .tex (booktabs).\n\n" +
                   stats::markdown_header({"file", "what"},
                                          {stats::Align::kLeft, stats::Align::kLeft});
  for (const Output& out : outputs) md += stats::markdown_row({out.name, out.what});
  md += stats::markdown_row({"README.md", "this list"});
  return md;
}

// Throws IncompleteRunError naming what is missing or damaged, unless the run is whole (or has no
// plan to compare with) or --allow-incomplete.
void refuse_if_incomplete(const RunCompleteness& completeness, const AnalyzeOptions& o) {
  if (completeness.has_plan && !completeness.complete() && !o.allow_incomplete)
    throw IncompleteRunError(o.run_dir + ": " + completeness.markdown() +
                             completeness.remedy("analyze"));
}

// The run's records (and, when the run has a plan to check them against, their seals), with what
// --point-margin-px needs to generate each point again.
RunRecords load_records(const AnalyzeOptions& o) {
  LoadOptions load;
  load.jobs = o.jobs;
  load.read_seals = std::filesystem::exists(rundir::run_folder::experiment(o.run_dir));
  std::optional<rundir::Experiment>
      experiment;  // the views and seed that generate each point again
  if (o.point_margin_px > 0) {
    const std::string path = rundir::run_folder::experiment(o.run_dir);
    if (!std::filesystem::exists(path))
      throw util::UserError(o.run_dir + ": --point-margin-px needs the run's experiment.toml (" +
                            path + " is missing)");
    experiment = rundir::load_run_experiment(o.run_dir);
    load.point_margin_px = o.point_margin_px;
    load.experiment = &*experiment;
  }
  return load_run_records(o.run_dir, load);
}

// A stage started on a thread of its own, with the wall time it took.
template <typename Work>
auto timed_task(Work work) {
  return std::async(std::launch::async, [work = std::move(work)] {
    Stopwatch watch;
    auto value = work();
    return std::make_pair(std::move(value), watch.lap());
  });
}

// The stage's result (its exception, if it threw); its time goes to result.timings.
template <typename Task>
auto take(Task& task, const char* stage, AnalyzeResult& result) {
  auto [value, seconds] = task.get();
  result.timings.push_back({stage, seconds});
  return std::move(value);
}

TableOptions table_options(const AnalyzeOptions& o, const EquivalenceOptions& eq) {
  TableOptions to;
  to.quantiles = o.quantiles;
  to.pixel_pitches_mm = o.pixel_pitches_mm;
  to.alpha = o.alpha;
  to.comparison = eq.comparison;
  to.jobs = o.jobs;
  to.bootstrap.resamples = o.bootstrap_resamples;
  to.bootstrap.seed = o.bootstrap_seed;
  if (o.paper_values != "none") {
    const std::string path = o.paper_values.empty() ? default_paper_values_path() : o.paper_values;
    if (!path.empty()) {
      PaperValues paper = load_paper_values(path);
      to.paper = std::move(paper.tables);
      to.paper_differences = std::move(paper.differences);
      to.paper_primitives_per_group = paper.primitives_per_view_group;
    }
  }
  return to;
}

// The equivalence verdicts in brief, for report.md and the terminal.
std::string verdicts_markdown(const RunRecords& run, const std::vector<ViewEquivalence>& equivalence,
                              const AnalyzeOptions& o, std::size_t not_equivalent) {
  std::string verdicts = "## View equivalence\n\n";
  std::size_t undecided = 0, none = 0;
  for (const ViewEquivalence& e : equivalence) {
    undecided += e.verdict == Verdict::kUndecided;
    none += e.verdict == Verdict::kNoComparison;
  }
  verdicts += std::to_string(equivalence.size()) +
              " comparisons of orientation views (alpha = " + stats::format_significant(o.alpha, 3) +
              "; location t/ANOVA and Levene median on raw " + "data): " +
              std::to_string(equivalence.size() - not_equivalent - undecided - none) +
              " equivalent, " + std::to_string(not_equivalent) + " NOT equivalent, " +
              std::to_string(undecided) + " undecided, " + std::to_string(none) +
              " without comparison.\n";
  std::size_t listed = 0;
  for (const ViewEquivalence& e : equivalence) {
    if (e.verdict != Verdict::kNotEquivalent) continue;
    if (listed++ == 12) {
      verdicts += "- ... (all in view_equivalence.md)\n";
      break;
    }
    verdicts += std::string("- NOT equivalent: ") + run.platforms[e.platform] + ", " +
                kind_label_plural(e.kind) + ", " + kind_metrics(e.kind)[e.metric].symbol +
                ", view group " + e.label + ": " + e.explanation + "\n";
  }
  verdicts +=
      std::string(not_equivalent ? "The views were pooled into view groups anyway, "
                                          "as the paper did (see view_equivalence.md).\n"
                                        : "Views pooled into view groups, as the paper "
                                          "did.\n");
  return verdicts;
}

// Every file of the analysis, rendered: report.md first (its content filled by the caller), then
// view equivalence, conformance, the paper's tables, the figure data. `all_tables` gets every
// table in Markdown, `printed` those the terminal shows.
std::vector<Output> render_outputs(const RunRecords& run, const AnalyzeOptions& o,
                                   const EquivalenceOptions& eq,
                                   const std::vector<ViewEquivalence>& equivalence,
                                   const ConformanceSummary& conformance,
                                   const std::vector<stats::Table>& tables, const nlohmann::json& figures,
                                   std::string* all_tables, std::string* printed) {
  const stats::Table conformance_tab = conformance_table(conformance);
  std::vector<Output> outputs;
  outputs.push_back(
      {"report.md", "every table below in Markdown, with the view-equivalence verdicts", ""});
  outputs.push_back({"view_equivalence.md",
                     "orientation views compared (t, F, Levene; raw and Box-Cox), the rule, every "
                     "group not equivalent, the pooling note",
                     view_equivalence_markdown(run, equivalence, eq)});
  outputs.push_back({"view_equivalence.csv",
                     "the same comparisons with every statistic, one row each",
                     stats::render_csv(view_equivalence_table(run, equivalence, eq))});
  // Conformance first: "does this driver rasterize as GL allows?" before the details.
  const std::string conformance_md = stats::render_markdown(conformance_tab);
  *all_tables = conformance_md + "\n";
  *printed = conformance_tab.rows.empty() ? "" : conformance_md + "\n";
  outputs.push_back({"conformance.csv", "conformance classes per platform, kind, view group (CSV)",
                     stats::render_csv(conformance_tab)});
  outputs.push_back({"conformance.md", "the same (Markdown)", conformance_md});
  outputs.push_back({"conformance.tex", "the same (LaTeX)", stats::render_latex(conformance_tab)});
  outputs.push_back({"violations.md",
                     "every record that breaks a GL rasterization rule, worst first, with the "
                     "`renderaudit show` line that draws it",
                     violations_markdown(conformance, o.run_dir)});
  for (const stats::Table& t : tables) {
    const std::string md = stats::render_markdown(t);
    *all_tables += md + "\n";
    const bool supplement = t.file_stem.rfind("table", 0) == 0 &&
                            std::isalpha(static_cast<unsigned char>(t.file_stem[7])) != 0;
    if (!supplement && t.file_stem != "cross_platform") *printed += md + "\n";
    const std::string what = t.title.substr(0, t.title.find(';'));
    outputs.push_back({t.file_stem + ".csv", what + " (CSV)", stats::render_csv(t)});
    outputs.push_back({t.file_stem + ".md", what + " (Markdown)", md});
    outputs.push_back({t.file_stem + ".tex", what + " (LaTeX)", stats::render_latex(t)});
  }
  outputs.push_back({rundir::run_folder::kTallyFile,
                     "what plot and report count: records, conformance with the reference and GL "
                     "verdicts per view group, records not ok, render time (schema "
                     "renderaudit-tally v" +
                         std::to_string(kTallySchemaVersion) + ", analysis/run_tally.h)",
                     tally_json(tally_run(run, conformance)).dump(2) + "\n"});
  outputs.push_back({rundir::run_folder::kFigureDataFile,
                     "figure data for the plots stage: box plots, Q-Q plots, relative "
                     "bihistograms, speed against error (schema renderaudit-figures v" +
                         std::to_string(kFiguresSchemaVersion) + ", analysis/figure_data.h)",
                     figures.dump() + "\n"});

  return outputs;
}

// Writes the outputs into DIR/analysis, with README.md listing them; removes the files of an
// earlier analysis that this one does not write again.
void write_outputs(const AnalyzeOptions& o, const std::vector<Output>& outputs,
                   const RunRecords& run, const RunCompleteness& completeness,
                   AnalyzeResult& result) {
  const fs::path out_dir = rundir::run_folder::analysis(o.run_dir);
  std::error_code ec;
  fs::create_directories(out_dir, ec);
  if (ec)
    throw util::UserError(out_dir.string() + ": cannot create the directory (" + ec.message() +
                          ")");
  for (const auto& e : fs::directory_iterator(out_dir)) {
    const std::string name = e.path().filename().string();
    bool current = false;
    for (const Output& out : outputs) current = current || out.name == name;
    if (!current && e.is_regular_file() && generated_name(name)) fs::remove(e.path(), ec);
  }
  for (const Output& out : outputs) {
    util::write_file_atomic((out_dir / out.name).string(), out.content);
    result.files.push_back(out.name);
  }
  util::write_file_atomic((out_dir / "README.md").string(),
                          files_readme(outputs, run, o, completeness));
  result.files.push_back("README.md");
  result.out_dir = out_dir.string();
}

}  // namespace

AnalyzeResult analyze_run(const AnalyzeOptions& o) {
  check_options(o);
  AnalyzeResult result;
  Stopwatch watch;
  // The records are loaded first, their seals read in the same pass; the completeness check then
  // judges the run from those seals instead of reading every file again. A run that is not whole
  // is refused as if it had been checked first: also when one of its files does not even parse.
  RunRecords run;
  try {
    run = load_records(o);
  } catch (const std::exception&) {
    refuse_if_incomplete(check_run_completeness(o.run_dir), o);
    throw;
  }
  const RunCompleteness completeness = check_run_completeness(o.run_dir, &run.seals);
  refuse_if_incomplete(completeness, o);
  result.completeness = completeness.one_line();
  result.records = run.record_count;
  result.timings.push_back({"load", watch.lap()});

  EquivalenceOptions eq;
  eq.alpha = o.alpha;
  eq.quantiles = o.quantiles;
  eq.comparison.box_cox_subsample = o.box_cox_subsample;
  eq.jobs = o.jobs;
  FigureOptions fo;
  fo.quantiles = o.quantiles;
  fo.jobs = o.jobs;
  fo.alpha = o.alpha;
  // The three statistics stages only read the records: they run at once, so that each one's serial
  // parts overlap the others' parallel ones. Each stage's own wall time is reported.
  const TableOptions to = table_options(o, eq);
  auto equivalence_task = timed_task([&] { return assess_view_equivalence(run, eq); });
  auto tables_task = timed_task([&] { return paper_tables(run, to); });
  auto figures_task = timed_task([&] { return figure_data(run, fo); });
  const std::vector<ViewEquivalence> equivalence = take(equivalence_task, "equivalence", result);
  const std::vector<stats::Table> tables = take(tables_task, "tables", result);
  const nlohmann::json figures = take(figures_task, "figures", result);
  result.comparisons = equivalence.size();
  for (const ViewEquivalence& e : equivalence)
    result.not_equivalent += e.verdict == Verdict::kNotEquivalent;
  result.timings.push_back({"statistics", watch.lap()});

  const ConformanceSummary& conformance = run.conformance;  // tallied while loading

  // render everything, then write
  std::string all_tables, printed;
  std::vector<Output> outputs = render_outputs(run, o, eq, equivalence, conformance, tables,
                                               figures, &all_tables, &printed);
  const std::string verdicts = verdicts_markdown(run, equivalence, o, result.not_equivalent);
  const std::string header = "# Analysis of " + run.run_dir + "\n\n" + completeness.markdown() +
                             "\n" + std::to_string(run.record_count) + " records; platforms: ";
  std::string platforms;
  for (std::size_t p = 0; p < run.platforms.size(); ++p) {
    platforms += (p ? ", " : "") + run.platforms[p];
  }
  outputs[0].content = header + platforms + "; quartiles " + quantile_label(o.quantiles) + ".\n\n" +
                       verdicts + "\n" + all_tables;
  result.summary = header + platforms + ".\n\n" + verdicts + "\n" + printed;
  write_outputs(o, outputs, run, completeness, result);
  result.timings.push_back({"write", watch.lap()});
  return result;
}

}  // namespace ra::analysis
