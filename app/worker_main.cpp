// renderaudit-worker: the `worker` subcommand alone, in a program that links only the runner.
// `run` and `audit` start one process per shard (or re-render); the full renderaudit links VTK,
// cairo, OpenImageIO and SQLite (329 shared libraries) and took 0.6 s to start here, this one
// 0.03 s. Found beside renderaudit (util/worker_program.h); renderaudit's own hidden `worker`
// subcommand does the same where it is missing.
#include <CLI/CLI.hpp>

#include "app/commands.h"
#include "app/exit_status.h"

int main(int argc, char** argv) {
  CLI::App app{"renderaudit-worker: runs one shard of a run (started by `renderaudit run`)"};
  app.require_subcommand(1);
  int exit_code = ra::app::kExitOk;
  ra::app::register_worker_command(app, exit_code);
  return ra::app::run_command_line(app, argc, argv, exit_code, "renderaudit-worker");
}
