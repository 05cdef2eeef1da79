// `renderaudit bisect`: every driver change a run found, each named to the commit that made it.
//
// A run holds two platforms whose records differ (e.g. `egl-llvmpipe` and `egl-llvmpipe@new`);
// every primitive whose pixels differ is selected (or a sample that covers each kind, view group
// and conformance transition, when there are more than --max-primitives; or those named). The
// good and the bad ref of a Mesa git tree are built (builds/source_build.h, one incremental build
// folder shared by every step) and draw the selection: their pixel hashes are the two ends, and
// primitives both draw alike are dropped. The commits between them are a line (`git rev-list
// --first-parent`, optionally restricted to paths); triage/bisect_plan.h chooses the next commit
// to build, the one that splits the most unresolved ranges, until each primitive's every change
// sits between two neighbouring commits. Each built commit draws every selected primitive in
// child processes (audit/flake_check.h's re-render, the commit's build declared in a private copy
// of the run's experiment). A commit that fails to build is skipped for all and named.
//
// The tree is locked for the whole bisection (one writer per tree), kept at the steps' commits
// and returned to its branch at the end, also when a signal stops the bisection (the build's
// process group is stopped first); after kill -9, the next bisection of the tree restores the
// branch bisect.json recorded. Every built step is written to OUT/bisect.json before the next is
// chosen, so the same command resumes where it stopped. OUT/bisect.md is the report for the
// driver's developers: one section per culprit commit (triage/bisect_report.h).
#pragma once

#include <functional>
#include <string>

#include "triage/bisect_types.h"

namespace ra::triage {

// The command that runs these options, as a person would paste it (every value shell-quoted): what
// the report's "Repeat it" shows.
std::string bisect_command_line(const BisectOptions& o);

// Runs (or resumes) the bisection. `progress` gets one line per event. Throws UserError for bad
// input (checked before anything is built: a run without the platforms, a tree that is not git or
// has uncommitted changes or is in use, refs that are not commits, equal refs, a good ref that is
// not an ancestor of the bad one, an OUT that is a file or holds another bisection), and
// util::Interrupted when a signal stopped it (the tree restored).
BisectResult run_bisect(const BisectOptions& options,
                        const std::function<void(const std::string&)>& progress = {});

// The build name each step's build has in the drawing children's experiment.
constexpr const char* kStepBuild = "bisect-step";

// The run's experiment.toml with [builds.bisect-step] dir = BUILD_DIR added: what draws a step.
std::string bisect_step_experiment(const std::string& run_dir, const std::string& build_dir);

}  // namespace ra::triage
