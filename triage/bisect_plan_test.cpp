// The attribution plan against a brute-force answer: histories of primitive states over a line of
// commits, each checked for the changes it must name and the builds it may use.
#include "triage/bisect_plan.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <tuple>
#include <functional>

namespace ra::triage {
namespace {

// States[p][label]: what the commit at position p draws. `broken`: positions that do not build.
struct History {
  std::vector<std::map<std::string, uint64_t>> states;
  std::set<std::size_t> broken;
};

struct Outcome {
  std::vector<AttributionPlan::Change> changes;
  std::size_t builds = 0;
};

Outcome attribute(const History& h) {
  AttributionPlan plan(h.states.size() - 1);
  plan.observe(0, h.states.front());
  plan.observe(h.states.size() - 1, h.states.back());
  Outcome o;
  while (const auto p = plan.next()) {
    ++o.builds;
    if (h.broken.count(*p))
      plan.fail(*p);
    else
      plan.observe(*p, h.states[*p]);
    EXPECT_LT(o.builds, h.states.size()) << "a position was built twice";
    if (o.builds >= h.states.size()) break;
  }
  o.changes = plan.changes();
  return o;
}

// Every position where a label's state differs from the position before: what a build of every
// commit would name.
std::vector<std::pair<std::string, std::size_t>> brute_force(const History& h) {
  std::vector<std::pair<std::string, std::size_t>> out;
  for (const auto& [label, first] : h.states.front())
    for (std::size_t p = 1; p < h.states.size(); ++p)
      if (h.states[p].at(label) != h.states[p - 1].at(label)) out.push_back({label, p});
  return out;
}

std::vector<std::pair<std::string, std::size_t>> resolved(const Outcome& o) {
  std::vector<std::pair<std::string, std::size_t>> out;
  for (const auto& c : o.changes)
    if (c.resolved) out.push_back({c.label, c.to});
  return out;
}

// n positions; `at(label, p)` gives each state.
History make(std::size_t n, const std::vector<std::string>& labels,
             const std::function<uint64_t(const std::string&, std::size_t)>& at) {
  History h;
  for (std::size_t p = 0; p < n; ++p) {
    h.states.emplace_back();
    for (const std::string& l : labels) h.states.back()[l] = at(l, p);
  }
  return h;
}

TEST(AttributionPlan, OneCulpritTakesTheStepsOfABinarySearch) {
  // Why: a bisection with one culprit must stay as fast as git bisect's.
  for (std::size_t culprit : {1u, 2u, 500u, 999u, 1000u}) {
    const History h = make(1001, {"a", "b", "c"}, [&](const std::string&, std::size_t p) {
      return p >= culprit ? 2u : 1u;
    });
    const Outcome o = attribute(h);
    EXPECT_EQ(resolved(o), brute_force(h)) << culprit;
    EXPECT_LE(o.builds, std::size_t(std::ceil(std::log2(1000.0)))) << culprit;
  }
}

TEST(AttributionPlan, TwoCulpritsOfDisjointPrimitivesAreBothNamed) {
  // Why: one selection, two commits; each primitive gets its own commit.
  const History h = make(301, {"even", "odd"}, [](const std::string& l, std::size_t p) {
    return l == "even" ? (p >= 37 ? 5u : 1u) : (p >= 250 ? 9u : 1u);
  });
  const Outcome o = attribute(h);
  EXPECT_EQ(resolved(o), (std::vector<std::pair<std::string, std::size_t>>{{"even", 37}, {"odd", 250}}));
  EXPECT_LE(o.builds, 2 * 9u);
}

TEST(AttributionPlan, APrimitiveChangedTwiceHasBothChangesNamed) {
  // Why: good -> state 2 -> bad is two commits, not "neither".
  const History h = make(129, {"p"}, [](const std::string&, std::size_t p) {
    return p >= 100 ? 3u : p >= 20 ? 2u : 1u;
  });
  const Outcome o = attribute(h);
  EXPECT_EQ(resolved(o), brute_force(h));
  ASSERT_EQ(o.changes.size(), 2u);
  EXPECT_EQ(o.changes[0].hash_before, 1u);
  EXPECT_EQ(o.changes[0].hash_after, 2u);
  EXPECT_EQ(o.changes[1].hash_after, 3u);
}

TEST(AttributionPlan, ABuildThatFailsNextToTheChangeLeavesCandidates) {
  // Why: the commit cannot be named when its only neighbour does not build; both are said.
  History h = make(17, {"p", "q"}, [](const std::string& l, std::size_t p) {
    return l == "p" ? (p >= 9 ? 2u : 1u) : (p >= 4 ? 2u : 1u);
  });
  h.broken = {8};
  const Outcome o = attribute(h);
  ASSERT_EQ(o.changes.size(), 2u);
  for (const auto& c : o.changes) {
    if (c.label == "q") {
      EXPECT_TRUE(c.resolved);
      EXPECT_EQ(c.to, 4u);
    } else {
      EXPECT_FALSE(c.resolved);
      EXPECT_EQ(c.candidates, (std::vector<std::size_t>{8, 9}));
    }
  }
}

TEST(AttributionPlan, AChangeUndoneInsideTheRangeIsSeenOnlyWhereABuildFallsInIt) {
  // Why: the ends of the range are alike, so nothing asks for a build inside (the documented
  // limit); a change undone while another primitive is being bisected is named in full.
  const History hidden = make(65, {"p"}, [](const std::string&, std::size_t p) {
    return p >= 10 && p < 20 ? 2u : 1u;
  });
  EXPECT_TRUE(attribute(hidden).changes.empty());
  const History seen = make(65, {"p", "q"}, [](const std::string& l, std::size_t p) {
    if (l == "q") return p >= 40 ? 2u : 1u;
    return p >= 20 && p < 50 ? 2u : 1u;  // the build at 32 falls inside
  });
  const Outcome o = attribute(seen);
  EXPECT_EQ(resolved(o), brute_force(seen));
}

TEST(AttributionPlan, RandomHistoriesMatchABuildOfEveryCommit) {
  // Why: the plan's answer must be what building every commit would say, for every primitive
  // whose changes are visible from the built positions; histories with few changes, as Mesa's.
  uint64_t state = 12345;
  const auto rnd = [&] {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return state >> 33;
  };
  for (int trial = 0; trial < 200; ++trial) {
    const std::size_t n = 2 + rnd() % 200;
    std::vector<std::vector<std::size_t>> change_at(6);
    for (auto& c : change_at)
      for (int k = int(rnd() % 3); k > 0; --k) c.push_back(1 + rnd() % (n - 1));
    const History h = make(n, {"0", "1", "2", "3", "4", "5"}, [&](const std::string& l, std::size_t p) {
      uint64_t s = 0;  // every change makes a new state (never undone)
      for (std::size_t c : change_at[std::stoul(l)]) s += p >= c ? c * 1000 + 1 : 0;
      return s;
    });
    const Outcome o = attribute(h);
    EXPECT_EQ(resolved(o), brute_force(h)) << "trial " << trial;
  }
}

// Rounds of k builds at once: every position of a round built (in the order given by `shuffle`),
// except those another result of the same round made needless (cancelled).
struct RoundsOutcome {
  std::vector<AttributionPlan::Change> changes;
  std::size_t rounds = 0, builds = 0, cancelled = 0;
};

RoundsOutcome attribute_in_rounds(const History& h, std::size_t k, uint64_t shuffle = 0) {
  AttributionPlan plan(h.states.size() - 1);
  plan.observe(0, h.states.front());
  plan.observe(h.states.size() - 1, h.states.back());
  RoundsOutcome o;
  std::set<std::size_t> built;
  for (std::vector<std::size_t> round = plan.next_k(k); !round.empty(); round = plan.next_k(k)) {
    ++o.rounds;
    EXPECT_LE(round.size(), k);
    if (shuffle) std::rotate(round.begin(), round.begin() + shuffle % round.size(), round.end());
    for (std::size_t p : round) {
      EXPECT_TRUE(built.insert(p).second) << "position " << p << " chosen twice";
      if (!plan.needed(p)) {
        ++o.cancelled;
        continue;
      }
      ++o.builds;
      if (h.broken.count(p))
        plan.fail(p);
      else
        plan.observe(p, h.states[p]);
    }
    if (o.rounds > h.states.size()) break;
  }
  o.changes = plan.changes();
  return o;
}

TEST(AttributionPlanK, OneCulpritInNCommitsTakesLogKPlusOneRounds) {
  // Why: K builds a round must cut the rounds from log2 n to log_(K+1) n (the point of --ways).
  for (const auto& [k, n, rounds] : std::vector<std::tuple<std::size_t, std::size_t, std::size_t>>{
           {1, 64, 6}, {3, 64, 3}, {7, 512, 3}, {15, 4096, 3}, {3, 1000, 5}}) {
    for (std::size_t culprit : {std::size_t(1), n / 3, n / 2 + 1, n - 1, n}) {
      const History h = make(n + 1, {"a", "b"}, [&](const std::string&, std::size_t p) {
        return p >= culprit ? 2u : 1u;
      });
      const RoundsOutcome o = attribute_in_rounds(h, k);
      EXPECT_EQ(resolved(Outcome{o.changes, 0}), brute_force(h)) << k << " " << culprit;
      EXPECT_LE(o.rounds, rounds) << "k " << k << ", n " << n << ", culprit " << culprit;
    }
  }
}

TEST(AttributionPlanK, OneGapGetsEvenlySpacedBuilds) {
  // Why: with one culprit the K builds cut its range into K + 1 equal parts.
  AttributionPlan plan(64);
  plan.observe(0, {{"p", 1}});
  plan.observe(64, {{"p", 2}});
  EXPECT_EQ(plan.next_k(3), (std::vector<std::size_t>{16, 32, 48}));
  EXPECT_EQ(plan.next_k(1), (std::vector<std::size_t>{32}));
  EXPECT_EQ(plan.next_k(2), (std::vector<std::size_t>{21, 42}));
  EXPECT_EQ(plan.rounds_to_go(3), 3u);
  EXPECT_EQ(plan.rounds_to_go(1), 6u);
  EXPECT_EQ(plan.unresolved(), 1u);
}

TEST(AttributionPlanK, EveryGapGetsABuildTheMostChangesFirst) {
  // Why: "split the most unresolved changes": one build splits every change of its gap, so a
  // round covers the gaps in order of their changes before it splits any gap twice.
  AttributionPlan plan(64);
  plan.observe(0, {{"a", 1}, {"b", 1}, {"c", 1}, {"d", 1}});
  plan.observe(32, {{"a", 2}, {"b", 2}, {"c", 2}, {"d", 1}});
  plan.observe(64, {{"a", 2}, {"b", 2}, {"c", 2}, {"d", 2}});
  EXPECT_EQ(plan.next_k(1), (std::vector<std::size_t>{16}));
  EXPECT_EQ(plan.next_k(2), (std::vector<std::size_t>{16, 48}));
  EXPECT_EQ(plan.next_k(4), (std::vector<std::size_t>{10, 21, 42, 53}));
  EXPECT_EQ(plan.unresolved(), 4u);
}

TEST(AttributionPlanK, AGapOfFewChangesIsNotLeftToTheLastRounds) {
  // Why: rounds, not builds, are the wall time: a gap of one change beside a gap of a thousand
  // gets its share of every round, so both searches end together.
  std::map<std::string, uint64_t> good, mid, bad;
  for (int i = 0; i < 1000; ++i) {
    const std::string l = "many" + std::to_string(i);
    good[l] = 1, mid[l] = 1, bad[l] = 2;
  }
  good["one"] = 1, mid["one"] = 2, bad["one"] = 2;
  AttributionPlan plan(2000);
  plan.observe(0, good);
  plan.observe(1000, mid);
  plan.observe(2000, bad);
  const std::vector<std::size_t> round = plan.next_k(6);
  EXPECT_EQ(std::count_if(round.begin(), round.end(), [](std::size_t p) { return p < 1000; }), 3);
}

TEST(AttributionPlanK, FailedAndBuiltPositionsAreNeverChosenAndFewOpenGiveFewBuilds) {
  // Why: a round must not rebuild a commit nor retry one that failed; a gap of two open commits
  // takes two builds however many ways are asked for.
  AttributionPlan plan(5);
  plan.observe(0, {{"p", 1}});
  plan.observe(5, {{"p", 2}});
  plan.fail(2);
  plan.fail(3);
  EXPECT_EQ(plan.next_k(7), (std::vector<std::size_t>{1, 4}));
  plan.observe(1, {{"p", 1}});
  EXPECT_FALSE(plan.needed(1));
  EXPECT_TRUE(plan.needed(4));
  plan.observe(4, {{"p", 2}});
  EXPECT_TRUE(plan.next_k(3).empty());
  EXPECT_FALSE(plan.needed(4));
}

TEST(AttributionPlanK, AResultOfTheRoundMakesTheOthersOfItsRangeNeedless) {
  // Why: the build at 16 drawing bad puts the culprit before it; 32 and 48 are cancelled.
  AttributionPlan plan(64);
  plan.observe(0, {{"p", 1}});
  plan.observe(64, {{"p", 2}});
  plan.observe(16, {{"p", 2}});
  EXPECT_FALSE(plan.needed(32));
  EXPECT_FALSE(plan.needed(48));
  EXPECT_TRUE(plan.needed(8));
}

TEST(AttributionPlanK, RandomHistoriesInRoundsMatchABuildOfEveryCommit) {
  // Why: whatever K and whatever order a round's results come back in (cancelling what another
  // result made needless), the answer is a build of every commit's, failed builds included.
  uint64_t state = 777;
  const auto rnd = [&] {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return state >> 33;
  };
  for (int trial = 0; trial < 300; ++trial) {
    const std::size_t n = 2 + rnd() % 300, k = 1 + rnd() % 16;
    std::vector<std::vector<std::size_t>> change_at(5);
    for (auto& c : change_at)
      for (int i = int(rnd() % 3); i > 0; --i) c.push_back(1 + rnd() % (n - 1));
    History h = make(n, {"0", "1", "2", "3", "4"}, [&](const std::string& l, std::size_t p) {
      uint64_t s = 0;
      for (std::size_t c : change_at[std::stoul(l)]) s += p >= c ? c * 1000 + 1 : 0;
      return s;
    });
    if (trial % 3 == 0 && n > 4) h.broken = {1 + rnd() % (n - 2)};
    const RoundsOutcome o = attribute_in_rounds(h, k, rnd());
    // A change next to a failed build is left with candidates; the rest are named.
    std::vector<std::pair<std::string, std::size_t>> expected;
    for (const auto& [label, p] : brute_force(h))
      if (!h.broken.count(p) && !h.broken.count(p - 1)) expected.push_back({label, p});
    std::vector<std::pair<std::string, std::size_t>> named;
    for (const auto& c : o.changes)
      if (c.resolved && !h.broken.count(c.to - 1)) named.push_back({c.label, c.to});
    if (h.broken.empty()) {
      EXPECT_EQ(resolved(Outcome{o.changes, 0}), brute_force(h)) << "trial " << trial;
    } else {
      for (const auto& e : expected)
        EXPECT_NE(std::find(named.begin(), named.end(), e), named.end())
            << "trial " << trial << ": " << e.first << " at " << e.second;
    }
  }
}

}  // namespace
}  // namespace ra::triage
