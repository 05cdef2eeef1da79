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
      "Where a run stands: shards done, running, failed and waiting, the time left, and the\n"
      "Slurm jobs of a `run --slurm`. Exit 0 when the run is complete, 3 while it is at work or\n"
      "queued, 1 when it stopped incomplete, 4 when the Slurm scheduler could not be asked\n"
      "(squeue missing or the controller unreachable: the state is not known).");
  static std::string dir;
  static bool json = false, wait = false;
  static double every_s = 10;
  cmd->add_option("dir", dir, "run directory")->required()->check(CLI::ExistingDirectory);
  cmd->add_flag("--json", json, "one JSON object instead of lines");
  cmd->add_flag("--wait", wait, "wait until the run is no longer at work or queued, then answer");
  cmd->add_option("--every", every_s, "seconds between looks with --wait (default 10)")
      ->check(CLI::Range(0.1, 3600.0));
  cmd->callback([&exit_code] {
    const char* env = std::getenv("RENDERAUDIT_SQUEUE");  // tests substitute a fake
    const std::string squeue = env && *env ? env : "squeue";
    runner::RunStatus s = runner::read_run_status(dir, squeue);
    while (wait && (s.state() == "running" || s.state() == "queued")) {
      std::this_thread::sleep_for(std::chrono::duration<double>(every_s));
      s = runner::read_run_status(dir, squeue);
    }
    if (json)
      std::printf("%s\n", runner::to_json(s).dump(1).c_str());
    else
      std::printf("%s", runner::format_run_status(s).c_str());
    const std::string state = s.state();
    exit_code = state == "complete"                      ? kExitOk
                : state == "running" || state == "queued" ? kExitIncomplete
                : state == "unknown"                      ? kExitSchedulerUnknown
                                                          : kExitFindings;
  });
}

}  // namespace ra::app
