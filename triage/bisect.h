// `renderaudit bisect`: the driver change that made a finding, found in the driver's git history.
//
// A run holds two platforms whose records differ (e.g. `egl-llvmpipe` and `egl-llvmpipe@new`);
// the primitives whose pixels changed most (or those named) are the selection. The good and the
// bad ref of a Mesa git tree are built (runner/source_build.h) and draw the selection first: their
// pixel hashes are the two references, and primitives both draw alike are dropped. Then `git
// bisect` (optionally restricted to paths) chooses commits; each is built (or reused from the build
// cache), draws the selection in child processes (audit/flake_check.h's re-render, with the
// commit's build declared in a private copy of the run's experiment), and is judged:
//   good: every selected primitive has the good ref's pixels;
//   bad:  every selected primitive has the bad ref's pixels;
//   skip: the build failed, the drawing failed, or the pixels are neither (each named).
// Every judged step is written to OUT/bisect.json before git is told, so a bisection that is
// interrupted resumes where it stopped (the same command; the steps are replayed into git). At the
// end the first bad commit's parent is drawn too (if no step did), the tree is returned to where
// it was (`git bisect reset`), and OUT/bisect.md is the report for the driver's developers
// (triage/bisect_report.h).
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "geometry/primitive.h"
#include "runner/source_build.h"

namespace ra::triage {

// One primitive of the selection, with what the run's two platforms drew.
struct BisectPrimitive {
  geometry::Kind kind = geometry::Kind::kPoint;
  int view = 0;        // 1-based
  uint64_t index = 0;  // under the run's seed
  int64_t run_good_pixels = -1, run_bad_pixels = -1;  // the run's records (-1: not from the run)
  std::string label() const;  // "line 721 of view 5"
};

// What one build drew: pixel hash and lit pixels per selected primitive, by label().
struct Drawing {
  std::map<std::string, uint64_t> hashes;
  std::map<std::string, int64_t> pixels;
  std::string error;  // the drawing failed: why
};

enum class StepVerdict { kGood, kBad, kSkip };
const char* verdict_name(StepVerdict v);  // "good", "bad", "skip"

// good/bad/skip of a drawing against the two references, with the reason in words
// ("pixels are neither: 3 like the good ref, 1 like the bad ref, 1 like neither (line 5/721: ...)").
std::pair<StepVerdict, std::string> judge_drawing(const std::vector<BisectPrimitive>& selection,
                                              const Drawing& drawing, const Drawing& good,
                                              const Drawing& bad);

struct BisectStep {
  std::string role;    // "good ref", "bad ref", "step", "parent of the first bad commit"
  std::string commit, subject, date, version;
  StepVerdict verdict = StepVerdict::kSkip;
  std::string reason;
  std::string build;   // the build's cache name ("" when the build failed)
  std::string build_dir;
  bool reused = false;
  double build_s = 0, draw_s = 0;
  Drawing drawing;
};

struct BisectOptions {
  std::string run_dir;                      // where the selection comes from
  std::string good_platform, bad_platform;  // two platforms of the run (--between)
  std::string platform;          // draws every build; "": the bad platform without its @build
  std::vector<std::string> kinds;           // selection filters ("line", ...); empty: all
  std::vector<int> views;                   // empty: all
  std::vector<std::string> primitives;      // explicit "KIND:VIEW:INDEX" (instead of the run's)
  std::size_t max_primitives = 24;          // the largest pixel changes first
  std::string source;                       // Mesa git tree
  std::string good_ref, bad_ref;
  std::vector<std::string> paths;           // restrict the commits (git bisect -- PATHS)
  std::string out_dir;                      // "": RUN/bisect
  runner::SourceBuildOptions build;         // cache, LLVM, meson options, build command
  unsigned jobs = 0;                        // drawing children at once
  bool pictures = true;                     // `show` pictures in the report
  std::string command_line;                 // how it was started (the report repeats it)
};

struct BisectResult {
  std::vector<BisectPrimitive> selection;
  std::vector<std::string> dropped;  // selected but drawn alike by both refs
  BisectStep good, bad;
  std::vector<BisectStep> steps;     // in order, resumed ones included
  bool found = false;
  std::string first_bad, first_bad_subject, first_bad_date, parent;
  std::vector<std::string> candidates;  // when skips leave several commits
  std::map<std::string, BisectStep> confirm;  // "first bad" and "parent": their drawings
  double seconds = 0;          // this invocation's wall time
  double total_build_s = 0;    // all steps' builds, resumed ones included
  std::string json_path, report_path;
};

// Runs (or resumes) the bisection. `progress` gets one line per event. Throws UserError for bad
// input (a run without the platforms, a tree that is not git or has uncommitted changes, refs
// that are not commits, a good ref that is not an ancestor of the bad one, references that draw
// the selection alike, an OUT of another bisection).
BisectResult run_bisect(const BisectOptions& options,
                        const std::function<void(const std::string&)>& progress = {});

// The build name each step's build has in the drawing children's experiment.
constexpr const char* kStepBuild = "bisect-step";

// The run's experiment.toml with [builds.bisect-step] dir = BUILD_DIR added: what draws a step.
std::string bisect_step_experiment(const std::string& run_dir, const std::string& build_dir);

// "KIND:VIEW:INDEX" -> primitive; throws UserError naming the allowed form.
BisectPrimitive parse_primitive(const std::string& text);

}  // namespace ra::triage
