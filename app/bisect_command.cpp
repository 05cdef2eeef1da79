// `renderaudit bisect RUN --between GOOD_PLATFORM BAD_PLATFORM --source MESA --good REF --bad REF
// [-- PATHS]`: the commit that made each change (triage/bisect.h), and the report for the driver's
// developers (triage/bisect_report.h).
#include <cstdio>
#include <cstdlib>

#include "app/commands.h"
#include "triage/bisect.h"
#include "util/errors.h"
#include "util/interrupt.h"

namespace ra::app {

void register_bisect_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand(
      "bisect",
      "Name the driver commit that made each change of a run: every primitive whose pixels\n"
      "differ between two platforms of RUN (a sample covering every kind, view group and GL\n"
      "verdict change past --max-primitives; or those named) is drawn by builds of the commits\n"
      "between --good and --bad of a Mesa git tree (one incremental meson build folder, each\n"
      "build kept in the build cache), the next commit always the one that splits the most\n"
      "unresolved ranges, until each change sits between two neighbouring commits. A commit that\n"
      "fails to build is skipped for all. Resumable: the same command goes on where it stopped.\n"
      "Writes OUT/bisect.json and OUT/bisect.md (a section per culprit: reproducer, pictures, GL\n"
      "verdict). Prints one line per culprit: `first bad commit: HASH SUBJECT (N primitives)`.\n"
      "With --ways K, K commits are built at once each round (each in a git worktree; --slurm: as\n"
      "a Slurm job array), and each round prints `round R: K builds (...), N changes\n"
      "unresolved, about M rounds to go`; the end `R rounds, B builds, T of building`.\n"
      "With --speed, drawing time too: the groups whose time moved between the refs are placed\n"
      "at each step and their commits named, `first slower commit: HASH SUBJECT (KIND, view\n"
      "group G: RATIO x [LOW, HIGH])` or `first faster commit: ...` (docs/driver-builds.md).\n"
      "Exit 0: every change named; 1: some are left between failed builds (candidates listed);\n"
      "2: bad input; 130: interrupted (the tree restored).");
  struct Options {
    triage::BisectOptions o;
    std::vector<std::string> between;
    bool fresh_builds = false;
  };
  const auto opts = std::make_shared<Options>();  // alive as long as the callbacks
  cmd->add_option("run", opts->o.run_dir, "run directory whose records choose the primitives")
      ->required();
  cmd->add_option("--between", opts->between,
                  "GOOD_PLATFORM BAD_PLATFORM: two platforms of the run (e.g. egl-llvmpipe "
                  "egl-llvmpipe@backports)")
      ->expected(2);
  cmd->add_option("--baseline", opts->o.baseline_run,
                  "a second run whose GOOD_PLATFORM is compared with RUN's BAD_PLATFORM");
  cmd->add_option("--source", opts->o.source,
                  "Mesa git checkout (each step checks out a commit in it)")
      ->required();
  cmd->add_option("--good", opts->o.good_ref, "a ref that draws as the good platform")->required();
  cmd->add_option("--bad", opts->o.bad_ref, "a ref that draws as the bad platform")->required();
  cmd->add_option("--platform", opts->o.platform,
                  "the platform that draws every build (default: the bad platform without @build; "
                  "egl-llvmpipe for Mesa >= 25.1, which has no OSMesa)");
  cmd->add_option("--kind", opts->o.kinds, "select only these kinds (point, line, triangle)")
      ->check(CLI::IsMember({"point", "line", "triangle"}));
  cmd->add_option("--view", opts->o.views, "select only these views (1-based)")
      ->check(CLI::Range(1, 1000));
  cmd->add_option("--primitive", opts->o.primitives,
                  "KIND:VIEW:INDEX to select (repeatable) instead of the run's changes");
  cmd->add_option("--max-primitives", opts->o.max_primitives,
                  "at most this many of the run's changed primitives (past it: a sample covering "
                  "every kind, view group and verdict change)")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000000));
  cmd->add_option("--out,-o", opts->o.out_dir,
                  "the folder for bisect.json and bisect.md (default RUN/bisect)");
  add_commit_build_options(cmd, opts->o.build, opts->fresh_builds);
  cmd->add_option("--jobs,-j", opts->o.jobs, "drawing children at once, and ninja jobs");
  cmd->add_flag(
      "--no-pictures", [opts](int64_t) { opts->o.pictures = false; },
      "no `show` pictures in the report");
  add_speed_attribution_options(
      cmd, opts->o.speed,
      "also attribute drawing-time changes: the refs timed with an A/A control, each step's time "
      "placed between theirs, each culprit confirmed beside its parent");
  cmd->add_option("--ways", opts->o.ways,
                  "build this many commits at once each round, each in a git worktree of its own "
                  "(ninja -j max(1, jobs / WAYS) each): one culprit in n commits takes about "
                  "log_(WAYS+1) n rounds")
      ->capture_default_str()
      ->check(CLI::Range(1, 64));
  auto* on_slurm = cmd->add_flag(
      "--slurm", opts->o.slurm,
      "each round's builds as the tasks of a Slurm job array (the source's git folder and the "
      "build cache on a file system every node sees; drawing stays here)");
  cmd->add_option("--partition", opts->o.slurm_options.partition, "--slurm: the partition")
      ->needs(on_slurm);
  cmd->add_option("--max-parallel", opts->o.slurm_options.max_parallel,
                  "--slurm: at most this many builds at once (sbatch --array=...%M)")
      ->check(CLI::Range(1, 100000))
      ->needs(on_slurm);
  cmd->add_option("--time-limit", opts->o.slurm_options.time_limit,
                  "--slurm: each build's time limit, in sbatch --time syntax (e.g. 2:00:00)")
      ->needs(on_slurm);
  cmd->add_flag("--allow-node-local", opts->o.slurm_options.allow_node_local,
                "--slurm: accept a source or build cache that looks local to one node (/tmp, "
                "tmpfs), for a one-node cluster")
      ->needs(on_slurm);
  cmd->add_option("paths", opts->o.paths, "-- PATHS: only commits touching these");
  cmd->positionals_at_end(false);
  cmd->callback([opts, &exit_code] {
    triage::BisectOptions& o = opts->o;
    if (!opts->between.empty()) o.good_platform = opts->between[0], o.bad_platform = opts->between[1];
    o.build.jobs = o.jobs;
    // As `builds build` spells them: a build at once (--ways) finds its own in the cache.
    for (std::string& v : o.build.meson_options)
      if (v.rfind("-D", 0) != 0) v = "-D" + v;
    if (const char* sbatch = std::getenv("RENDERAUDIT_SBATCH"); sbatch && *sbatch)
      o.slurm_options.sbatch = sbatch;
    o.build.incremental = !opts->fresh_builds;
    check_speed_options("bisect", o.speed);
    o.command_line = triage::bisect_command_line(o);
    try {
      const triage::BisectResult r = triage::run_bisect(o, [](const std::string& text) {
        std::fprintf(stderr, "bisect: %s\n", text.c_str());
      });
      std::printf("report: %s\n", r.report_path.c_str());
      for (const triage::Unattributed& u : r.unattributed) {
        std::string cands;
        for (const std::string& c : u.candidates) cands += " " + c.substr(0, 12);
        std::printf("unattributed: %s (one of:%s)\n", u.label.c_str(), cands.c_str());
      }
      for (const triage::SpeedUnattributed& u : r.speed_unattributed) {
        std::string cands;
        for (const std::string& c : u.candidates) cands += " " + c.substr(0, 12);
        std::printf("unattributed: %s (%s%s%s)\n", u.group.label().c_str(), u.why.c_str(),
                    cands.empty() ? "" : ("; one of:" + cands).c_str(),
                    u.next_command.empty() ? "" : ("; without them: " + u.next_command).c_str());
      }
      for (const triage::Culprit& c : r.culprits)
        std::printf("first bad commit: %s %s (%zu primitive%s)\n", c.commit.c_str(),
                    c.subject.c_str(), c.primitives.size(), c.primitives.size() == 1 ? "" : "s");
      for (const triage::SpeedCulprit& c : r.speed_culprits)
        for (const std::string& line : triage::speed_culprit_lines(c))
          std::printf("%s\n", line.c_str());
      exit_code = r.complete() ? kExitOk : kExitFindings;
    } catch (const util::Interrupted& e) {
      std::fprintf(stderr, "bisect: %s: the tree is back where it was; the same command resumes\n",
                   e.what());
      exit_code = 128 + e.signal;
    }
  });
}

}  // namespace ra::app
