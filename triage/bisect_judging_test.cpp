// Judging a bisection's drawings: which primitives the ends tell apart, a step's drawing in
// words, and the plan's changes turned into culprits (named with git in a small history made
// here) and unattributed changes.
#include "triage/bisect_judging.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <vector>

#include "builds/git_command.h"

namespace fs = std::filesystem;

namespace ra::triage {
namespace {

BisectPrimitive line(uint64_t index) {
  BisectPrimitive p;
  p.kind = geometry::Kind::kLine;
  p.view = 1;
  p.index = index;
  return p;
}

// Lines 1-4 of view 1: 1 and 3 drawn alike by both ends, 2 and 4 differently.
struct Ends {
  std::vector<BisectPrimitive> selection = {line(1), line(2), line(3), line(4)};
  Drawing good, bad;
  Ends() {
    for (const BisectPrimitive& p : selection) {
      good.hashes[p.label()] = 100 + p.index;
      bad.hashes[p.label()] = p.index % 2 ? 100 + p.index : 200 + p.index;
    }
  }
};

TEST(BisectJudging, OnlyWhatTheEndsDrawDifferentlyIsJudged) {
  const Ends e;
  std::vector<BisectPrimitive> judged;
  std::vector<std::string> dropped = {"left from before"};
  split_by_ends(e.selection, e.good, e.bad, judged, dropped);
  ASSERT_EQ(judged.size(), 2u);
  EXPECT_EQ(judged[0].label(), "line 2 of view 1");  // in selection order
  EXPECT_EQ(judged[1].label(), "line 4 of view 1");
  EXPECT_EQ(dropped, (std::vector<std::string>{"line 1 of view 1", "line 3 of view 1"}));
}

// A step that drew one judged primitive as the good end, none as the bad, one as neither, and
// missed one: the missing one is not counted at all.
TEST(BisectJudging, AStepIsSummedUpAgainstTheEnds) {
  const Ends e;
  const std::vector<BisectPrimitive> judged = {line(2), line(4), line(6)};
  Drawing good = e.good, bad = e.bad;
  good.hashes["line 6 of view 1"] = 106;
  bad.hashes["line 6 of view 1"] = 206;
  Drawing step;
  step.hashes["line 2 of view 1"] = 102;  // as the good end
  step.hashes["line 4 of view 1"] = 999;  // as neither
  step.hashes["line 1 of view 1"] = 101;  // not judged: not counted
  EXPECT_EQ(drawing_summary(judged, good, bad, step),
            "1 like the good ref, 0 like the bad ref, 1 like neither");
  step.hashes["line 6 of view 1"] = 206;
  EXPECT_EQ(drawing_summary(judged, good, bad, step),
            "1 like the good ref, 1 like the bad ref, 1 like neither");
  const auto hashes = judged_hashes(judged, step);
  EXPECT_EQ(hashes, (std::map<std::string, uint64_t>{{"line 2 of view 1", 102},
                                                     {"line 4 of view 1", 999},
                                                     {"line 6 of view 1", 206}}));
}

// A history of `n` commits in a fresh repository, oldest first: "c0" ... "c{n-1}".
std::vector<std::string> make_history(const std::string& dir, int n) {
  using builds::git;
  fs::create_directories(dir);
  if (!git(dir, {"init", "-q"}).ok) return {};
  std::vector<std::string> commits;
  for (int i = 0; i < n; ++i) {
    const std::string msg = "c" + std::to_string(i);
    if (!git(dir, {"-c", "user.name=t", "-c", "user.email=t@example.org", "commit", "-q",
                   "--allow-empty", "-m", msg})
             .ok)
      return {};
    commits.push_back(git(dir, {"rev-parse", "HEAD"}).out);
  }
  return commits;
}

// Line 2 changed at position 2 (resolved); line 4 changed somewhere in 2-4 where position 3's build
// failed (unattributed, with candidates 3 and 4); a drawing time's label is not a primitive.
TEST(BisectJudging, CulpritsAndUnattributedChangesFromThePlan) {
  const std::string dir =
      (fs::temp_directory_path() / ("bisect-judging-" + std::to_string(::getpid()))).string();
  fs::remove_all(dir);
  const std::vector<std::string> history = make_history(dir, 5);
  if (history.empty()) GTEST_SKIP() << "git cannot make a repository in " << dir;
  const std::vector<BisectPrimitive> judged = {line(4), line(2)};
  const std::string l2 = line(2).label(), l4 = line(4).label();

  BisectResult r;
  r.good.drawing.hashes = {{l2, 1}, {l4, 1}, {"speed group", 1}};
  r.good.drawing.pixels = {{l2, 10}, {l4, 40}};
  r.bad.drawing.hashes = {{l2, 2}, {l4, 2}, {"speed group", 2}};
  r.bad.drawing.pixels = {{l2, 12}, {l4, 44}};
  BisectStep one;
  one.position = 1;
  one.drawing.hashes = {{l2, 1}, {l4, 1}, {"speed group", 1}};
  one.drawing.pixels = {{l2, 10}, {l4, 40}};
  BisectStep two = one;
  two.position = 2;
  two.drawing.hashes = {{l2, 2}, {l4, 1}, {"speed group", 2}};
  two.drawing.pixels = {{l2, 11}, {l4, 40}};
  BisectStep three;
  three.position = 3;
  three.error = "build failed: no compiler";
  r.steps = {one, two, three};

  AttributionPlan plan(4);
  plan.observe(0, r.good.drawing.hashes);
  plan.observe(4, r.bad.drawing.hashes);
  plan.observe(1, one.drawing.hashes);
  plan.observe(2, two.drawing.hashes);
  plan.fail(3);

  std::vector<std::string> said;
  collect_culprits(plan, history, judged, dir, r, [&](const std::string& s) { said.push_back(s); });

  ASSERT_EQ(r.culprits.size(), 1u);  // the speed group's change at 2 is not a primitive's
  const Culprit& k = r.culprits[0];
  EXPECT_EQ(k.commit, history[2]);
  EXPECT_EQ(k.previous, history[1]);
  EXPECT_EQ(k.subject, "c2");
  EXPECT_FALSE(k.merge);
  EXPECT_FALSE(k.date.empty());
  EXPECT_EQ(k.primitives, (std::vector<std::string>{l2}));
  EXPECT_EQ(k.pixels.at(l2), (std::pair<int64_t, int64_t>{10, 11}));

  ASSERT_EQ(r.unattributed.size(), 1u);
  const Unattributed& u = r.unattributed[0];
  EXPECT_EQ(u.label, l4);
  EXPECT_EQ(u.from, history[2]);
  EXPECT_EQ(u.to, history[4]);
  EXPECT_EQ(u.candidates, (std::vector<std::string>{history[3], history[4]}));

  ASSERT_EQ(said.size(), 2u);
  EXPECT_EQ(said[0], "named " + history[2].substr(0, 12) + " c2: 1 primitives");
  EXPECT_EQ(said[1].rfind("1 changes stay unattributed", 0), 0u) << said[1];
  fs::remove_all(dir);
}

}  // namespace
}  // namespace ra::triage
