// The speed verdict as a pure function of an interval, and the comparison's statistics against
// SciPy 1.10 (Debian 12's python3-scipy) on the same per-primitive times: Welch's t and Levene's
// test (median centre) on the Box-Cox transformed samples with the lambda chosen here, and the
// Hodges-Lehmann ratio against NumPy's median of the Walsh averages of the log ratios.
#include "audit/speed_audit.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "audit/distribution_audit.h"
#include "stats/box_cox.h"
#include "stats/stats_testing.h"

namespace ra::audit {
namespace {

// Per-primitive times shaped like a driver's: log-normal spread over two decades (the primitives
// differ), each multiplied by `factor` and a few percent of noise on the second side.
void paired_times(std::size_t n, double factor, unsigned seed, std::vector<double>& base,
                  std::vector<double>& cur) {
  std::mt19937_64 rng(seed);
  std::lognormal_distribution<double> size(3.0, 1.2);
  std::normal_distribution<double> noise(0.0, 0.03);
  base.clear(), cur.clear();
  for (std::size_t i = 0; i < n; ++i) {
    const double t = size(rng);
    base.push_back(t * std::exp(noise(rng)));
    cur.push_back(factor * t * std::exp(noise(rng)));
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
  std::vector<double> base, cur, ctl, unused;
  paired_times(200, 1.30, 1, base, cur);
  paired_times(200, 1.00, 2, unused, ctl);
  // the control: the baseline's primitives again with their own noise
  std::mt19937_64 rng(3);
  std::normal_distribution<double> noise(0.0, 0.03);
  for (std::size_t i = 0; i < base.size(); ++i) ctl[i] = base[i] * std::exp(noise(rng));
  const SpeedComparison c = compare_speed(base, cur, ctl, 0.05, 3);
  ASSERT_TRUE(c.box_cox.applicable);
  ASSERT_TRUE(c.welch.defined);
  ASSERT_TRUE(c.levene.defined);
  EXPECT_EQ(c.verdict, SpeedVerdict::kSlower);
  EXPECT_NEAR(c.ratio, 1.30, 0.02);
  EXPECT_LT(c.low, 1.30);
  EXPECT_GT(c.high, 1.30);
  EXPECT_NEAR(c.control_ratio, 1.0, 0.02);
  EXPECT_GE(c.band, 1.05);

  const nlohmann::json ref = stats::testing::run_scipy(R"(
b = np.array(inp["base"]); c = np.array(inp["cur"]); lam = inp["lambda"]
d = np.log(c / b)
i, j = np.triu_indices(len(d))
hl = float(np.median((d[i] + d[j]) / 2))
tb = scipy.stats.boxcox(b, lmbda=lam); tc = scipy.stats.boxcox(c, lmbda=lam)
w = scipy.stats.ttest_ind(tb, tc, equal_var=False)
l = scipy.stats.levene(tb, tc, center="median")
out = {"ratio": math.exp(hl), "welch_t": float(w.statistic), "welch_p": float(w.pvalue),
       "levene_w": float(l.statistic), "levene_p": float(l.pvalue)}
)",
                                                      {{"base", base},
                                                       {"cur", cur},
                                                       {"lambda", c.box_cox.lambda}});
  EXPECT_NEAR(c.ratio, ref["ratio"].get<double>(), 1e-12);
  // Our t is baseline minus current, as SciPy's first-minus-second.
  EXPECT_NEAR(c.welch.statistic, ref["welch_t"].get<double>(),
              1e-9 * std::fabs(ref["welch_t"].get<double>()));
  EXPECT_NEAR(c.welch.p_value, ref["welch_p"].get<double>(), 1e-9);
  EXPECT_NEAR(c.levene.statistic, ref["levene_w"].get<double>(),
              1e-9 * std::fabs(ref["levene_w"].get<double>()));
  EXPECT_NEAR(c.levene.p_value, ref["levene_p"].get<double>(), 1e-9);
}

TEST(SpeedComparison, IdenticalSidesAreSameAndTooFewAreUnknown) {
  std::vector<double> base, cur;
  paired_times(150, 1.0, 4, base, cur);
  const SpeedComparison same = compare_speed(base, cur, {}, 0.05, 3);
  EXPECT_EQ(same.verdict, SpeedVerdict::kSame);
  EXPECT_TRUE(std::isnan(same.control_ratio));
  // five primitives cannot give a 95% signed-rank interval
  const SpeedComparison few = compare_speed({1, 2, 3, 4, 5}, {1, 2, 3, 4, 5}, {}, 0.05, 3);
  EXPECT_EQ(few.verdict, SpeedVerdict::kUnknown);
  EXPECT_NE(few.reason.find("at least 6"), std::string::npos);
  EXPECT_THROW(compare_speed({1, 2}, {1}, {}, 0.05, 3), std::invalid_argument);
}

TEST(SpeedComparison, HolmOverEveryDefinedSpeedTest) {
  std::vector<double> base, cur;
  std::vector<SpeedComparison> all;
  for (unsigned s = 0; s < 3; ++s) {
    paired_times(60, 1.0 + 0.1 * s, 10 + s, base, cur);
    all.push_back(compare_speed(base, cur, {}, 0.05, 3));
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
