// The plain records of `renderaudit bisect` (triage/bisect.h): its options, the selected
// primitives, what each build drew, the rounds, the culprits and the result, which the bisection's
// parts (selection, steps, rounds, state file, report) share.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "geometry/primitive.h"
#include "util/slurm_sbatch.h"
#include "builds/source_build.h"
#include "triage/bisect_speed.h"

namespace ra::triage {

// One primitive of the selection, with what the run's two platforms drew.
struct BisectPrimitive {
  geometry::Kind kind = geometry::Kind::kPoint;
  int view = 0;        // 1-based
  uint64_t index = 0;  // under the run's seed
  int view_group = -1;  // 0 = A; -1: not from the run
  int64_t run_good_pixels = -1, run_bad_pixels = -1;  // the run's records (-1: not from the run)
  std::string run_good_conformance, run_bad_conformance;  // the run's GL verdicts ("": none)
  std::string label() const;  // "line 721 of view 5"
};

// What one build drew: pixel hash and lit pixels per selected primitive, by label().
struct Drawing {
  std::map<std::string, uint64_t> hashes;
  std::map<std::string, int64_t> pixels;
  std::string error;  // the drawing failed: why
};

struct BisectStep {
  std::string role;    // "good ref", "bad ref", "step"
  std::string commit, subject, date, version;
  std::size_t position = 0;  // on the line of commits: 0 the good ref, last the bad ref
  std::string error;         // the build or the drawing failed: why ("" when it drew)
  std::string summary;       // what it drew against the two ends, in words
  std::string build;         // the build's cache name ("" when the build failed)
  std::string build_dir;
  bool reused = false;
  double build_s = 0, draw_s = 0;
  Drawing drawing;
  // --speed: where this step's drawing time lies between the ends', for the groups whose
  // unresolved range holds it (empty for the ends and for steps no time range asked for)
  std::vector<StepTime> speed;
  double time_s = 0;  // seconds of timing
};

// One round of builds: --ways K commits built at once (one a round with --ways 1, in the tree).
struct BisectRound {
  std::size_t round = 0;                  // 1-based, counted over every invocation
  std::size_t ways = 1;                   // the --ways it ran with
  std::string where;                      // "tree" (--ways 1), "worktrees", "slurm"
  std::vector<std::string> commits;       // chosen, in line order
  std::vector<std::string> failed;        // their builds or drawings failed
  std::vector<std::string> cancelled;     // stopped: another result of the round resolved them
  std::size_t unresolved = 0;             // changes unresolved when it began
  std::size_t rounds_to_go = 0;           // the estimate said then, this round included
  double build_wall_s = 0;                // from its start to its last build's end
  double seconds = 0;                     // the whole round, drawing included
  bool finished = false;                  // false: interrupted (its finished steps are kept)
};

// A commit that changed primitives: each of them drew one way at `previous` and another here.
struct Culprit {
  std::string commit, subject, date;
  std::string previous;       // the commit before it on the line (its parent unless paths are given)
  bool merge = false;         // a merge commit: the change came with its merged branch
  std::vector<std::string> primitives;               // labels, in selection order
  std::map<std::string, std::pair<int64_t, int64_t>> pixels;  // label -> lit pixels before, after
};

// A change whose commit cannot be named: only failed builds lie between two drawn commits.
struct Unattributed {
  std::string label;
  std::string from, to;                 // the drawn commits on either side
  std::vector<std::string> candidates;  // the commits that may have made it
};

struct BisectOptions {
  std::string run_dir;                      // where the selection comes from
  std::string good_platform, bad_platform;  // two platforms of the run (--between)
  std::string baseline_run;  // "": both platforms in run_dir; else good_platform is this run's
  std::string platform;          // draws every build; "": the bad platform without its @build
  std::vector<std::string> kinds;           // selection filters ("line", ...); empty: all
  std::vector<int> views;                   // empty: all
  std::vector<std::string> primitives;      // explicit "KIND:VIEW:INDEX" (instead of the run's)
  std::size_t max_primitives = 2000;        // more changed ones: a sample covering every stratum
  std::string source;                       // Mesa git tree
  std::string good_ref, bad_ref;
  std::vector<std::string> paths;           // restrict the commits (rev-list -- PATHS)
  std::string out_dir;                      // "": RUN/bisect
  builds::SourceBuildOptions build;         // cache, LLVM, meson options, build command
  unsigned jobs = 0;                        // drawing children at once
  bool pictures = true;                     // `show` pictures in the report
  BisectSpeedOptions speed;                 // --speed: attribute drawing-time changes too
  std::string command_line;                 // how it was started, quoted (the report repeats it)
  // --ways K: K commits built at once each round, each in a git worktree of its own
  // (builds/build_slots.h) by a `builds build` process with ninja -j max(1, jobs / K); --slurm:
  // as the tasks of a Slurm job array (builds/slurm_builds.h). Drawing stays here.
  std::size_t ways = 1;
  bool slurm = false;
  util::SlurmOptions slurm_options;
};

struct BisectResult {
  std::vector<BisectPrimitive> selection;
  std::string selection_rule;        // how the selection was made, in words
  std::size_t changed_in_run = 0;    // changed primitives the run holds (before any sampling)
  std::vector<std::string> dropped;  // selected but drawn alike by both refs
  BisectStep good, bad;
  std::vector<BisectStep> steps;     // in order, resumed ones included
  std::vector<BisectRound> rounds;   // resumed ones included
  std::size_t commits_in_range = 0;  // on the line, the bad ref included
  std::vector<Culprit> culprits;     // by position on the line
  std::vector<Unattributed> unattributed;
  // --speed: every timed group at the ends, the commits that moved a group's drawing time, and
  // the moved groups no commit could be named for
  std::vector<SpeedAtEnds> speed_ends;
  std::vector<SpeedCulprit> speed_culprits;
  std::vector<SpeedUnattributed> speed_unattributed;
  std::string original_head;         // the branch (or commit) the tree is returned to
  double seconds = 0;                // this invocation's wall time
  double total_build_s = 0;          // all builds, resumed ones included
  std::string json_path, report_path;
  // Every change named: pixels and (with --speed) drawing time, at least one culprit.
  bool complete() const {
    return unattributed.empty() && speed_unattributed.empty() &&
           (!culprits.empty() || !speed_culprits.empty());
  }
};

}  // namespace ra::triage
