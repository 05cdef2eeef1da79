#include "triage/watch.h"

#include <gtest/gtest.h>

namespace ra::triage {
namespace {

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

}  // namespace
}  // namespace ra::triage
