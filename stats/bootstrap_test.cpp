// The order-statistic bootstrap of the median and IQR: against the textbook draw-and-sort
// bootstrap on the same sample, and against the asymptotic standard errors of sample quantiles,
// Var(x_p) = p(1 - p) / (n f(x_p)^2) and Cov(x_p, x_q) = p(1 - q) / (n f(x_p) f(x_q)) for p < q
// (Serfling 1980, 2.3.3), on large normal and uniform samples.
#include "stats/bootstrap.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

namespace ra::stats {
namespace {

std::vector<double> sorted_sample(std::size_t n, bool normal, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> z;
  std::uniform_real_distribution<double> u;
  std::vector<double> v(n);
  for (double& x : v) x = normal ? z(rng) : u(rng);
  std::sort(v.begin(), v.end());
  return v;
}

double sd(const std::vector<double>& v) { return mean_and_variance(v).sd; }

TEST(Bootstrap, EqualsTheDrawAndSortBootstrapOnTheSameSample) {
  for (QuantileDefinition d :
       {QuantileDefinition::kHyndmanFan6, QuantileDefinition::kHyndmanFan7}) {
    for (std::size_t n : {std::size_t(7), std::size_t(41), std::size_t(300)}) {
      const std::vector<double> x = sorted_sample(n, true, 11 + n);
      const int b = 40000;
      std::mt19937_64 rng(99);
      std::uniform_int_distribution<std::size_t> pick(0, n - 1);
      std::vector<double> medians, iqrs, resample(n);
      for (int r = 0; r < b; ++r) {
        for (double& v : resample) v = x[pick(rng)];
        const Description s = describe(resample, d);
        medians.push_back(s.median);
        iqrs.push_back(s.iqr);
      }
      BootstrapOptions o;
      o.resamples = b;
      o.definition = d;
      const MedianIqrBootstrap ours = bootstrap_median_iqr(x, o);
      // two independent Monte Carlo estimates of one SE: within 3% (each about 0.4% here)
      EXPECT_NEAR(ours.median.se / sd(medians), 1.0, 0.03) << n;
      EXPECT_NEAR(ours.iqr.se / sd(iqrs), 1.0, 0.03) << n;
      std::sort(medians.begin(), medians.end());
      const double spacing = (x.back() - x.front()) / double(n);
      EXPECT_NEAR(ours.median.lo95,
                  quantile_sorted(medians, 0.025, QuantileDefinition::kHyndmanFan7), 3 * spacing)
          << n;
      EXPECT_NEAR(ours.median.hi95,
                  quantile_sorted(medians, 0.975, QuantileDefinition::kHyndmanFan7), 3 * spacing)
          << n;
    }
  }
}

TEST(Bootstrap, MatchesTheAsymptoticStandardErrorsOnLargeNormalAndUniformSamples) {
  const std::size_t n = 100000;
  const double root_n = std::sqrt(double(n));
  BootstrapOptions o;
  o.resamples = 4000;
  // N(0, 1): f(0) = 1/sqrt(2 pi), f(z_0.75) = phi(0.6744898) = 0.3177766.
  const double f50 = 1 / std::sqrt(2 * M_PI), f75 = 0.31777657;
  const double se_median_normal = std::sqrt(0.25 / (f50 * f50)) / root_n;  // 1.2533 / sqrt n
  const double var_q = 0.25 * 0.75 / (f75 * f75), cov_q = 0.25 * 0.25 / (f75 * f75);
  const double se_iqr_normal = std::sqrt(2 * var_q - 2 * cov_q) / root_n;  // 1.5733 / sqrt n
  const MedianIqrBootstrap normal = bootstrap_median_iqr(sorted_sample(n, true, 5), o);
  EXPECT_NEAR(se_median_normal * root_n, 1.2533141, 1e-6);
  EXPECT_NEAR(se_iqr_normal * root_n, 1.5733, 1e-3);
  EXPECT_NEAR(normal.median.se / se_median_normal, 1.0, 0.12);
  EXPECT_NEAR(normal.iqr.se / se_iqr_normal, 1.0, 0.12);
  // U(0, 1): f = 1; SE(median) = 0.5 / sqrt n, Var(IQR) = 2 (3/16 - 1/16) / n = 1 / (4n).
  const MedianIqrBootstrap uniform = bootstrap_median_iqr(sorted_sample(n, false, 6), o);
  EXPECT_NEAR(uniform.median.se / (0.5 / root_n), 1.0, 0.12);
  EXPECT_NEAR(uniform.iqr.se / (0.5 / root_n), 1.0, 0.12);
  // the 95% interval of the median: about +-1.96 SE around the true 0.5
  EXPECT_NEAR(uniform.median.lo95, 0.5 - 1.96 * 0.5 / root_n, 0.002);
  EXPECT_NEAR(uniform.median.hi95, 0.5 + 1.96 * 0.5 / root_n, 0.002);
}

TEST(Bootstrap, IsReproducibleAndSaysNothingOfAConstantSample) {
  const std::vector<double> x = sorted_sample(1000, true, 3);
  BootstrapOptions o;
  const MedianIqrBootstrap a = bootstrap_median_iqr(x, o), b = bootstrap_median_iqr(x, o);
  EXPECT_EQ(a.median.se, b.median.se);
  EXPECT_EQ(a.iqr.hi95, b.iqr.hi95);
  EXPECT_EQ(a.resamples, 2000);
  o.seed = 7;
  EXPECT_NE(bootstrap_median_iqr(x, o).median.se, a.median.se);
  const MedianIqrBootstrap one = bootstrap_median_iqr({4.5}, o);
  EXPECT_EQ(one.median.se, 0);
  EXPECT_EQ(one.median.lo95, 4.5);
  EXPECT_EQ(bootstrap_median_iqr({2, 2, 2, 2}, o).iqr.se, 0);
  EXPECT_THROW(bootstrap_median_iqr({}, o), std::invalid_argument);
  EXPECT_THROW(bootstrap_median_iqr({2, 1}, o), std::invalid_argument);
}

}  // namespace
}  // namespace ra::stats
