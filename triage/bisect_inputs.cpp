// The bisection's inputs checked (bisect_inputs.h).
#include "triage/bisect_inputs.h"

#include <algorithm>
#include <filesystem>

#include "rundir/platform_spec.h"
#include "rundir/run_experiment.h"
#include "rundir/run_folder.h"
#include "builds/git_command.h"
#include "triage/bisect.h"
#include "triage/bisect_selection.h"
#include "triage/bisect_step.h"
#include "util/atomic_file.h"
#include "util/errors.h"

namespace fs = std::filesystem;

namespace ra::triage {
namespace {

using builds::git;
using builds::GitResult;

std::string rev(const std::string& dir, const std::string& ref, const char* option) {
  const GitResult g =
      git(dir, {"rev-parse", "--verify", "--quiet", "--end-of-options", ref + "^{commit}"});
  if (!g.ok || g.out.empty())
    throw util::UserError(std::string("bisect: ") + option + " '" + ref + "' is not a commit of " +
                          dir);
  return g.out;
}

}  // namespace

CheckedInputs check_bisect_inputs(BisectOptions& o, BisectResult& result) {
  std::error_code ec;
  if (!fs::exists(rundir::run_folder::experiment(o.run_dir), ec))
    throw util::UserError("bisect: " + o.run_dir + " is not a run directory (no experiment.toml)");
  if (o.source.empty() || !fs::is_directory(o.source, ec))
    throw util::UserError("bisect: --source '" + o.source + "' is not a folder");
  o.source = fs::canonical(o.source).string();
  if (o.out_dir.empty()) o.out_dir = rundir::run_folder::bisect(o.run_dir);
  if (fs::exists(o.out_dir, ec) && !fs::is_directory(o.out_dir, ec))
    throw util::UserError("bisect: --out " + o.out_dir +
                          " is a file; --out names a folder for bisect.json and bisect.md");
  // Inside the tree, the bisection's own state would be an untracked file that every step's
  // build sees, and that the advice for untracked files (`git clean`) would delete.
  const fs::path out = fs::weakly_canonical(fs::absolute(o.out_dir), ec);
  const fs::path rel = out.lexically_relative(o.source);
  if (!ec && !rel.empty() && *rel.begin() != "..")
    throw util::UserError("bisect: --out " + o.out_dir + " is inside the source tree " +
                          o.source +
                          ": every step's build would see bisect.json, and cleaning the tree "
                          "would delete it; choose a folder outside " + o.source);
  if (!git(o.source, {"rev-parse", "--git-dir"}).ok)
    throw util::UserError("bisect: " + o.source + " is not a git checkout");
  // A step's timing (--speed) compares the step with both ends on this machine, one after the
  // other; builds at once would time one another's load.
  if (o.speed.enabled && (o.ways > 1 || o.slurm))
    throw util::UserError("bisect: --speed times each step beside the ends on one quiet machine; "
                          "it does not go with --ways above 1 or --slurm (drop --speed, or bisect "
                          "the pixels with --ways first and the drawing time on the range left)");
  if (!git(o.source, {"status", "--porcelain", "--untracked-files=no"}).out.empty())
    throw util::UserError("bisect: " + o.source +
                          " has uncommitted changes; commit or stash them first (each step "
                          "checks out another commit)");
  // A file git does not track (often left by a checkout that failed half-way) is seen by every
  // step's build: an old commit's meson refuses a newer meson.options, for one.
  const std::string untracked =
      git(o.source, {"ls-files", "--others", "--exclude-standard", "--directory"}).out;
  if (!untracked.empty()) {
    std::vector<std::string> files;
    for (std::size_t at = 0; at < untracked.size();) {
      const std::size_t nl = std::min(untracked.find('\n', at), untracked.size());
      files.push_back(untracked.substr(at, nl - at));
      at = nl + 1;
    }
    std::string shown;
    for (std::size_t i = 0; i < files.size() && i < 3; ++i) shown += (i ? ", " : "") + files[i];
    if (files.size() > 3) shown += ", ...";
    throw util::UserError("bisect: " + o.source + " has " + std::to_string(files.size()) +
                          (files.size() == 1 ? " untracked file (" : " untracked files (") + shown +
                          "); every step's build would see it: `git -C " + o.source +
                          " clean -n -d` lists them, `git stash -u` or `git clean -fd` removes them");
  }
  const GitResult git_dir = git(o.source, {"rev-parse", "--absolute-git-dir"});
  if (!git_dir.ok)
    throw util::UserError("bisect: git rev-parse failed in " + o.source + ":\n" + git_dir.out);
  const std::string good = rev(o.source, o.good_ref, "--good");
  const std::string bad = rev(o.source, o.bad_ref, "--bad");
  if (good == bad)
    throw util::UserError("bisect: --good " + o.good_ref + " and --bad " + o.bad_ref +
                          " are the same commit (" + short_hash(good) + "): nothing between them");
  if (!git(o.source, {"merge-base", "--is-ancestor", good, bad}).ok)
    throw util::UserError("bisect: the good ref " + o.good_ref +
                          " is not an ancestor of the bad ref " + o.bad_ref + " in " + o.source);
  if (o.platform.empty()) o.platform = rundir::split_build(o.bad_platform).first;
  if (o.platform.empty())
    throw util::UserError("bisect: name the platform that draws each build (--platform, e.g. "
                          "egl-llvmpipe)");
  if (!rundir::find_platform(o.platform + "@" + kStepBuild))
    throw util::UserError("bisect: platform '" + o.platform +
                          "' cannot draw with a driver build (allowed: the osmesa-* and "
                          "surfaceless egl-* platforms, vk-lavapipe, faulty)");
  const Selection sel = select_primitives(o);
  const std::size_t views = rundir::load_run_experiment(o.run_dir).views.size();
  for (const BisectPrimitive& p : sel.primitives)
    if (p.view < 1 || std::size_t(p.view) > views)
      throw util::UserError("bisect: --primitive " + p.label() + ": the run has views 1-" +
                            std::to_string(views));
  result.selection = sel.primitives;
  result.selection_rule = sel.rule;
  result.changed_in_run = sel.changed;
  fs::create_directories(o.out_dir, ec);
  if (ec) throw util::UserError(util::io_error_message("cannot create", o.out_dir));
  return {git_dir.out, good, bad};
}

}  // namespace ra::triage
