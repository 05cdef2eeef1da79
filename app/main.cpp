// renderaudit: measures how accurately and how fast renderers draw points, lines and triangles.
// One program, git-style subcommands; see README.md.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <csignal>
#include <cstdio>
#include <string>
#include <vector>

#include "app/commands.h"
#include "app/exit_status.h"
#include "app/help_format.h"

int main(int argc, char** argv) {
  // A closed pipe on stdout (`renderaudit records RUN | head`) reaches the writer as EPIPE, which
  // ends the command quietly (util/standard_output.h), while a full disk stays an error it says:
  // not a death by SIGPIPE (exit 141) that cannot tell the two apart. Children inherit it, as
  // those of `run` must (runner/run_coordinator.cpp).
  std::signal(SIGPIPE, SIG_IGN);
  CLI::App app{
      "renderaudit: how accurately and how fast a renderer draws.\n"
      "Runs declarative experiments (experiments/*.toml) and turns them into statistics."};
  app.require_subcommand(1);
  app.set_version_flag("--version", "renderaudit 0.1.0");
  int exit_code = ra::app::kExitOk;
  ra::app::register_run_command(app, exit_code);
  ra::app::register_worker_command(app, exit_code);
  ra::app::register_stats_command(app, exit_code);
  ra::app::register_analyze_command(app, exit_code);
  ra::app::register_plot_command(app, exit_code);
  ra::app::register_report_command(app, exit_code);
  ra::app::register_audit_command(app, exit_code);
  ra::app::register_history_command(app, exit_code);
  ra::app::register_show_command(app, exit_code);
  ra::app::register_timing_command(app, exit_code);
  ra::app::register_platforms_command(app, exit_code);
  ra::app::register_merge_command(app, exit_code);
  ra::app::register_status_command(app, exit_code);
  ra::app::register_records_command(app, exit_code);
  ra::app::register_conformance_command(app, exit_code);
  ra::app::register_builds_command(app, exit_code);
  ra::app::register_reproduce_command(app, exit_code);
  ra::app::register_bisect_command(app, exit_code);
  ra::app::register_watch_command(app, exit_code);
  ra::app::use_help_format(app);
  // `renderaudit help [COMMAND]`: the same as `--help`.
  if (argc > 1 && std::string(argv[1]) == "help") {
    if (argc == 2) {
      std::fputs(app.help().c_str(), stdout);
      return ra::app::kExitOk;
    }
    std::vector<std::string> names;
    for (const CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) {
      if (sub->get_name() == argv[2]) {
        std::fputs(sub->help().c_str(), stdout);
        return ra::app::kExitOk;
      }
      names.push_back(sub->get_name());
    }
    const std::string near = ra::app::nearest_name(argv[2], names);
    std::fprintf(stderr, "renderaudit: unknown command '%s'%s (renderaudit --help lists them)\n",
                 argv[2], near.empty() ? "" : ("; did you mean '" + near + "'?").c_str());
    return ra::app::kExitUsage;
  }
  // A mistyped command ("analyse") is named with the nearest one, before CLI11 would read it as
  // a missing subcommand (or print the main help for `analyse --help`).
  if (argc > 1 && argv[1][0] != '-' && std::string(argv[1]) != "help") {
    std::vector<std::string> names;
    for (const CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; }))
      names.push_back(sub->get_name());
    if (const std::string unknown = argv[1];
        std::find(names.begin(), names.end(), unknown) == names.end()) {
      const std::string near = ra::app::nearest_name(unknown, names);
      std::fprintf(stderr, "renderaudit: unknown command '%s'%s (renderaudit --help lists them)\n",
                   unknown.c_str(), near.empty() ? "" : ("; did you mean '" + near + "'?").c_str());
      return ra::app::kExitUsage;
    }
  }
  return ra::app::exit_code_after_stdout(
      ra::app::run_command_line(app, argc, argv, exit_code, "renderaudit"), "renderaudit");
}
