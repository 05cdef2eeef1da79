// Table 6 and c over repeated runs (repeated_runs.h) on hand-made per-run numbers (the experiment
// key that asks for the runs, study_runs, is tested with the others in timing_experiment_test.cpp).
#include "timing/repeated_runs.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace ra::timing {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Student's t quantiles by hand: with 1 degree of freedom t is Cauchy, t_0.975 = tan(0.475 pi);
// with 2, F(t) = 1/2 + t / (2 sqrt(2 + t^2)), so t_0.975^2 = 2 * 0.95^2 / (1 - 0.95^2).
const double kT1 = std::tan(0.475 * M_PI);               // 12.7062...
const double kT2 = std::sqrt(2 * 0.9025 / (1 - 0.9025));  // 4.30265...

TEST(RepeatedRuns, SpreadOfThreeRuns) {
  // 2, 4, 6: mean 4, SD sqrt((4 + 0 + 4) / 2) = 2, interval 4 -+ t2 * 2 / sqrt(3)
  const RunSpread s = spread_over_runs({2, 4, 6});
  EXPECT_EQ(s.n, 3u);
  EXPECT_DOUBLE_EQ(s.mean, 4);
  EXPECT_DOUBLE_EQ(s.sd, 2);
  EXPECT_EQ(s.min, 2);
  EXPECT_EQ(s.max, 6);
  EXPECT_NEAR(kT2, 4.302652729749464, 1e-12);
  EXPECT_NEAR(s.ci_low, 4 - kT2 * 2 / std::sqrt(3.0), 1e-9);
  EXPECT_NEAR(s.ci_high, 4 + kT2 * 2 / std::sqrt(3.0), 1e-9);
  EXPECT_EQ(s.values, (std::vector<double>{2, 4, 6}));
}

TEST(RepeatedRuns, SpreadOfTwoRunsOneRunAndNone) {
  // two runs: SD = |a - b| / sqrt 2, half width t1 * SD / sqrt 2 = t1 |a - b| / 2
  const RunSpread two = spread_over_runs({1.5, 2.5});
  EXPECT_DOUBLE_EQ(two.mean, 2);
  EXPECT_NEAR(two.sd, 1 / std::sqrt(2.0), 1e-15);
  EXPECT_NEAR(two.ci_low, 2 - kT1 * 0.5, 1e-9);
  EXPECT_NEAR(two.ci_high, 2 + kT1 * 0.5, 1e-9);
  // a 90% interval is narrower: t_0.95 with 1 df = tan(0.45 pi)
  const RunSpread ninety = spread_over_runs({1.5, 2.5}, 0.90);
  EXPECT_NEAR(ninety.ci_high, 2 + std::tan(0.45 * M_PI) * 0.5, 1e-9);
  // a run that gave no number is left out of n, kept in values
  const RunSpread one = spread_over_runs({kNaN, 3});
  EXPECT_EQ(one.n, 1u);
  EXPECT_EQ(one.values.size(), 2u);
  EXPECT_DOUBLE_EQ(one.mean, 3);
  EXPECT_EQ(one.min, 3);
  EXPECT_EQ(one.max, 3);
  EXPECT_TRUE(std::isnan(one.sd));  // no spread from one run
  EXPECT_TRUE(std::isnan(one.ci_low));
  const RunSpread none = spread_over_runs({});
  EXPECT_EQ(none.n, 0u);
  EXPECT_TRUE(std::isnan(none.mean));
  EXPECT_THROW(spread_over_runs({1, 2}, 1.0), std::invalid_argument);
}

TEST(RepeatedRuns, RankingPutsMissingLastAndKeepsTiesInOrder) {
  const std::vector<std::string> methods{"h1", "h2", "h3", "h4", "pos"};
  EXPECT_EQ(rank_methods({{"h1", 3}, {"h2", kNaN}, {"h3", 1}, {"h4", 3}}, methods),
            (std::vector<std::string>{"h3", "h1", "h4", "h2", "pos"}));
  EXPECT_TRUE(is_paper_method("h3"));
  EXPECT_TRUE(is_paper_method("pos"));
  EXPECT_FALSE(is_paper_method("h3+b"));
}

