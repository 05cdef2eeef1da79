// `renderaudit status DIR [--json] [--wait]`: where a run stands (runner/run_status.h), local or
// on Slurm, read without disturbing it.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <thread>

#include "app/commands.h"
#include "runner/run_status.h"

namespace ra::app {

// status only: the scheduler could not be asked, so the run's state is not known (--wait stops)
constexpr int kExitSchedulerUnknown = 4;

void register_status_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand(
      "status",
      "Where a run stands: shards done, running, failed and waiting, damaged records files, the\n"
      "time left, and the Slurm jobs of a `run --slurm`. Every records file is read and judged\n"
      "by its seal, as analyze judges it (--quick: only by its presence). Exit 0 when the run is\n"
      "complete, 3 while it is at work or queued, 1 when it stopped incomplete or a records file\n"
      "is damaged, 4 when the Slurm scheduler could not be asked (squeue missing or the\n"
      "controller unreachable: the state is not known).");
  struct Options {
    std::string dir;
    bool json = false;
    bool wait = false;
    bool quick = false;
    double every_s = 10;
  };
  const auto opts = std::make_shared<Options>();  // alive as long as the callbacks
  cmd->add_option("dir", opts->dir, "run directory")->required()->check(CLI::ExistingDirectory);
  cmd->add_flag("--json", opts->json, "one JSON object instead of lines");
  cmd->add_flag("--quick", opts->quick,
                "count a shard done when its records file exists, without reading it (no seal "
                "check: fast on a large run, and says so)");
  cmd->add_flag("--wait", opts->wait,
                "wait until the run is no longer at work or queued, then answer");
  cmd->add_option("--every", opts->every_s, "seconds between looks with --wait (default 10)")
      ->check(CLI::Range(0.1, 3600.0));
  cmd->callback([opts, &exit_code] {
    const char* env = std::getenv("RENDERAUDIT_SQUEUE");  // tests substitute a fake
    const std::string squeue = env && *env ? env : "squeue";
    runner::RunStatus s = runner::read_run_status(opts->dir, squeue, !opts->quick);
    while (opts->wait && (s.state() == "running" || s.state() == "queued")) {
      std::this_thread::sleep_for(std::chrono::duration<double>(opts->every_s));
      s = runner::read_run_status(opts->dir, squeue, !opts->quick);
    }
    if (opts->json)
      std::printf("%s\n", runner::to_json(s).dump(1).c_str());
    else
      std::printf("%s", runner::format_run_status(s).c_str());
    const std::string state = s.state();
    exit_code = state == "complete"                       ? kExitOk
                : state == "running" || state == "queued" ? kExitIncomplete
                : state == "unknown"                      ? kExitSchedulerUnknown
                                                          : kExitFindings;
  });
}

}  // namespace ra::app
