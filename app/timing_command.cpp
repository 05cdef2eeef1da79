// `renderaudit timing EXPERIMENT.toml [--out DIR] [--platform P ...] [--quiet] [--no-figures]`:
// the rendering-time study of Wimmer & Wonka 2003 (timing/timing_run.h) on OSMesa platforms:
// system-task constant c, heuristics H1-H4 fitted on object measurements, per-object sampling,
// and Table 6 along each scene's camera path. `renderaudit run` does the same for a file with a
// [timing] table; this command adds --no-figures.
#include <cstdio>
#include <string>
#include <vector>

#include "app/commands.h"
#include "timing/timing_run.h"

namespace ra::app {

void register_timing_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand(
      "timing",
      "The rendering-time study (Wimmer & Wonka 2003) on OSMesa platforms: each scene drawn as\n"
      "indexed triangle strips, the system-task constant c (99 %), heuristics H1-H4 fitted on\n"
      "object measurements, per-object sampling, and Table 6 (average squared error of frame\n"
      "time predictions along each camera path). Each platform is measured in its own process;\n"
      "run it on an otherwise idle machine.");
  struct Options {
    rundir::StudyRunOptions q;
    bool quiet = false;
    bool no_figures = false;
  };
  const auto opts = std::make_shared<Options>();  // alive as long as the callbacks
  cmd->add_option("experiment", opts->q.experiment,
                  "experiment file ([timing] and [[scene]] tables)")
      ->required();
  cmd->add_option("--out,-o", opts->q.out_dir, "output directory (default: outputs/<name>)");
  cmd->add_option("--platform,-p", opts->q.platforms,
                  "measure only these platforms of the experiment (repeatable)");
  cmd->add_flag("--quiet,-q", opts->quiet, "no progress lines on stderr");
  cmd->add_flag("--no-figures", opts->no_figures, "write the JSON and CSV files only");
  cmd->callback([opts, &exit_code] {
    opts->q.progress = !opts->quiet;
    const rundir::StudyRunResult r = timing::run_timing_study(opts->q, !opts->no_figures);
    std::printf("%s", r.summary.c_str());
    exit_code = r.findings ? kExitFindings : kExitOk;
  });
}

}  // namespace ra::app
