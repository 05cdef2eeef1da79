// `renderaudit report DIR`: DIR/report/report.pdf and report.html, the whole run in one document
// (report/report.h). Runs `analyze` and `plot` first when their output is missing or stale.
#include <cstdio>

#include "app/commands.h"
#include "report/report.h"

namespace ra::app {

void register_report_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand(
      "report",
      "Write DIR/report/report.pdf and DIR/report/report.html: the experiment and its provenance,\n"
      "failures, time per primitive, conformance with the reference rasterizer, the view-\n"
      "equivalence tests, every table of DIR/analysis/ and every figure of DIR/figures/.\n"
      "Runs `renderaudit analyze DIR` and `renderaudit plot DIR` first when their output is\n"
      "missing or older than the records (--no-run: stop and name them instead). Needs no display.\n"
      "For a study folder (study.json: timing, LOD, regulation): its text, tables and figures.");
  static report::ReportOptions options;
  static bool no_run = false;
  cmd->add_option("dir", options.run_dir, "run directory")->required();
  cmd->add_flag("--no-run", no_run, "do not run missing stages; say which command to run");
  cmd->callback([&exit_code] {
    options.run_missing = !no_run;
    prepare_study_report(options.run_dir, options.run_missing);
    const report::ReportResult r = report::write_report(options);
    std::printf("report: %d pages (%d text, %d figures), %zu tables, %.1f s\n", r.pages,
                r.text_pages, r.figure_pages, r.table_titles.size(), r.seconds);
    std::printf("%s\n%s\n", r.pdf.c_str(), r.html.c_str());
    exit_code = kExitOk;
  });
}

}  // namespace ra::app
