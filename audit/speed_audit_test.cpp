// The speed verdict as a pure function of an interval, and the comparison's statistics against
// SciPy 1.10 (Debian 12's python3-scipy) on the same per-primitive times: Welch's t and Levene's
// test (median centre) on the Box-Cox transformed samples with the lambda chosen here, and the
// Hodges-Lehmann ratio against NumPy's median of the Walsh averages of the log ratios.
#include "audit/speed_audit.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "audit/distribution_audit.h"
#include "stats/box_cox.h"
#include "stats/stats_testing.h"

namespace ra::audit {
namespace {

// Times shaped like a driver's, [primitive][round]: log-normal spread over two decades (the
// primitives differ), each multiplied by `factor` on the second side, by a factor per process
// (round and side: the machine's luck, 2%) and by a few percent of noise per draw.
void paired_times(std::size_t n, int rounds, double factor, unsigned seed, RoundTimes& base,
                  RoundTimes& cur) {
  std::mt19937_64 rng(seed);
  std::lognormal_distribution<double> size(3.0, 1.2);
  std::normal_distribution<double> noise(0.0, 0.03), process(0.0, 0.02);
  std::vector<double> luck_base(rounds), luck_cur(rounds);
  for (int r = 0; r < rounds; ++r) luck_base[r] = std::exp(process(rng)), luck_cur[r] = std::exp(process(rng));
  base.assign(n, std::vector<double>(rounds));
  cur.assign(n, std::vector<double>(rounds));
  for (std::size_t i = 0; i < n; ++i) {
    const double t = size(rng);
    for (int r = 0; r < rounds; ++r) {
      base[i][r] = t * luck_base[r] * std::exp(noise(rng));
      cur[i][r] = factor * t * luck_cur[r] * std::exp(noise(rng));
    }
  }
}

TEST(SpeedVerdict, IntervalAgainstTheBand) {
  // band exp(max(log 1.05, control)): 5% without a control
  EXPECT_EQ(decide_speed(1.10, 1.20, 0.05, 0, 3).verdict, SpeedVerdict::kSlower);
  EXPECT_EQ(decide_speed(0.70, 0.80, 0.05, 0, 3).verdict, SpeedVerdict::kFaster);
  EXPECT_EQ(decide_speed(0.97, 1.03, 0.05, 0, 3).verdict, SpeedVerdict::kSame);
  // straddling the band's upper edge: unknown, and more repeats named
  const SpeedDecision straddle = decide_speed(1.02, 1.12, 0.05, 0, 3);
  EXPECT_EQ(straddle.verdict, SpeedVerdict::kUnknown);
  EXPECT_GT(straddle.repeats_to_settle, 3);
  // the same interval is `same` when the A/A control moved 15% (log 1.15 = 0.14)
  EXPECT_EQ(decide_speed(1.02, 1.12, 0.05, std::log(1.15), 3).verdict, SpeedVerdict::kSame);
  // a 10% slowdown is not counted when the control moved 20%
  EXPECT_EQ(decide_speed(1.08, 1.12, 0.05, std::log(1.2), 3).verdict, SpeedVerdict::kSame);
  // a wide interval around 1: unknown
  EXPECT_EQ(decide_speed(0.6, 1.6, 0.05, 0, 3).verdict, SpeedVerdict::kUnknown);
  // undefined intervals are unknown with no advice
  const SpeedDecision none = decide_speed(NAN, NAN, 0.05, 0, 3);
  EXPECT_EQ(none.verdict, SpeedVerdict::kUnknown);
  EXPECT_EQ(none.repeats_to_settle, 0);
  // the band's edge itself: inside
  EXPECT_EQ(decide_speed(1.0, 1.05, 0.05, 0, 3).verdict, SpeedVerdict::kSame);
}

TEST(SpeedComparison, RatioIntervalAndTestsEqualSciPy) {
  RoundTimes base, cur, ctl, unused;
  paired_times(200, 6, 1.30, 1, base, cur);
  paired_times(200, 6, 1.00, 2, ctl, unused);
  // the control: the baseline's primitives again, with their own process luck and noise
  for (std::size_t i = 0; i < base.size(); ++i)
    for (int r = 0; r < 6; ++r) ctl[i][r] = base[i][r] * (ctl[i][r] / unused[i][r]);
  const SpeedComparison c = compare_speed(base, cur, ctl, 0.05);
  ASSERT_TRUE(c.box_cox.applicable);
  ASSERT_TRUE(c.welch.defined);
  ASSERT_TRUE(c.levene.defined);
  EXPECT_EQ(c.repeats, 6);
  EXPECT_EQ(c.verdict, SpeedVerdict::kSlower);
  EXPECT_NEAR(c.ratio, 1.30, 0.04);
  EXPECT_NEAR(c.control_ratio, 1.0, 0.04);
  EXPECT_GE(c.band, 1.05);

  std::vector<double> base_median, cur_median;
  for (std::size_t i = 0; i < base.size(); ++i) {
    std::vector<double> b = base[i], k = cur[i];
    std::sort(b.begin(), b.end()), std::sort(k.begin(), k.end());
    base_median.push_back((b[2] + b[3]) / 2), cur_median.push_back((k[2] + k[3]) / 2);
  }
  const nlohmann::json ref = stats::testing::run_scipy(R"(
B = np.array(inp["base"]); C = np.array(inp["cur"]); lam = inp["lambda"]
d = []
for r in range(B.shape[1]):
    x = np.log(C[:, r] / B[:, r])
    i, j = np.triu_indices(len(x))
    d.append(float(np.median((x[i] + x[j]) / 2)))
d = np.array(d)
lo, hi = scipy.stats.t.interval(0.95, len(d) - 1, loc=d.mean(), scale=scipy.stats.sem(d))
b = np.array(inp["base_median"]); c = np.array(inp["cur_median"])
tb = scipy.stats.boxcox(b, lmbda=lam); tc = scipy.stats.boxcox(c, lmbda=lam)
w = scipy.stats.ttest_ind(tb, tc, equal_var=False)
l = scipy.stats.levene(tb, tc, center="median")
out = {"ratio": math.exp(d.mean()), "low": math.exp(lo), "high": math.exp(hi),
       "welch_t": float(w.statistic), "welch_p": float(w.pvalue),
       "levene_w": float(l.statistic), "levene_p": float(l.pvalue)}
)",
                                                      {{"base", base},
                                                       {"cur", cur},
                                                       {"base_median", base_median},
                                                       {"cur_median", cur_median},
                                                       {"lambda", c.box_cox.lambda}});
  EXPECT_NEAR(c.ratio, ref["ratio"].get<double>(), 1e-12);
  EXPECT_NEAR(c.low, ref["low"].get<double>(), 1e-9);  // Boost's and SciPy's t quantiles: 1e-11 apart
  EXPECT_NEAR(c.high, ref["high"].get<double>(), 1e-9);
  // Our t is baseline minus current, as SciPy's first-minus-second.
  EXPECT_NEAR(c.welch.statistic, ref["welch_t"].get<double>(),
              1e-9 * std::fabs(ref["welch_t"].get<double>()));
  EXPECT_NEAR(c.welch.p_value, ref["welch_p"].get<double>(), 1e-9);
  EXPECT_NEAR(c.levene.statistic, ref["levene_w"].get<double>(),
              1e-9 * std::fabs(ref["levene_w"].get<double>()));
  EXPECT_NEAR(c.levene.p_value, ref["levene_p"].get<double>(), 1e-9);
}

TEST(SpeedComparison, TheRoundsNotThePrimitivesAreTheReplicates) {
  // Why: every primitive of one process shares that process's luck. With the sides' processes 6%
  // apart by luck alone (no true change), 200 primitives must not make the interval narrow.
  RoundTimes base, cur;
  paired_times(200, 4, 1.0, 7, base, cur);
  for (std::size_t i = 0; i < cur.size(); ++i)
    for (int r = 0; r < 4; ++r) cur[i][r] *= r % 2 ? 1.06 : 0.97;
  const SpeedComparison c = compare_speed(base, cur, {}, 0.05);
  EXPECT_NE(c.verdict, SpeedVerdict::kSlower);
  EXPECT_NE(c.verdict, SpeedVerdict::kFaster);
  EXPECT_LT(c.low, 1.0);
  EXPECT_GT(c.high, 1.0);
}

TEST(SpeedComparison, IdenticalSidesAreSameAndOneRoundIsUnknown) {
  RoundTimes base, cur;
  paired_times(150, 6, 1.0, 4, base, cur);
  const SpeedComparison same = compare_speed(base, cur, {}, 0.05);
  EXPECT_EQ(same.verdict, SpeedVerdict::kSame);
  EXPECT_TRUE(std::isnan(same.control_ratio));
  paired_times(150, 1, 1.0, 4, base, cur);
  const SpeedComparison one = compare_speed(base, cur, {}, 0.05);
  EXPECT_EQ(one.verdict, SpeedVerdict::kUnknown);
  EXPECT_NE(one.reason.find("at least 2"), std::string::npos);
  EXPECT_TRUE(std::isnan(one.low));
  EXPECT_THROW(compare_speed({{1, 2}}, {{1}}, {}, 0.05), std::invalid_argument);
  EXPECT_EQ(compare_speed({}, {}, {}, 0.05).verdict, SpeedVerdict::kUnknown);
}

TEST(SpeedComparison, HolmOverEveryDefinedSpeedTest) {
  RoundTimes base, cur;
  std::vector<SpeedComparison> all;
  for (unsigned s = 0; s < 3; ++s) {
    paired_times(60, 4, 1.0 + 0.1 * s, 10 + s, base, cur);
    all.push_back(compare_speed(base, cur, {}, 0.05));
  }
  adjust_speed_tests(all);
  std::vector<double> p;
  for (const SpeedComparison& c : all) p.push_back(c.welch.p_value), p.push_back(c.levene.p_value);
  const std::vector<double> holm = holm_adjust(p);
  for (std::size_t i = 0; i < all.size(); ++i) {
    EXPECT_DOUBLE_EQ(all[i].welch_p_holm, holm[2 * i]);
    EXPECT_DOUBLE_EQ(all[i].levene_p_holm, holm[2 * i + 1]);
  }
}

TEST(SpeedTiming, RoundsAlternateTheirOrder) {
  EXPECT_EQ(round_order(3, 0), (std::vector<std::size_t>{0, 1, 2}));
  EXPECT_EQ(round_order(3, 1), (std::vector<std::size_t>{2, 1, 0}));
  EXPECT_EQ(round_order(3, 2), (std::vector<std::size_t>{0, 1, 2}));
  // over two rounds every side has the same mean position
  for (std::size_t k = 1; k <= 5; ++k) {
    std::vector<double> position(k, 0);
    for (int r = 0; r < 2; ++r) {
      const auto order = round_order(k, r);
      for (std::size_t at = 0; at < k; ++at) position[order[at]] += double(at);
    }
    for (double p : position) EXPECT_DOUBLE_EQ(p, double(k - 1));
  }
}

}  // namespace
}  // namespace ra::audit
