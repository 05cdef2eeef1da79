#include "triage/watch_plan.h"

#include <gtest/gtest.h>

namespace ra::triage {
namespace {

const std::string kLast = std::string(40, 'a');
const std::string kHead = std::string(40, 'b');

NightCounts counts(std::size_t changed, std::size_t bisected, std::size_t attributed,
                   std::size_t unattributed, std::size_t culprits) {
  NightCounts n;
  n.changed = changed;
  n.bisected = bisected;
  n.attributed = attributed;
  n.unattributed = unattributed;
  n.culprit_commits = culprits;
  return n;
}

// A night that compared both builds, nothing found yet.
ComparedNight compared() {
  ComparedNight n;
  n.last_commit = kLast;
  n.night_dir = "/state/nights/N";
  return n;
}

TEST(NightKind, TheHeadAgainstLastNightsCommit) {
  // Night 1: no baseline, whatever the ancestry says.
  EXPECT_EQ(night_kind("", kHead, false), NightKind::first_night);
  // The head is last night's commit: nothing new, even where its ancestry was not read.
  EXPECT_EQ(night_kind(kLast, kLast, false), NightKind::nothing_new);
  EXPECT_EQ(night_kind(kLast, kLast, true), NightKind::nothing_new);
  EXPECT_EQ(night_kind(kLast, kHead, true), NightKind::compare);
  // Reset or rewritten upstream: tonight is drawn alone and becomes the baseline.
  EXPECT_EQ(night_kind(kLast, kHead, false), NightKind::moved_backwards);
}

TEST(NightExitCode, EachVerdictsCode) {
  for (const char* v : {"nothing new", "unchanged", "baseline established"})
    EXPECT_EQ(night_exit_code(v), 0) << v;
  for (const char* v : {"changed", "moved backwards"}) EXPECT_EQ(night_exit_code(v), 1) << v;
  for (const char* v : {"fetch failed", "upstream gone", "build failed", "run failed", "other"})
    EXPECT_EQ(night_exit_code(v), 2) << v;
}

// Changes whose bisection could not run stay between the baseline and the next night's head, so
// that the next night bisects them; every other kept verdict moves the baseline to tonight.
TEST(NightMovesBaseline, AChangedNightWhoseBisectionCouldNotRunKeepsTheBaseline) {
  EXPECT_FALSE(night_moves_baseline("changed", {"faulty: bisect: refused"}));
  EXPECT_TRUE(night_moves_baseline("changed", {}));
  for (const char* v : {"baseline established", "moved backwards", "unchanged"})
    EXPECT_TRUE(night_moves_baseline(v, {})) << v;
  for (const char* v :
       {"nothing new", "build failed", "run failed", "fetch failed", "upstream gone"})
    EXPECT_FALSE(night_moves_baseline(v, {})) << v;
}

// A night that cannot see upstream is an error that keeps the baseline, never "nothing new".
TEST(NightEnd, UpstreamUnseenAndNothingNewKeepTheBaseline) {
  const NightEnd unseen = unseen_night("fetch failed", "git fetch failed");
  EXPECT_EQ(unseen.verdict, "fetch failed");
  EXPECT_EQ(unseen.note, "git fetch failed");
  EXPECT_EQ(unseen.exit_code, 2);
  EXPECT_FALSE(unseen.moves_baseline);
  const NightEnd same = nothing_new_night();
  EXPECT_EQ(same.verdict, "nothing new");
  EXPECT_EQ(same.note, "the branch head is last night's commit");
  EXPECT_EQ(same.exit_code, 0);
  EXPECT_FALSE(same.moves_baseline);
}

// One line on stdout: the error's first line, cut at 160 characters; all of it in its file.
TEST(NightEnd, AFailedBuildSaysItsFirstLineAndKeepsLastNightsBuild) {
  const NightEnd e =
      build_failed_night(kHead, "meson: no compiler\nmore\nlines", "/n/err.txt", true);
  EXPECT_EQ(e.verdict, "build failed");
  EXPECT_EQ(e.note,
            "the build of bbbbbbbbbbbb failed (meson: no compiler; the whole error: /n/err.txt); "
            "last night's build stays the baseline");
  EXPECT_EQ(e.exit_code, 2);
  EXPECT_FALSE(e.moves_baseline);
  // A failed first night has no baseline to keep.
  const NightEnd first = build_failed_night(kHead, std::string(200, 'x'), "/n/err.txt", false);
  EXPECT_EQ(first.note, "the build of bbbbbbbbbbbb failed (" + std::string(157, 'x') +
                            "...; the whole error: /n/err.txt)");
  const std::string exactly(160, 'y');
  EXPECT_NE(build_failed_night(kHead, exactly, "f", false).note.find(exactly + ";"),
            std::string::npos);
}

TEST(NightEnd, ARunThatDidNotFinishFailsTheNight) {
  EXPECT_TRUE(run_finished(0));
  EXPECT_TRUE(run_finished(1));  // findings: still audited
  EXPECT_FALSE(run_finished(2));
  EXPECT_FALSE(run_finished(143));
  const NightEnd e = run_failed_night(143, "/n/run.log");
  EXPECT_EQ(e.verdict, "run failed");
  EXPECT_EQ(e.note, "the run exited 143 (/n/run.log)");
  EXPECT_EQ(e.exit_code, 2);
  EXPECT_FALSE(e.moves_baseline);
}

TEST(NightEnd, AFirstNightOrABranchMovedBackwardsBecomesTheBaseline) {
  const NightEnd first = uncompared_night(NightKind::first_night, "");
  EXPECT_EQ(first.verdict, "baseline established");
  EXPECT_EQ(first.note, "tonight's build is the baseline from now on");
  EXPECT_EQ(first.exit_code, 0);
  EXPECT_TRUE(first.moves_baseline);
  const NightEnd back = uncompared_night(NightKind::moved_backwards, kLast);
  EXPECT_EQ(back.verdict, "moved backwards");
  EXPECT_EQ(back.note,
            "the branch no longer holds last night's commit aaaaaaaaaaaa: tonight is the new "
            "baseline");
  EXPECT_EQ(back.exit_code, 1);
  EXPECT_TRUE(back.moves_baseline);
  EXPECT_FALSE(back.baseline_kept);
}

TEST(NightCommands, TheRunAndEachPlatformsAudit) {
  EXPECT_EQ(run_arguments("/n/experiment.toml", "/n/run", 0),
            (std::vector<std::string>{"run", "/n/experiment.toml", "--out", "/n/run", "--quiet",
                                      "--jobs", "2"}));
  EXPECT_EQ(run_arguments("e", "r", 6).back(), "6");
  BisectSpeedOptions speed;
  EXPECT_EQ(audit_arguments("faulty", "/n/run", "/n/audit-faulty", "/n/audits.sqlite", 4, speed),
            (std::vector<std::string>{"audit", "/n/run", "--between", "faulty@watch-last",
                                      "faulty@watch-tonight", "--out", "/n/audit-faulty", "--db",
                                      "/n/audits.sqlite", "--jobs", "4"}));
  // --speed: warn-only, with the night's repeats, primitives and threshold.
  speed.enabled = true;
  speed.repeats = 8;
  speed.per_view = 60;
  speed.threshold = 0.05;
  const std::vector<std::string> timed = audit_arguments("faulty", "r", "o", "d", 0, speed);
  const std::vector<std::string> tail(timed.begin() + 11, timed.end());
  EXPECT_EQ(tail,
            (std::vector<std::string>{"--speed", "--speed-warn-only", "--speed-repeats", "8",
                                      "--speed-primitives", "60", "--speed-threshold", "0.05"}));
  EXPECT_EQ(timed[10], "2");
}

// The audit's exit code per platform: 0 alike, 1 changed, 2 or more failed.
TEST(PlatformAudit, ChangedUnchangedOrFailed) {
  EXPECT_FALSE(audit_failed(0));
  EXPECT_FALSE(audit_failed(1));
  EXPECT_TRUE(audit_failed(2));
  EXPECT_TRUE(audit_failed(137));  // a driver killed
  EXPECT_TRUE(audit_judged(0));
  EXPECT_TRUE(audit_judged(1));
  EXPECT_FALSE(audit_judged(2));  // no verdict written: no drawing times to read
  EXPECT_FALSE(platform_needs_bisection(0, 0));
  EXPECT_TRUE(platform_needs_bisection(1, 0));
  EXPECT_TRUE(platform_needs_bisection(0, 2));  // --speed: time alone moved
  EXPECT_FALSE(platform_needs_bisection(2, 0));
}

TEST(NightBisection, LastNightsCommitAgainstTonightsHead) {
  const NightBisection b = night_bisection("egl-llvmpipe", kLast, kHead);
  EXPECT_EQ(b.good_platform, "egl-llvmpipe@watch-last");
  EXPECT_EQ(b.bad_platform, "egl-llvmpipe@watch-tonight");
  EXPECT_EQ(b.good_ref, kLast);
  EXPECT_EQ(b.bad_ref, kHead);
}

TEST(ChangedNightNote, EveryChangeAttributed) {
  EXPECT_EQ(changed_night_note(counts(40, 40, 40, 0, 2)),
            "40 primitives changed, 2 culprit commit(s)");
  EXPECT_EQ(changed_night_note(counts(1, 1, 1, 0, 1)), "1 primitive changed, 1 culprit commit(s)");
}

// A night past --max-primitives attributes a sample: the note must not call the sample the change.
TEST(ChangedNightNote, ASampleIsNotCalledTheWholeChange) {
  EXPECT_EQ(
      changed_night_note(counts(2005, 2000, 2000, 0, 1)),
      "2005 primitives changed (2000 of them bisected: a sample, see the bisection's report), "
      "1 culprit commit(s)");
}

// Every change bisected, none named (only failed builds between): not a sample, and said.
TEST(ChangedNightNote, ChangesNoCommitCouldBeNamedForAreNotCalledASample) {
  EXPECT_EQ(changed_night_note(counts(40, 40, 0, 40, 0)),
            "40 primitives changed, 0 culprit commit(s), 40 change(s) not attributed (only commits "
            "that failed to build lie between)");
}

TEST(ChangedNightNote, DrawingTimeAloneOrWithPixels) {
  NightCounts time = counts(0, 0, 0, 0, 0);
  time.time_moved = 1;
  time.speed_culprit_commits = 1;
  EXPECT_EQ(changed_night_note(time),
            "no primitive changed; drawing time of 1 group moved, 1 commit(s) named");
  NightCounts both = counts(60, 60, 60, 0, 1);
  both.time_moved = 2;
  both.speed_culprit_commits = 1;
  EXPECT_EQ(changed_night_note(both),
            "60 primitives changed, 1 culprit commit(s); drawing time of 2 groups moved, 1 "
            "commit(s) named");
}

// A failed audit fails the night even when another platform changed: its changes are not
// trusted as a night's finding, and the baseline stays.
TEST(ComparedNight, AFailedAuditWinsOverAChange) {
  ComparedNight n = compared();
  n.audit_failed = true;
  n.changed = true;
  n.counts = counts(40, 40, 40, 0, 1);
  const NightEnd e = compared_night(n);
  EXPECT_EQ(e.verdict, "run failed");
  EXPECT_EQ(e.note, "a driver crashed or the audit failed (/state/nights/N)");
  EXPECT_EQ(e.exit_code, 2);
  EXPECT_FALSE(e.moves_baseline);
  EXPECT_FALSE(e.baseline_kept);
}

TEST(ComparedNight, UnchangedMovesTheBaseline) {
  ComparedNight n = compared();
  NightEnd e = compared_night(n);
  EXPECT_EQ(e.verdict, "unchanged");
  EXPECT_EQ(e.note, "no primitive changed");
  EXPECT_EQ(e.exit_code, 0);
  EXPECT_TRUE(e.moves_baseline);
  n.speed = true;
  EXPECT_EQ(compared_night(n).note, "no primitive changed, no drawing time moved");
}

TEST(ComparedNight, ChangedAndBisectedMovesTheBaseline) {
  ComparedNight n = compared();
  n.changed = true;
  n.counts = counts(40, 40, 40, 0, 2);
  const NightEnd e = compared_night(n);
  EXPECT_EQ(e.verdict, "changed");
  EXPECT_EQ(e.note, "40 primitives changed, 2 culprit commit(s)");
  EXPECT_EQ(e.exit_code, 1);
  EXPECT_TRUE(e.moves_baseline);
  EXPECT_FALSE(e.baseline_kept);
}

// Changes only failed builds separate from their cause advance the baseline: building those
// commits again would fail again.
TEST(ComparedNight, UnattributedChangesMoveTheBaseline) {
  ComparedNight n = compared();
  n.changed = true;
  n.counts = counts(40, 40, 0, 40, 0);
  EXPECT_TRUE(compared_night(n).moves_baseline);
}

// A bisection that could not run (refused on one platform of two): the night is still "changed",
// but the baseline stays so that the next night bisects those changes with its own.
TEST(ComparedNight, ABisectionThatCouldNotRunKeepsTheBaseline) {
  ComparedNight n = compared();
  n.changed = true;
  n.counts = counts(20, 20, 20, 0, 1);
  n.not_bisected = {"faulty: bisect: the tree has 1 untracked file"};
  const NightEnd e = compared_night(n);
  EXPECT_EQ(e.verdict, "changed");
  EXPECT_EQ(e.exit_code, 1);
  EXPECT_FALSE(e.moves_baseline);
  EXPECT_TRUE(e.baseline_kept);
  EXPECT_EQ(e.note,
            "20 primitives changed, 1 culprit commit(s); 1 platform(s) not bisected: their "
            "changes are kept, last night's commit aaaaaaaaaaaa stays the baseline and the next "
            "night bisects them with its own");
  // No bisection ran at all: no counts to quote, only that primitives changed.
  n.counts = NightCounts{};
  EXPECT_EQ(compared_night(n).note,
            "primitives changed; 1 platform(s) not bisected: their changes are kept, last night's "
            "commit aaaaaaaaaaaa stays the baseline and the next night bisects them with its own");
}

TEST(NightFolderName, AStampThatSortsInTimeAndIsPrunable) {
  EXPECT_EQ(night_folder_name("2026-11-29T02:00:00Z"), "2026-11-29T02-00-00Z");
  const std::vector<std::string> names = {night_folder_name("2026-11-29T02:00:00Z"),
                                          night_folder_name("2026-11-30T02:00:00Z")};
  EXPECT_EQ(nights_to_prune(names, 1, names[1]), std::vector<std::string>{names[0]});
}

TEST(NightsToPrune, TheOldestBeyondKeepAndNeverTonightOrAnotherFolder) {
  const std::vector<std::string> names = {
      "2026-11-03T02-00-00Z", "2026-11-01T02-00-00Z", "notes",
      "2026-11-02T02-00-00Z", "2026-11-04T02-00-00Z", "2026-11-0XT02-00-00Z"};
  EXPECT_EQ(nights_to_prune(names, 2, "2026-11-04T02-00-00Z"),
            (std::vector<std::string>{"2026-11-01T02-00-00Z", "2026-11-02T02-00-00Z"}));
  EXPECT_EQ(nights_to_prune(names, 1, "2026-11-04T02-00-00Z").size(), 3u);
  EXPECT_TRUE(nights_to_prune(names, 0, "").empty());  // 0: keep every night
  EXPECT_TRUE(nights_to_prune(names, 4, "").empty());
  // Tonight is never removed, even when a clock set back makes it sort first.
  EXPECT_EQ(nights_to_prune(names, 1, "2026-11-01T02-00-00Z"),
            (std::vector<std::string>{"2026-11-02T02-00-00Z", "2026-11-03T02-00-00Z"}));
}

// A night with nothing new has no folder of its own: pruning keeps the newest, oldest removed
// first.
TEST(NightsToPrune, OnANightWithoutAFolderTheNewestStay) {
  const std::vector<std::string> names = {"2026-11-02T02-00-00Z", "2026-11-03T02-00-00Z",
                                          "2026-11-01T02-00-00Z"};
  EXPECT_EQ(nights_to_prune(names, 2, ""), std::vector<std::string>{"2026-11-01T02-00-00Z"});
}

}  // namespace
}  // namespace ra::triage
