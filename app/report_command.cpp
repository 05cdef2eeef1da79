// `renderaudit report DIR`: DIR/report/report.pdf and report.html, the whole run in one document
// (report/report.h). The report stage only reads; this command first runs, in this process, the
// stages whose output is missing or stale (`analyze`, `plot`) unless --no-run.
#include <cstdio>

#include "analysis/run_analysis.h"
#include "analysis/run_completeness.h"
#include "analysis/run_finding.h"
#include "analysis/run_tally.h"
#include "app/commands.h"
#include "plots/plot_run.h"
#include "report/markdown_document.h"
#include "report/report.h"
#include "report/upgrade_sentences.h"
#include "triage/upgrade_report.h"
#include "util/errors.h"

namespace ra::app {
namespace {

// The stages a run's report needs, run here (the report stage itself never starts one).
void prepare_run_report(const std::string& dir, bool allow_incomplete) {
  for (const report::Step& s : report::missing_steps(dir)) {
    std::fprintf(stderr, "report: running `%s` (%s)\n", s.command.c_str(), s.reason.c_str());
    if (s.stage == "analyze") {
      analysis::AnalyzeOptions o;
      o.run_dir = dir;
      o.allow_incomplete = allow_incomplete;
      analysis::analyze_run(o);
    } else {
      plots::PlotOptions po;
      po.run_dir = dir;
      plots::plot_run(po);
    }
  }
}

}  // namespace

void register_report_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand(
      "report",
      "Write DIR/report/report.pdf and DIR/report/report.html: the experiment and its provenance,\n"
      "completeness, failures, time per primitive, conformance with the reference rasterizer, the\n"
      "view-equivalence tests, every table of DIR/analysis/ and every figure of DIR/figures/.\n"
      "Runs `renderaudit analyze DIR` and `renderaudit plot DIR` first when their output is\n"
      "missing or older than the records (--no-run: stop and name them instead). Needs no "
      "display.\n"
      "A run with missing or damaged shards is refused (exit 3) unless --allow-incomplete.\n"
      "For a study folder (study.json: timing, LOD, regulation): its text, tables and figures.\n"
      "--markdown FILE.md instead: that file as FILE.pdf and FILE.html beside it, its pictures\n"
      "(![caption](path)) in the text (the driver upgrade's report).\n"
      "--upgrade BUILD --platforms P... instead: print the driver upgrade report (Markdown) of\n"
      "each P against P@BUILD in DIR, from the audits in DIR/audit-P (--audit-suffix S:\n"
      "DIR/audit-PS), and write DIR/upgrade-summary-BUILD.json and the pictures it shows.\n"
      "--upgrade-sentences SUMMARY.json instead: print the driver upgrade report's first sentence\n"
      "(Markdown), and the culprits of a bisection of its run, from that summary.");
  struct Options {
    report::ReportOptions options;
    bool no_run = false;
    std::string markdown;
    std::string upgrade_summary;
    triage::UpgradeReportOptions upgrade;
    ConformanceGate gate;
  };
  const auto opts = std::make_shared<Options>();  // alive as long as the callbacks
  cmd->add_option("dir", opts->options.run_dir, "run directory");
  cmd->add_option("--markdown", opts->markdown,
                  "a Markdown file to set as PDF and HTML, instead of a run")
      ->check(CLI::ExistingFile);
  cmd->add_option("--upgrade-sentences", opts->upgrade_summary,
                  "print the driver upgrade's sentences from its summary (upgrade-summary-BUILD.json)")
      ->check(CLI::ExistingFile);
  cmd->add_option("--upgrade", opts->upgrade.build,
                  "the driver upgrade report of DIR against BUILD (needs --platforms)")
      ->option_text("BUILD");
  cmd->add_option("--platforms", opts->upgrade.platforms,
                  "with --upgrade: the platforms P audited against P@BUILD")
      ->expected(1, -1)
      ->option_text("P ...");
  cmd->add_option("--audit-suffix", opts->upgrade.audit_suffix,
                  "with --upgrade: the audits are in DIR/audit-P<SUFFIX> (default: DIR/audit-P)")
      ->option_text("SUFFIX");
  cmd->add_flag("--no-run", opts->no_run, "do not run missing stages; say which command to run");
  cmd->add_flag("--allow-incomplete", opts->options.allow_incomplete,
                "report a run with missing or damaged shards, saying so on its first page");
  add_conformance_gate_options(cmd, opts->gate);
  cmd->callback([opts, &exit_code] {
    if (!opts->upgrade_summary.empty()) {
      if (!opts->options.run_dir.empty() || !opts->markdown.empty())
        throw util::UserError("report: --upgrade-sentences takes no run directory and no --markdown");
      std::printf("%s", report::upgrade_sentences_markdown(
                            report::read_upgrade_summary(opts->upgrade_summary)).c_str());
      exit_code = kExitOk;
      return;
    }
    if (!opts->upgrade.build.empty()) {
      if (opts->options.run_dir.empty() || opts->upgrade.platforms.empty() ||
          !opts->markdown.empty())
        throw util::UserError(
            "report --upgrade BUILD needs a run directory and --platforms P..., and no --markdown");
      opts->upgrade.run_dir = opts->options.run_dir;
      std::printf("%s", triage::upgrade_report_markdown(opts->upgrade).c_str());
      exit_code = kExitOk;
      return;
    }
    if (!opts->upgrade.platforms.empty() || !opts->upgrade.audit_suffix.empty())
      throw util::UserError("report: --platforms and --audit-suffix go with --upgrade BUILD");
    if (!opts->markdown.empty()) {
      if (!opts->options.run_dir.empty())
        throw util::UserError("report: give a run directory or --markdown FILE.md, not both");
      const report::MarkdownDocumentResult r = report::write_markdown_document(opts->markdown);
      std::printf("report: %d pages, %d pictures", r.pages, r.pictures);
      if (r.missing_pictures)
        std::printf(" (%d not found: said in their place)", r.missing_pictures);
      std::printf("\n%s\n%s\n", r.pdf.c_str(), r.html.c_str());
      exit_code = kExitOk;
      return;
    }
    if (opts->options.run_dir.empty())
      throw util::UserError("report needs a run directory (or --markdown FILE.md)");
    read_conformance_gate(opts->gate);  // a malformed file stops before any work
    if (opts->gate.fail_on_violations && rundir::read_study_info(opts->options.run_dir))
      throw util::UserError(opts->options.run_dir +
                            ": --fail-on-violations judges a run's primitives; a study folder "
                            "has no verdicts");
    try {
      if (rundir::read_study_info(opts->options.run_dir))
        prepare_study_report(opts->options.run_dir, !opts->no_run);
      else if (!opts->no_run)
        prepare_run_report(opts->options.run_dir, opts->options.allow_incomplete);
      const report::ReportResult r = report::write_report(opts->options);
      std::printf("report: %s (and report.html): %d pages (%d text, %d figures), %zu tables, "
                  "%.1f s\n",
                  r.pdf.c_str(), r.pages, r.text_pages, r.figure_pages, r.table_titles.size(),
                  r.seconds);
      if (!r.completeness.empty() && r.completeness.rfind("complete", 0) != 0)
        std::printf("run %s\n", r.completeness.c_str());
      // What the run found, from the data: the one line a terminal needs (a study's report has
      // its own findings in its text). The report is written by now: a tally it cannot read
      // (an analysis by an older renderaudit) costs the line, not the report.
      if (!rundir::read_study_info(opts->options.run_dir)) try {
          std::printf("%s\n",
                      analysis::run_finding_line(analysis::read_tally(opts->options.run_dir),
                                                 opts->options.run_dir)
                          .c_str());
        } catch (const util::UserError& e) {
          std::printf("finding: not said here (%s)\n", e.what());
        }
      exit_code = conformance_gate_exit(opts->gate, opts->options.run_dir, kExitOk);
    } catch (const analysis::IncompleteRunError& e) {
      std::fprintf(stderr, "renderaudit report: %s\n", e.what());
      exit_code = kExitIncomplete;
    }
  });
}

}  // namespace ra::app
