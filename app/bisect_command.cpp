// `renderaudit bisect RUN --between GOOD_PLATFORM BAD_PLATFORM --source MESA --good REF --bad REF
// [-- PATHS]`: the commit that made a finding (triage/bisect.h), and the report for the driver's
// developers (triage/bisect_report.h).
#include <cstdio>

#include "app/commands.h"
#include "triage/bisect.h"
#include "util/errors.h"
#include "util/shell_quote.h"

namespace ra::app {

void register_bisect_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand(
      "bisect",
      "Find the driver commit that changed a run's pixels: the primitives that differ most "
      "between\n"
      "two platforms of RUN (or those named) are drawn by a build of every commit git bisect\n"
      "chooses between --good and --bad of a Mesa git tree (built with meson, reused from the "
      "build\n"
      "cache when built before); a commit is good when every selected primitive has the good "
      "ref's\n"
      "pixels, bad when every one has the bad ref's, else skipped (said why). Resumable: the same\n"
      "command goes on where it stopped. Writes OUT/bisect.json and OUT/bisect.md, the report for\n"
      "the driver's developers (reproducer, pictures, versions). Exit 0: first bad commit found;\n"
      "1: only skipped commits are left (the candidates are listed); 2: bad input.");
  struct Options {
    triage::BisectOptions o;
    std::vector<std::string> between;
  };
  const auto opts = std::make_shared<Options>();  // alive as long as the callbacks
  cmd->add_option("run", opts->o.run_dir, "run directory whose records choose the primitives")
      ->required();
  cmd->add_option("--between", opts->between,
                  "GOOD_PLATFORM BAD_PLATFORM: two platforms of the run (e.g. egl-llvmpipe "
                  "egl-llvmpipe@backports)")
      ->expected(2);
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
                  "KIND:VIEW:INDEX to select (repeatable) instead of the run's largest changes");
  cmd->add_option("--max-primitives", opts->o.max_primitives,
                  "the run's changed primitives with the largest pixel change, at most this many")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000));
  cmd->add_option("--out,-o", opts->o.out_dir,
                  "where bisect.json and bisect.md go (default RUN/bisect)");
  cmd->add_option("--cache", opts->o.build.cache, "build cache folder");
  cmd->add_option("--llvm-config", opts->o.build.llvm_config, "the LLVM every build uses")
      ->capture_default_str();
  cmd->add_option("--meson-option,-D", opts->o.build.meson_options, "extra meson option KEY=VALUE");
  cmd->add_option("--build-command", opts->o.build.build_command,
                  "a shell command that installs the checked-out commit's driver into "
                  "$RENDERAUDIT_BUILD_PREFIX instead of meson");
  cmd->add_option("--jobs,-j", opts->o.jobs, "drawing children at once, and ninja jobs");
  cmd->add_flag(
      "--no-pictures", [opts](int64_t) { opts->o.pictures = false; },
      "no `show` pictures in the report");
  cmd->add_option("paths", opts->o.paths,
                  "-- PATHS: only commits touching these (git bisect -- PATHS)");
  cmd->positionals_at_end(false);
  cmd->callback([opts, &exit_code] {
    if (!opts->between.empty())
      opts->o.good_platform = opts->between[0], opts->o.bad_platform = opts->between[1];
    opts->o.build.jobs = opts->o.jobs;
    for (std::string& v : opts->o.build.meson_options)
      if (v.rfind("-D", 0) != 0) v = "-D" + v;
    // The command as a person would type it again (the report repeats it), every value one shell
    // word.
    std::vector<std::string> w = {"bisect", opts->o.run_dir};
    auto add = [&w](std::initializer_list<std::string> words) { w.insert(w.end(), words); };
    if (!opts->between.empty()) add({"--between", opts->between[0], opts->between[1]});
    add({"--source", opts->o.source, "--good", opts->o.good_ref, "--bad", opts->o.bad_ref});
    if (!opts->o.platform.empty()) add({"--platform", opts->o.platform});
    for (const std::string& k : opts->o.kinds) add({"--kind", k});
    for (int v : opts->o.views) add({"--view", std::to_string(v)});
    for (const std::string& p : opts->o.primitives) add({"--primitive", p});
    if (opts->o.max_primitives != triage::BisectOptions{}.max_primitives)
      add({"--max-primitives", std::to_string(opts->o.max_primitives)});
    if (!opts->o.out_dir.empty()) add({"--out", opts->o.out_dir});
    if (!opts->o.build.cache.empty()) add({"--cache", opts->o.build.cache});
    if (opts->o.build.llvm_config != runner::SourceBuildOptions{}.llvm_config)
      add({"--llvm-config", opts->o.build.llvm_config});
    for (const std::string& m : opts->o.build.meson_options) add({m});
    if (!opts->o.build.build_command.empty()) add({"--build-command", opts->o.build.build_command});
    if (!opts->o.paths.empty()) {
      add({"--"});
      for (const std::string& p : opts->o.paths) add({p});
    }
    opts->o.command_line = "renderaudit " + util::shell_command(w);
    const triage::BisectResult r = triage::run_bisect(opts->o, [](const std::string& line) {
      std::fprintf(stderr, "bisect: %s\n", line.c_str());
    });
    if (r.found) {
      std::printf("first bad commit: %s %s (%s)\nparent: %s\nreport: %s\n", r.first_bad.c_str(),
                  r.first_bad_subject.c_str(), r.first_bad_date.c_str(), r.parent.c_str(),
                  r.report_path.c_str());
      exit_code = kExitOk;
    } else {
      std::printf("no single first bad commit: skipped commits leave %zu candidates\nreport: %s\n",
                  r.candidates.size(), r.report_path.c_str());
      exit_code = kExitFindings;
    }
  });
}

}  // namespace ra::app
