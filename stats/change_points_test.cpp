// E-Divisive change points: the divergence against a brute-force evaluation of its definition,
// and the segmentation on series whose steps are known (nightly drawing times: log
// microseconds with a few percent of noise).
#include "stats/change_points.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>

namespace ra::stats {
namespace {

// Q(t) straight from its definition (no running sums).
double divergence(const std::vector<double>& x, std::size_t t) {
  const std::size_t n = x.size();
  double cross = 0, left = 0, right = 0;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j) {
      const double d = std::fabs(x[i] - x[j]);
      if (j < t) left += d;
      else if (i >= t) right += d;
      else cross += d;
    }
  const double a = double(t), b = double(n - t);
  return a * b / (a + b) *
         (2 * cross / (a * b) - left / (a * (a - 1) / 2) - right / (b * (b - 1) / 2));
}

// `levels[k]` for `lengths[k]` nights each, log-normal noise of `sd`.
std::vector<double> nights(const std::vector<double>& levels, const std::vector<int>& lengths,
                           double sd, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0, sd);
  std::vector<double> x;
  for (std::size_t k = 0; k < levels.size(); ++k)
    for (int i = 0; i < lengths[k]; ++i) x.push_back(std::log(levels[k]) + noise(rng));
  return x;
}

TEST(ChangePoints, DivergenceEqualsItsDefinition) {
  const std::vector<double> x = nights({1.0, 1.2, 0.9}, {7, 5, 9}, 0.05, 1);
  for (std::size_t m : {2u, 3u, 5u}) {
    const std::vector<double> q = split_divergences(x, m);
    ASSERT_EQ(q.size(), x.size() - 2 * m + 1);
    for (std::size_t i = 0; i < q.size(); ++i)
      EXPECT_NEAR(q[i], divergence(x, m + i), 1e-12 * (1 + std::fabs(q[i]))) << "m " << m;
  }
  EXPECT_TRUE(split_divergences({1, 2, 3}, 2).empty());
}

TEST(ChangePoints, OneStepIsFoundOnTheNightItEntered) {
  // 25 nights at 100 us, then 30 at 130 us, 3% noise
  const std::vector<ChangePoint> c = e_divisive(nights({100, 130}, {25, 30}, 0.03, 2));
  ASSERT_EQ(c.size(), 1u);
  EXPECT_EQ(c[0].index, 25u);
  EXPECT_LT(c[0].p_value, 0.01);
}

TEST(ChangePoints, TwoStepsBothWaysAreBothFound) {
  const std::vector<ChangePoint> c = e_divisive(nights({100, 125, 95}, {20, 15, 20}, 0.03, 3));
  ASSERT_EQ(c.size(), 2u);
  EXPECT_EQ(c[0].index, 20u);
  EXPECT_EQ(c[1].index, 35u);
}

TEST(ChangePoints, NoiseAndASingleBadNightAreNoChange) {
  for (unsigned seed = 10; seed < 20; ++seed) {
    std::vector<double> x = nights({100}, {60}, 0.04, seed);
    EXPECT_TRUE(e_divisive(x).empty()) << "seed " << seed;
    x[30] += std::log(2.0);  // one night twice as slow (a busy machine), then back
    EXPECT_TRUE(e_divisive(x).empty()) << "seed " << seed;
  }
}

TEST(ChangePoints, ShortAndBadInput) {
  EXPECT_TRUE(e_divisive({}).empty());
  EXPECT_TRUE(e_divisive({1, 2, 3, 4, 5}).empty());  // fewer than 2 x 3 values
  EXPECT_THROW(e_divisive({1, 2, NAN, 4, 5, 6, 7}), std::invalid_argument);
  ChangePointOptions one;
  one.min_segment = 1;
  EXPECT_THROW(e_divisive({1, 2, 3, 4}, one), std::invalid_argument);
  // constant series: every split has Q = 0, which no permutation exceeds... nor falls below
  EXPECT_TRUE(e_divisive(std::vector<double>(20, 4.6)).empty());
  // the same input and seed: the same answer
  const std::vector<double> x = nights({100, 112}, {12, 12}, 0.03, 5);
  const auto a = e_divisive(x), b = e_divisive(x);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i].p_value, b[i].p_value);
}

}  // namespace
}  // namespace ra::stats
