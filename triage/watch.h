// `renderaudit watch SOURCE --experiment FILE --state DIR`: one night of a driver audit that
// follows a Mesa branch with no person in the loop, meant to run from cron or a systemd timer.
//
// A night: check the state and the experiment (before anything is built: bad input is refused,
// exit 2, and is no night); bring the tree's branch head (`git fetch` where the tree has a remote,
// then its upstream; else its HEAD); when it is last night's commit, say so and stop ("nothing
// new"). Otherwise build it (builds/source_build.h, one incremental build folder), then run the
// experiment with last night's build and tonight's side by side in one run (platforms P@watch-last
// and P@watch-tonight for each of the file's platforms P: both drawn tonight, on the same machine,
// so a difference is the driver's), audit the two (`audit --between`), and when primitives
// changed, attribute every change to its commit between last night's and tonight's
// (triage/bisect.h). The history database records the night: commit, verdict and culprits.
//
// Bad nights: a fetch that fails or an upstream branch that is gone is "fetch failed" or "upstream
// gone" (nothing built: a night that cannot see upstream must not say "nothing new"); a build that
// fails is "build failed" (last night's build stays the one compared with tomorrow); a driver that
// crashes or a run that fails is "run failed"; a branch that moved backwards or was rewritten is
// "moved backwards" (tonight becomes the baseline, nothing is bisected). Exit code: 0 nothing new,
// unchanged or a baseline; 1 changed or moved backwards; 2 failed or bad input. The night's
// decisions, apart from the work, are triage/watch_plan.h's.
//
// A night is recorded before the state moves on: night.json and night.md, then the history, then
// watch.json. A night that cannot record itself keeps last night's state, so the next night finds
// what it found again. A changed night whose bisection could not run keeps last night's commit and
// build as the baseline, so that the next night bisects those changes again with its own.
//
// The state folder: watch.json (the last good night: commit, build, branch and the tree it
// follows), nights/<UTC>/ (the night's experiment, run, audits and their history, bisections,
// night.json and night.md), history.sqlite. The night's audits write to the night's own
// nights/<UTC>/audits.sqlite and are copied into the history after the night's row, so a night
// stopped by a signal or kill -9 leaves no audit row in the history without its night.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "builds/source_build.h"
#include "triage/bisect_speed.h"
#include "triage/watch_plan.h"

namespace ra::triage {

struct WatchOptions {
  std::string source;      // the Mesa git tree
  std::string experiment;  // the experiment file (its platforms must be able to draw a build)
  std::string state;       // the state folder
  std::string db;          // "": STATE/history.sqlite
  builds::SourceBuildOptions build;  // cache, LLVM, meson options, build command
  unsigned jobs = 0;
  std::size_t max_primitives = 2000;  // per bisection
  bool pictures = true;
  bool fetch = true;       // git fetch when the tree has a remote
  // --speed: each audit judges drawing time too (warn-only: a slower group is a finding, not a
  // failed audit), and a night whose time moved is bisected for it (triage/bisect_speed.h)
  BisectSpeedOptions speed;
  // --keep-nights N: after a night is recorded, the folders of all but the N newest nights are
  // removed (0: every night kept; the history keeps its rows, their folders gone)
  std::size_t keep_nights = 0;
};

struct WatchNight {
  std::string date_utc, dir;            // the night's folder ("" on a night with nothing new)
  std::string run_dir;                  // the night's run ("" when none was made)
  std::string commit;                   // tonight's ("" when upstream could not be read)
  std::string previous_commit;          // last good night's ("" on night 1)
  std::string verdict;                  // see the header
  std::vector<std::string> culprits;    // "HASH SUBJECT (N primitives of P)": named commits only
  // --speed: "first slower commit: HASH SUBJECT (P: GROUP: RATIO x [LOW, HIGH])", or faster
  std::vector<std::string> speed_culprits;
  std::vector<std::string> unattributed;  // "N changes of P: ..." that no commit could be named for
  std::vector<std::string> not_bisected;  // "P: why": platforms whose bisection could not run
  NightCounts counts;
  bool baseline_kept = false;           // changed, but last night's build stays the baseline
  std::string note;                     // what happened, in a sentence
  int exit_code = 0;
};

// What `watch` prints on stdout for a night: "night: VERDICT: NOTE (COMMIT)", the night's folder,
// one "first bad commit: ..." per named commit, the "first slower/faster commit: ..." lines, and
// the changes no commit was named for under words of their own ("unattributed: ...", "not
// bisected: ..."), so that a script reading "first bad commit:" lines reads culprits only.
std::vector<std::string> night_lines(const WatchNight& night);

WatchNight watch_night(const WatchOptions& options,
                       const std::function<void(const std::string&)>& progress = {});

}  // namespace ra::triage
