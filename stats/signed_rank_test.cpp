// The signed-rank estimate and interval against a brute-force count of T+'s null distribution,
// against NumPy's median of every Walsh average, and against SciPy 1.10's `wilcoxon` (Debian 12's
// python3-scipy): the interval must be exactly the centres its two-sided test does not reject.
#include "stats/signed_rank.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>

#include "stats/stats_testing.h"

namespace ra::stats {
namespace {

// Deterministic skewed differences, like log time ratios: a shift, normal noise, a few outliers.
std::vector<double> log_ratios(std::size_t n, double shift, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, 0.08);
  std::exponential_distribution<double> tail(8.0);
  std::vector<double> d(n);
  for (double& x : d) x = shift + noise(rng) + (rng() % 10 == 0 ? tail(rng) : 0.0);
  return d;
}

TEST(SignedRank, NullDistributionEqualsEnumeratingEverySignPattern) {
  for (std::size_t n : {1u, 2u, 7u, 12u}) {
    const std::size_t total = n * (n + 1) / 2;
    std::vector<double> count(total + 1, 0);
    for (std::size_t mask = 0; mask < (std::size_t(1) << n); ++mask) {
      std::size_t s = 0;
      for (std::size_t k = 0; k < n; ++k)
        if (mask >> k & 1) s += k + 1;
      ++count[s];
    }
    double tail = 0;
    for (std::size_t t = total + 1; t-- > 0;) {
      tail += count[t] / double(std::size_t(1) << n);
      EXPECT_NEAR(signed_rank_upper_tail(n, double(t)), tail, 1e-15) << "n " << n << " t " << t;
    }
  }
}

TEST(SignedRank, IntervalIsWhatSciPysTestDoesNotReject) {
  nlohmann::json cases = nlohmann::json::array();
  std::vector<SignedRankInterval> ours;
  const std::vector<std::pair<std::size_t, double>> sizes = {{6, 0.1}, {9, -0.2}, {25, 0.0},
                                                             {50, 0.3}, {400, -0.05}};
  for (std::size_t c = 0; c < sizes.size(); ++c) {
    const std::vector<double> d = log_ratios(sizes[c].first, sizes[c].second, unsigned(c + 1));
    ours.push_back(signed_rank_interval(d));
    // Just inside and just outside each end: far below the gap between neighbouring Walsh
    // averages of continuous data.
    const double eps = 1e-9;
    cases.push_back({{"d", d},
                     {"exact", sizes[c].first <= 50},
                     {"probes", {ours.back().low + eps, ours.back().low - eps,
                                 ours.back().high - eps, ours.back().high + eps}}});
  }
  const nlohmann::json ref = testing::run_scipy(R"(
out = []
for c in inp:
    d = np.array(c["d"])
    i, j = np.triu_indices(len(d))
    hl = float(np.median((d[i] + d[j]) / 2))
    ps = []
    for m in c["probes"]:
        if c["exact"]:
            ps.append(float(scipy.stats.wilcoxon(d - m, method="exact").pvalue))
        else:
            ps.append(float(scipy.stats.wilcoxon(d - m, method="approx", correction=True).pvalue))
    out.append({"hl": hl, "p": ps})
)",
                                                cases);
  for (std::size_t c = 0; c < sizes.size(); ++c) {
    SCOPED_TRACE("n = " + std::to_string(sizes[c].first));
    EXPECT_NEAR(ours[c].estimate, ref[c]["hl"].get<double>(), 1e-12);
    EXPECT_LE(ours[c].low, ours[c].estimate);
    EXPECT_GE(ours[c].high, ours[c].estimate);
    EXPECT_EQ(ours[c].exact, sizes[c].first <= 300);
    const auto& p = ref[c]["p"];
    EXPECT_GT(p[0].get<double>(), 0.05) << "just inside the low end is rejected";
    EXPECT_LE(p[1].get<double>(), 0.05) << "just outside the low end is not rejected";
    EXPECT_GT(p[2].get<double>(), 0.05) << "just inside the high end is rejected";
    EXPECT_LE(p[3].get<double>(), 0.05) << "just outside the high end is not rejected";
  }
}

TEST(SignedRank, HardCases) {
  // Too few for any 95% interval: all six signs alike have probability 1/64 < 2.5%, five 1/32.
  EXPECT_THROW(signed_rank_interval({0.1, 0.2, 0.3, 0.4, 0.5}), std::invalid_argument);
  EXPECT_NO_THROW(signed_rank_interval({0.1, 0.2, 0.3, 0.4, 0.5, 0.6}));
  EXPECT_THROW(signed_rank_interval({0.1, 0.2, NAN, 0.4, 0.5, 0.6, 0.7}), std::invalid_argument);
  EXPECT_THROW(signed_rank_interval({}), std::invalid_argument);
  // n = 6: the interval is the smallest and largest Walsh average, the data's own ends.
  const SignedRankInterval six = signed_rank_interval({0.1, 0.2, 0.3, 0.4, 0.5, 0.6});
  EXPECT_DOUBLE_EQ(six.low, 0.1);
  EXPECT_DOUBLE_EQ(six.high, 0.6);
  EXPECT_DOUBLE_EQ(six.estimate, 0.35);
  // Constant differences: a point interval at the constant.
  const SignedRankInterval flat = signed_rank_interval(std::vector<double>(40, -0.25));
  EXPECT_EQ(flat.low, -0.25);
  EXPECT_EQ(flat.high, -0.25);
  EXPECT_EQ(flat.estimate, -0.25);
  // A large common offset: the estimate keeps the small differences' precision.
  std::vector<double> offset = log_ratios(80, 0.0, 7);
  const SignedRankInterval plain = signed_rank_interval(offset);
  for (double& x : offset) x += 1e6;
  const SignedRankInterval shifted = signed_rank_interval(offset);
  EXPECT_NEAR(shifted.estimate - 1e6, plain.estimate, 1e-9);
  EXPECT_NEAR(shifted.low - 1e6, plain.low, 1e-9);
  // The normal approximation and the exact count meet at the switch: n = 300 and 301 intervals of
  // nearly the same data are close.
  const std::vector<double> d300 = log_ratios(301, 0.1, 11);
  const SignedRankInterval a = signed_rank_interval({d300.begin(), d300.end() - 1});
  const SignedRankInterval b = signed_rank_interval(d300);
  EXPECT_TRUE(a.exact);
  EXPECT_FALSE(b.exact);
  EXPECT_NEAR(a.low, b.low, 0.01);
  EXPECT_NEAR(a.high, b.high, 0.01);
}

}  // namespace
}  // namespace ra::stats
