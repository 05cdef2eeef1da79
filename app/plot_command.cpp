// `renderaudit plot DIR`: every figure of a run as PNG + vector PDF (+ the numbers as CSV) in
// DIR/figures/, from DIR/analysis/figures.json and the records. Works without a display: a
// private Xvfb is started when DISPLAY is unset or unusable (plots/headless_display.h).
#include <unistd.h>

#include <cstdio>

#include "app/commands.h"
#include "plots/plot_run.h"
#include "rundir/study_dir.h"
#include "util/errors.h"

namespace ra::app {
namespace {

// `plot --list`: the plan without the drawing (a second or two: the records are read, no VTK).
void list_figures(const plots::PlotOptions& options) {
  if (rundir::read_study_info(options.run_dir))
    throw util::UserError("plot --list: " + options.run_dir +
                          " is a study folder (study.json); --list plans the figures of a run "
                          "directory");
  const plots::FigurePlan plan = plots::plan_figures(options.run_dir, options.jobs);
  for (const plots::Figure& f : plan.figures)
    std::printf("%s  %s\n", f.id.c_str(), f.title.c_str());
  for (const plots::SkippedFigure& s : plan.skipped)
    std::printf("  skipped (%s): %s: %s\n", s.section.c_str(), s.what.c_str(), s.reason.c_str());
  std::printf("%zu figures planned for %s (nothing drawn)\n", plan.figures.size(),
              options.run_dir.c_str());
}

}  // namespace

void register_plot_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand(
      "plot",
      "Draw every figure of a run (Q-Q plots, relative bihistograms, box plots, histograms,\n"
      "visibility classes, conformance with the reference rasterizer) as PNG and vector PDF,\n"
      "with the numbers drawn as CSV beside each, into DIR/figures/ (index.json lists them).\n"
      "Needs DIR/analysis/figures.json: run `renderaudit analyze DIR` first. Needs no display:\n"
      "starts a private Xvfb when DISPLAY is unset. For a study folder (study.json), the study's\n"
      "figures.");
  struct Options {
    plots::PlotOptions options;
    bool force_progress = false;
    bool quiet = false;
    bool list = false;
  };
  const auto opts = std::make_shared<Options>();  // alive as long as the callbacks
  cmd->add_option("dir", opts->options.run_dir, "run directory")->required();
  cmd->add_flag("--progress", opts->force_progress,
                "progress on stderr even when it is not a terminal (a line per figure); on a "
                "terminal it is shown by default, as one line rewritten");
  cmd->add_flag("--quiet,-q", opts->quiet, "no progress on stderr");
  cmd->add_flag("--list", opts->list,
                "print the figures the run would get (id and title, then the count) and the "
                "skipped ones, drawing nothing and leaving DIR/figures/ as it is");
  cmd->callback([opts, &exit_code] {
    opts->options.progress = !opts->quiet && (opts->force_progress || ::isatty(2));
    if (opts->list) {
      list_figures(opts->options);
      exit_code = kExitOk;
      return;
    }
    if (plot_study_if_present(opts->options.run_dir, exit_code)) return;
    const plots::PlotResult r = plots::plot_run(opts->options);
    // the figures skipped for lack of data, and why, are in index.json ("skipped")
    std::printf("plot: %zu figures (PNG + PDF + CSV) in %s, %.1f s, display %s%s; index: %s%s\n",
                r.figures.size(), r.figures_dir.c_str(), r.seconds, r.display.c_str(),
                r.private_xvfb ? " (private Xvfb, stopped)" : "", r.index_path.c_str(),
                r.skipped.empty()
                    ? ""
                    : (" (" + std::to_string(r.skipped.size()) + " skipped for lack of data: "
                       "its \"skipped\" says why)").c_str());
    exit_code = kExitOk;
  });
}

}  // namespace ra::app