// Three successful runs and a failed one of one platform, two scenes; every number by hand.
TEST(RepeatedRuns, AggregatesTable6WinsAndC) {
  const std::vector<std::string> methods{"h1", "h4", "h4+b", "pos"};
  std::vector<RunOutcome> runs(4);
  runs[0] = {true, {{"city", {{"h1", 10}, {"h4", 4}, {"h4+b", 2}, {"pos", 3}}},
                    {"forest", {{"h1", 1}, {"h4", 2}, {"h4+b", 3}, {"pos", kNaN}}}},
             1000, 10};
  runs[1] = {false, {}, 0, 1};  // failed: counted, left out
  runs[2] = {true, {{"city", {{"h1", 12}, {"h4", 6}, {"h4+b", 5}, {"pos", 1}}},
                    {"forest", {{"h1", 5}, {"h4", 2}, {"h4+b", 3}, {"pos", 4}}}},
             1500, 11};
  runs[3] = {true, {{"city", {{"h1", 14}, {"h4", 2}, {"h4+b", 3}, {"pos", 8}}},
                    {"forest", {{"h1", 5}, {"h4", 2}, {"h4+b", 3}, {"pos", 9}}}},
             2000, 12};
  const RepeatedPlatform p = aggregate_runs("osmesa-llvmpipe", methods, runs);
  EXPECT_EQ(p.platform, "osmesa-llvmpipe");
  EXPECT_EQ(p.runs, 3);
  EXPECT_EQ(p.failed, 1);
  EXPECT_EQ(p.wall_s, (std::vector<double>{10, 1, 11, 12}));
  EXPECT_EQ(p.methods, methods);

  // c: 1000, 1500, 2000 us -> mean 1500, SD 500, interval 1500 -+ t2 * 500 / sqrt 3
  EXPECT_EQ(p.c_us.n, 3u);
  EXPECT_DOUBLE_EQ(p.c_us.mean, 1500);
  EXPECT_DOUBLE_EQ(p.c_us.sd, 500);
  EXPECT_EQ(p.c_us.min, 1000);
  EXPECT_EQ(p.c_us.max, 2000);
  EXPECT_NEAR(p.c_us.ci_high, 1500 + kT2 * 500 / std::sqrt(3.0), 1e-9);

  // city: h1 10, 12, 14 (mean 12, SD 2); pos 3, 1, 8 (mean 4, SD sqrt(13))
  const RunSpread& h1 = p.table6_ms2.at("city").at("h1");
  EXPECT_DOUBLE_EQ(h1.mean, 12);
  EXPECT_DOUBLE_EQ(h1.sd, 2);
  EXPECT_NEAR(h1.ci_low, 12 - kT2 * 2 / std::sqrt(3.0), 1e-9);
  const RunSpread& pos = p.table6_ms2.at("city").at("pos");
  EXPECT_DOUBLE_EQ(pos.mean, 4);
  EXPECT_NEAR(pos.sd, std::sqrt(13.0), 1e-12);
  EXPECT_EQ(pos.min, 1);
  EXPECT_EQ(pos.max, 8);
  // rankings: h4+b < pos < h4 < h1; pos < h4+b < h4 < h1; h4 < h4+b < pos < h1
  const SceneRanking& city = p.ranking.at("city");
  ASSERT_EQ(city.per_run.size(), 3u);
  EXPECT_EQ(city.per_run[0], (std::vector<std::string>{"h4+b", "pos", "h4", "h1"}));
  EXPECT_EQ(city.per_run[1], (std::vector<std::string>{"pos", "h4+b", "h4", "h1"}));
  EXPECT_EQ(city.per_run[2], (std::vector<std::string>{"h4", "h4+b", "pos", "h1"}));
  EXPECT_EQ(city.wins, (std::map<std::string, int>{{"h1", 0}, {"h4", 1}, {"h4+b", 1}, {"pos", 1}}));
  // among the paper's forms (h1, h4, pos): pos, pos, h4
  EXPECT_EQ(city.paper_wins, (std::map<std::string, int>{{"h1", 0}, {"h4", 1}, {"pos", 2}}));
  EXPECT_EQ(city.runs_without_winner, 0);

  // forest: pos missing in run 1 (n = 2, ranked last there); h1 wins run 1, h4 runs 2 and 3
  const RunSpread& fpos = p.table6_ms2.at("forest").at("pos");
  EXPECT_EQ(fpos.n, 2u);
  EXPECT_DOUBLE_EQ(fpos.mean, 6.5);
  EXPECT_NEAR(fpos.ci_high, 6.5 + kT1 * 2.5, 1e-9);
  const SceneRanking& forest = p.ranking.at("forest");
  EXPECT_EQ(forest.per_run[0].back(), "pos");
  EXPECT_EQ(forest.wins, (std::map<std::string, int>{{"h1", 1}, {"h4", 2}, {"h4+b", 0}, {"pos", 0}}));
  int total = 0;
  for (const auto& [m, k] : forest.wins) total += k;
  EXPECT_EQ(total, p.runs);  // every run has exactly one winner
}

}  // namespace
}  // namespace ra::timing
