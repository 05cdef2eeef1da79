// The decisions of a watch night (triage/watch.h), apart from the work that carries them out:
// plain data in, plain decisions out, no git, no files, no child processes. watch.cpp reads the
// tree and the state, builds, runs, audits and bisects, and asks these functions what each result
// means for the night: what kind of night it is, what to run, which platforms to bisect between
// which commits, its verdict, note and exit code, whether tonight becomes the baseline, and which
// old night folders --keep-nights removes.
//
// Verdicts and exit codes: "nothing new", "unchanged" and "baseline established" exit 0; "changed"
// and "moved backwards" exit 1; "fetch failed", "upstream gone", "build failed" and "run failed"
// exit 2.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "triage/bisect_speed.h"

namespace ra::triage {

// The builds of the night's experiment: each watched platform P is drawn as P@watch-last (last
// night's build) and P@watch-tonight.
inline constexpr const char* kLastBuild = "watch-last";
inline constexpr const char* kTonightBuild = "watch-tonight";

// What tonight is, once the branch head is known.
enum class NightKind {
  nothing_new,      // the head is last night's commit: nothing is built or run
  first_night,      // no last good night: tonight's build is drawn alone and becomes the baseline
  moved_backwards,  // the head does not descend from last night's commit: drawn alone, the new
                    // baseline, nothing bisected
  compare,          // both builds drawn tonight and audited against each other
};

// last_commit: the last good night's ("" when there is none); head: tonight's branch head;
// head_descends: whether last_commit is an ancestor of head (not looked at when last_commit is ""
// or is the head).
NightKind night_kind(const std::string& last_commit, const std::string& head, bool head_descends);

// What the bisections of a changed night found, all platforms together.
struct NightCounts {
  std::size_t changed = 0;       // primitives that changed (the bisected platforms')
  std::size_t bisected = 0;      // of them, those bisected (fewer: a sample)
  std::size_t attributed = 0;    // of those, the ones named to a commit
  std::size_t unattributed = 0;  // of those, the ones only failed builds separate from a cause
  std::size_t culprit_commits = 0;
  std::size_t time_moved = 0;             // --speed: groups whose drawing time moved (audits)
  std::size_t speed_culprit_commits = 0;  // commits named for them
};

// How a night ends: what night.json and the history record, the exit code, and whether tonight's
// build becomes the baseline (STATE/watch.json) the next night compares with.
struct NightEnd {
  std::string verdict, note;
  int exit_code = 0;
  bool moves_baseline = false;  // tonight's build becomes the baseline
  bool baseline_kept = false;   // changed, but last night's build stays the baseline
};

// The exit code of a verdict (see the header); 2 for a verdict it does not know.
int night_exit_code(const std::string& verdict);

// Whether tonight's build becomes the baseline the next night compares with: yes for a baseline,
// a moved-backwards, an unchanged or a changed night, unless a bisection could not run (then its
// changes stay between the baseline and the next night's head, to be bisected then). Changes
// that only failed builds separate from their cause advance: building those commits again would
// fail again, and their candidates are named.
bool night_moves_baseline(const std::string& verdict, const std::vector<std::string>& not_bisected);

// Upstream could not be seen ("fetch failed", "upstream gone", and why): nothing built.
NightEnd unseen_night(const std::string& verdict, const std::string& why);
// The branch head is last night's commit.
NightEnd nothing_new_night();
// Tonight's build failed: the note holds the error's first line (at most 160 characters) and
// names `error_file`, which holds all of it; last night's build, if any, stays the baseline.
NightEnd build_failed_night(const std::string& commit, const std::string& error,
                            const std::string& error_file, bool has_baseline);
// Whether the night's run went far enough to be audited (`run` exits 0, or 1 with findings).
bool run_finished(int run_exit_code);
// The run exited `run_exit_code` (not run_finished), its output in `log`.
NightEnd run_failed_night(int run_exit_code, const std::string& log);
// A first night or a branch that moved backwards (tonight drawn alone): tonight is the baseline.
NightEnd uncompared_night(NightKind kind, const std::string& last_commit);

// `renderaudit run` of the night's experiment into `run_dir` (--jobs: `jobs`, 2 when 0).
std::vector<std::string> run_arguments(const std::string& experiment, const std::string& run_dir,
                                       unsigned jobs);
// `renderaudit audit --between P@watch-last P@watch-tonight` of the night's run into `out`, its
// history in `db`; with --speed, drawing time judged too (warn-only: a slower group is a
// finding, not a failed audit).
std::vector<std::string> audit_arguments(const std::string& platform, const std::string& run_dir,
                                         const std::string& out, const std::string& db,
                                         unsigned jobs, const BisectSpeedOptions& speed);

// A platform's audit exit code: 0 alike, 1 changed, 2 or more failed (a driver crashed).
bool audit_failed(int audit_exit_code);
// Whether the audit wrote its verdict, so that its drawing times can be read.
bool audit_judged(int audit_exit_code);
// Whether the platform is bisected tonight: its primitives changed, or (--speed) `time_moved`
// groups' drawing time moved.
bool platform_needs_bisection(int audit_exit_code, std::size_t time_moved);

// The bisection of a platform that changed: last night's commit, drawn as P@watch-last, against
// tonight's head, drawn as P@watch-tonight, in the night's run.
struct NightBisection {
  std::string good_platform, bad_platform, good_ref, bad_ref;
};
NightBisection night_bisection(const std::string& platform, const std::string& last_commit,
                               const std::string& head);

// The note of a night whose primitives or drawing time changed: "N primitives changed[ (M of
// them bisected: a sample, ...)], K culprit commit(s)[, U not attributed (...)][; drawing time of
// G group(s) moved, S commit(s) named]"; a night of time alone: "no primitive changed; drawing
// time of G group(s) moved, S commit(s) named".
std::string changed_night_note(const NightCounts& counts);

// What a night that compared both builds found once every platform was audited (and bisected
// where it changed).
struct ComparedNight {
  bool audit_failed = false;  // a platform's audit failed (a driver crashed)
  bool changed = false;       // a platform's primitives or drawing time changed
  NightCounts counts;
  std::vector<std::string> not_bisected;  // "P: why": bisections that could not run
  bool speed = false;                     // --speed: drawing time judged
  std::string last_commit;                // the baseline's
  std::string night_dir;                  // the night's folder
};
// A failed audit fails the night ("run failed") even when another platform changed; nothing
// changed is "unchanged"; else "changed", whose baseline stays when a bisection could not run.
NightEnd compared_night(const ComparedNight& night);

// The folder name of the night that started at `date_utc` (2026-11-29T02:00:00Z ->
// 2026-11-29T02-00-00Z): names that sort in time.
std::string night_folder_name(const std::string& date_utc);

// The night folders (nights/<UTC>, names that sort in time) to remove so that the `keep` newest
// stay, oldest first; never `tonight`. Names that are not a night's stamp are left alone. Empty
// when keep is 0.
std::vector<std::string> nights_to_prune(std::vector<std::string> names, std::size_t keep,
                                         const std::string& tonight);

}  // namespace ra::triage
