// The upgrade report's counts on hand-built comparisons: a small case whose counts are written out,
// and random ones against a brute force that counts each stratum on its own.
#include "audit/change_counts.h"

#include <gtest/gtest.h>

#include <random>

namespace ra::audit {
namespace {

using metrics::Conformance;
using metrics::Visibility;

ChangedPrimitive changed(geometry::Kind kind, int group, Visibility vb, Conformance cb,
                         Visibility va, Conformance ca, Recheck recheck = Recheck::kNotRerendered) {
  ChangedPrimitive c;
  c.kind = kind, c.view_group = group, c.view = group + 1, c.recheck = recheck;
  c.before.visibility = vb, c.before.conformance = cb;
  c.after.visibility = va, c.after.conformance = ca;
  return c;
}

// Why: the nesting of "not drawn" and "new violation" is what page 1 says; a flake must not count;
// a group that compared nothing has no row.
TEST(ChangeCounts, CountsASmallCaseByHand) {
  const auto tv = Visibility::kTrueVisible, fi = Visibility::kFalseInvisible;
  const auto ex = Conformance::kExact, vi = Conformance::kViolation,
             ws = Conformance::kWithinSpec, nc = Conformance::kNotCompared;
  const auto line = geometry::Kind::kLine;
  PrimitiveComparison cmp;
  cmp.views = {{0, line, 1, 0, 10, 5, 0, 0}, {0, line, 2, 1, 8, 1, 0, 0},
               {0, line, 3, 2, 0, 0, 0, 4}};
  cmp.changed = {
      changed(line, 0, tv, ex, fi, vi),                      // not drawn, a new violation
      changed(line, 0, tv, nc, fi, nc),                      // not drawn, nothing judged
      changed(line, 0, tv, ex, tv, vi),                      // a new violation, drawn
      changed(line, 0, fi, vi, tv, ex),                      // newly drawn, fixed
      changed(line, 0, tv, ex, tv, ws),                      // allowed
      changed(line, 1, tv, ex, tv, vi, Recheck::kFlake),     // a flake: left out
  };
  const std::vector<ChangeCounts> counts = count_changes(cmp);
  ASSERT_EQ(counts.size(), 2u);
  const ChangeCounts& a = counts[0];
  EXPECT_EQ(a.view_group, 0);
  EXPECT_EQ(a.compared, 10u);
  EXPECT_EQ(a.changed, 5u);
  EXPECT_EQ(a.not_drawn, 2u);
  EXPECT_EQ(a.newly_drawn, 1u);
  EXPECT_EQ(a.new_violations, 2u);
  EXPECT_EQ(a.not_drawn_violations, 1u);
  EXPECT_EQ(a.fixed_violations, 1u);
  EXPECT_EQ(a.allowed, 1u);
  EXPECT_EQ(counts[1].view_group, 1);
  EXPECT_EQ(counts[1].compared, 8u);
  EXPECT_EQ(counts[1].changed, 0u);
  EXPECT_EQ(change_category(cmp.changed[1]), ChangeCategory::kNotDrawn);
  EXPECT_EQ(change_category(cmp.changed[2]), ChangeCategory::kNewViolation);
  EXPECT_EQ(change_category(cmp.changed[3]), ChangeCategory::kFixed);
  EXPECT_EQ(change_category(cmp.changed[4]), ChangeCategory::kAllowed);
}

// Why: the counting runs over a map of strata; a brute force over each stratum's primitives, with
// each rule written out as the report's definition states it, must give the same numbers.
TEST(ChangeCounts, MatchesABruteForceOnRandomComparisons) {
  std::mt19937 rng(11);
  const Visibility vis[] = {Visibility::kTrueVisible, Visibility::kFalseInvisible,
                            Visibility::kTrueInvisible, Visibility::kFalseVisible};
  const Conformance conf[] = {Conformance::kNotCompared, Conformance::kExact,
                              Conformance::kSnapped, Conformance::kWithinSpec,
                              Conformance::kViolation};
  const auto pick = [&](int n) { return int(rng() % unsigned(n)); };
  for (int trial = 0; trial < 50; ++trial) {
    PrimitiveComparison cmp;
    for (std::size_t pair = 0; pair < 2; ++pair)
      for (int k = 0; k < 3; ++k)
        for (int view = 1; view <= 4; ++view)
          cmp.views.push_back({pair, geometry::Kind(k), view, (view - 1) / 2,
                               uint64_t(pick(3) ? 20 : 0), 0, 0, 0});
    for (const ViewCounts& v : cmp.views)
      for (uint64_t i = 0; i < v.compared; ++i)
        if (pick(3) == 0) {
          ChangedPrimitive c = changed(v.kind, v.view_group, vis[pick(4)], conf[pick(5)],
                                       vis[pick(4)], conf[pick(5)],
                                       pick(8) == 0 ? Recheck::kFlake : Recheck::kStillDifferent);
          c.pair = v.pair, c.view = v.view, c.index = i;
          cmp.changed.push_back(c);
        }
    const std::vector<ChangeCounts> counts = count_changes(cmp);
    std::size_t rows = 0;
    for (std::size_t pair = 0; pair < 2; ++pair)
      for (int k = 0; k < 3; ++k)
        for (int group = 0; group < 2; ++group) {
          ChangeCounts want;
          for (const ViewCounts& v : cmp.views)
            if (v.pair == pair && int(v.kind) == k && v.view_group == group)
              want.compared += v.compared;
          if (want.compared == 0) continue;
          for (const ChangedPrimitive& c : cmp.changed) {
            if (c.pair != pair || int(c.kind) != k || c.view_group != group ||
                c.recheck == Recheck::kFlake)
              continue;
            const auto [vb, va] = std::pair(c.before.visibility, c.after.visibility);
            const auto [cb, ca] = std::pair(c.before.conformance, c.after.conformance);
            const bool gone = vb == Visibility::kTrueVisible && va == Visibility::kFalseInvisible;
            const bool breaks = ca == Conformance::kViolation && cb != Conformance::kViolation;
            const bool fixes = cb == Conformance::kViolation && ca != Conformance::kViolation;
            const bool ok_before = cb != Conformance::kNotCompared && cb != Conformance::kViolation;
            const bool ok_after = ca != Conformance::kNotCompared && ca != Conformance::kViolation;
            ++want.changed;
            want.not_drawn += gone;
            want.newly_drawn += vb == Visibility::kFalseInvisible && va == Visibility::kTrueVisible;
            want.new_violations += breaks;
            want.not_drawn_violations += gone && breaks;
            want.fixed_violations += !gone && fixes;
            want.allowed += !gone && ok_before && ok_after;
          }
          ASSERT_LT(rows, counts.size());
          const ChangeCounts& got = counts[rows++];
          ASSERT_EQ(std::tuple(got.pair, int(got.kind), got.view_group),
                    std::tuple(pair, k, group));
          EXPECT_EQ(got.compared, want.compared);
          EXPECT_EQ(got.changed, want.changed);
          EXPECT_EQ(got.not_drawn, want.not_drawn);
          EXPECT_EQ(got.newly_drawn, want.newly_drawn);
          EXPECT_EQ(got.new_violations, want.new_violations);
          EXPECT_EQ(got.not_drawn_violations, want.not_drawn_violations);
          EXPECT_EQ(got.fixed_violations, want.fixed_violations);
          EXPECT_EQ(got.allowed, want.allowed);
        }
    EXPECT_EQ(rows, counts.size());
  }
}

}  // namespace
}  // namespace ra::audit
