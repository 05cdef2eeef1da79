// `renderaudit watch SOURCE --experiment FILE --state DIR`: one night of the audit that follows a
// Mesa branch, builds it, audits it against last night's build and names the commit of every
// change (triage/watch.h).
#include <cstdio>

#include "app/commands.h"
#include "audit/history_db.h"
#include "triage/watch.h"
#include "util/errors.h"
#include "util/interrupt.h"

namespace ra::app {

void register_watch_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand(
      "watch",
      "One night of a driver audit that follows a Mesa branch (run it from cron or a systemd\n"
      "timer): fetch the tree's branch head, build it (one incremental build folder), run the\n"
      "experiment with last night's build and tonight's side by side, audit them, and when\n"
      "primitives changed, name the commit of every change between the two nights (as `bisect`).\n"
      "The history database (STATE/history.sqlite; `renderaudit history --db` shows it) records\n"
      "each night's commit, verdict and culprits; STATE/nights/<UTC>/night.md says what happened.\n"
      "A night whose head is last night's commit costs a fetch; a fetch that fails or an upstream\n"
      "branch that is gone is an error, never \"nothing new\". Exit 0: nothing new, unchanged or\n"
      "a first baseline; 1: changed (or the branch moved backwards); 2: the fetch, the build, the\n"
      "run or a driver failed, or bad input (a damaged watch.json, a state of another tree, an\n"
      "experiment whose platforms cannot draw a build).");
  struct Options {
    triage::WatchOptions o;
    bool fresh_builds = false, no_fetch = false;
  };
  const auto opts = std::make_shared<Options>();  // alive as long as the callbacks
  cmd->add_option("source", opts->o.source, "the Mesa git tree to follow")->required();
  cmd->add_option("--experiment,-e", opts->o.experiment,
                  "the experiment (its platforms draw each night's build, e.g. egl-llvmpipe)")
      ->required();
  cmd->add_option("--state", opts->o.state, "the state folder (last night, nights, history)")
      ->required();
  cmd->add_option("--db", opts->o.db, "history database (default STATE/history.sqlite)");
  add_commit_build_options(cmd, opts->o.build, opts->fresh_builds);
  cmd->add_flag("--no-fetch", opts->no_fetch, "follow the tree's own head (no git fetch)");
  cmd->add_option("--max-primitives", opts->o.max_primitives,
                  "changed primitives each bisection attributes (past it: a stratified sample)")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000000));
  add_speed_attribution_options(
      cmd, opts->o.speed,
      "also judge drawing time: each audit times both builds (warn-only), and a night whose time "
      "moved is bisected for it (`first slower commit:` / `first faster commit:` lines)");
  cmd->add_option("--keep-nights", opts->o.keep_nights,
                  "keep the folders of the N newest nights, removing older ones once a night is "
                  "recorded (default 0: keep every night; a night's folder is about 17 MB)")
      ->check(CLI::Range(std::size_t(0), std::size_t(1000000)));
  cmd->add_option("--jobs,-j", opts->o.jobs, "processes at once, and ninja jobs");
  cmd->add_flag(
      "--no-pictures", [opts](int64_t) { opts->o.pictures = false; },
      "no pictures in the bisection reports");
  cmd->callback([opts, &exit_code] {
    triage::WatchOptions& o = opts->o;
    o.build.jobs = o.jobs;
    o.build.incremental = !opts->fresh_builds;
    o.fetch = !opts->no_fetch;
    check_speed_options("watch", o.speed);
    for (std::string& v : o.build.meson_options)
      if (v.rfind("-D", 0) != 0) v = "-D" + v;
    try {
      const triage::WatchNight n = triage::watch_night(o, [](const std::string& text) {
        std::fprintf(stderr, "watch: %s\n", text.c_str());
      });
      for (const std::string& line : triage::night_lines(n)) std::printf("%s\n", line.c_str());
      exit_code = n.exit_code;
    } catch (const util::Interrupted& e) {
      std::fprintf(stderr, "watch: %s\n", e.what());
      exit_code = 128 + e.signal;
    }
  });
}

}  // namespace ra::app
