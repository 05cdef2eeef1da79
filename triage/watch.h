// `renderaudit watch SOURCE --experiment FILE --state DIR`: one night of a driver audit that
// follows a Mesa branch with no person in the loop, meant to run from cron or a systemd timer.
//
// A night: bring the tree's branch head (`git fetch` where the tree has a remote, then its
// upstream; else its HEAD); when it is last night's commit, say so and stop ("nothing new").
// Otherwise build it (runner/source_build.h, one incremental build folder), then run the
// experiment with last night's build and tonight's side by side in one run (platforms P@watch-last
// and P@watch-tonight for each of the file's platforms P: both drawn tonight, on the same machine,
// so a difference is the driver's), audit the two (`audit --between`), and when primitives
// changed, attribute every change to its commit between last night's and tonight's
// (triage/bisect.h). The history database records the night: commit, verdict and culprits.
//
// Bad nights: a build that fails is "build failed" (last night's build stays the one compared
// with tomorrow); a driver that crashes or a run that fails is "run failed"; a branch that moved
// backwards or was rewritten is "moved backwards" (tonight becomes the baseline, nothing is
// bisected). Exit code: 0 nothing new, unchanged or a baseline; 1 changed; 2 failed or bad input.
//
// The state folder: watch.json (the last good night: commit and build), nights/<UTC>/ (the
// night's experiment, run, audits, bisections, night.json and night.md), history.sqlite.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "runner/source_build.h"

namespace ra::triage {

struct WatchOptions {
  std::string source;      // the Mesa git tree
  std::string experiment;  // the experiment file (its platforms must be able to draw a build)
  std::string state;       // the state folder
  std::string db;          // "": STATE/history.sqlite
  runner::SourceBuildOptions build;  // cache, LLVM, meson options, build command
  unsigned jobs = 0;
  std::size_t max_primitives = 2000;  // per bisection
  bool pictures = true;
  bool fetch = true;       // git fetch when the tree has a remote
};

struct WatchNight {
  std::string date_utc, dir;            // the night's folder ("" on a night with nothing new)
  std::string run_dir;                  // the night's run ("" when none was made)
  std::string commit, previous_commit;  // tonight's, last good night's ("" on night 1)
  std::string verdict;                  // see the header
  std::vector<std::string> culprits;    // "HASH SUBJECT (N primitives)"
  std::size_t changed = 0;              // primitives that changed, all platforms
  std::size_t attributed = 0;           // of them, those the bisections named to a commit
  std::string note;                     // what happened, in a sentence
  int exit_code = 0;
};

// The note of a night whose primitives changed: "N primitives changed[ (M of them attributed: a
// sample, ...)], K culprit commit(s)".
std::string changed_night_note(std::size_t changed, std::size_t attributed, std::size_t culprit_commits);

WatchNight watch_night(const WatchOptions& options,
                       const std::function<void(const std::string&)>& progress = {});

}  // namespace ra::triage
