#include "triage/watch.h"

#include <gtest/gtest.h>

namespace ra::triage {
namespace {

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

// A script reads "first bad commit:" lines as culprits: a bisection that could not run, or
// changes no commit was named for, are said under words of their own.
TEST(NightLines, OnlyNamedCommitsAreFirstBadCommits) {
  WatchNight n;
  n.verdict = "changed";
  n.note = "primitives changed";
  n.commit = std::string(40, 'a');
  n.dir = "/state/nights/N";
  n.culprits = {std::string(40, 'b') + " c2: x (20 primitives of faulty)"};
  n.unattributed = {"40 changes of egl-llvmpipe: only commits that failed to build lie between"};
  n.not_bisected = {"faulty: bisect: the tree has 1 untracked file"};
  const std::vector<std::string> lines = night_lines(n);
  ASSERT_EQ(lines.size(), 5u);
  EXPECT_EQ(lines[0], "night: changed: primitives changed (aaaaaaaaaaaa)");
  EXPECT_EQ(lines[1], "details: /state/nights/N/night.md");
  EXPECT_EQ(lines[2], "first bad commit: " + n.culprits[0]);
  EXPECT_EQ(lines[3], "unattributed: " + n.unattributed[0]);
  EXPECT_EQ(lines[4], "not bisected: " + n.not_bisected[0]);
}

// A night that could not see upstream has no commit of its own: no empty "()".
TEST(NightLines, ANightWithoutACommitSaysNone) {
  WatchNight n;
  n.verdict = "fetch failed";
  n.note = "git fetch failed";
  EXPECT_EQ(night_lines(n), std::vector<std::string>{"night: fetch failed: git fetch failed"});
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


TEST(NightsToPrune, TheOldestBeyondKeepAndNeverTonightOrAnotherFolder) {
  const std::vector<std::string> names = {"2026-11-03T02-00-00Z", "2026-11-01T02-00-00Z",
                                          "notes", "2026-11-02T02-00-00Z",
                                          "2026-11-04T02-00-00Z", "2026-11-0XT02-00-00Z"};
  EXPECT_EQ(nights_to_prune(names, 2, "2026-11-04T02-00-00Z"),
            (std::vector<std::string>{"2026-11-01T02-00-00Z", "2026-11-02T02-00-00Z"}));
  EXPECT_EQ(nights_to_prune(names, 1, "2026-11-04T02-00-00Z").size(), 3u);
  EXPECT_TRUE(nights_to_prune(names, 0, "").empty());  // 0: keep every night
  EXPECT_TRUE(nights_to_prune(names, 4, "").empty());
  // Tonight is never removed, even when a clock set back makes it sort first.
  EXPECT_EQ(nights_to_prune(names, 1, "2026-11-01T02-00-00Z"),
            (std::vector<std::string>{"2026-11-02T02-00-00Z", "2026-11-03T02-00-00Z"}));
}

}  // namespace
}  // namespace ra::triage
