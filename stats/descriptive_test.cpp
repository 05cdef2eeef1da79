// Tests of stats/descriptive.h against certified values (NIST StRD univariate summary
// statistics), SciPy / NumPy on the same data, and hand-made hard cases.
#include "stats/descriptive.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <cstdio>
#include <stdexcept>
#include <utility>
#include <vector>

#include "stats/stats_testing.h"

namespace ra::stats {
namespace {

using testing::lre;
using testing::relative_difference;

// NIST StRD: mean and sd with LRE >= 13. NUMACC1 (1e7 + 1, 2, 3) and NUMACC2 (1001 values,
// 1.2 +- 0.1) are the "many constant leading digits" cases; Lew and Michelso are real data.
TEST(DescriptiveStrd, MeanAndSdHaveAtLeast13CorrectDigits) {
  for (const char* file : {"NUMACC1.dat", "NUMACC2.dat", "Lew.dat", "Michelso.dat"}) {
    const auto s = testing::read_strd_univariate(file);
    const Description d = describe(s.data);
    const double lre_mean = lre(d.mean, s.mean);
    const double lre_sd = lre(d.sd, s.sd);
    std::printf("  StRD %-13s n = %4zu  LRE mean = %5.1f  LRE sd = %5.1f  (inf = exact)\n", file,
                d.n, lre_mean, lre_sd);
    EXPECT_EQ(d.n, s.data.size());
    EXPECT_GE(lre_mean, 13) << file << ": mean " << d.mean << " certified " << s.mean;
    EXPECT_GE(lre_sd, 13) << file << ": sd " << d.sd << " certified " << s.sd;
  }
}

// The same sums with a 1e9 offset (the shape of NUMACC3) must keep the digits of the noise:
// dyadic noise makes offset + noise exact, so the sd must equal the noise's sd.
TEST(DescriptiveHardCases, HugeOffsetKeepsTheNoise) {
  const auto noise = testing::dyadic_noise(500, 0.01, 11);
  const auto shifted = testing::plus(noise, 1e9);
  const Description a = describe(noise);
  const Description b = describe(shifted);
  EXPECT_LT(relative_difference(b.sd, a.sd), 1e-12) << b.sd << " vs " << a.sd;
  EXPECT_LT(std::fabs((b.mean - 1e9) - a.mean), 1e-6);  // the mean itself is exact to ~1 ulp of 1e9
  EXPECT_DOUBLE_EQ(b.iqr, a.iqr);
}

// Hyndman-Fan 6 and 7 by hand on {1, 2, 3, 4}.
TEST(DescriptiveQuantiles, HandComputedPositions) {
  const std::vector<double> x{1, 2, 3, 4};
  // HF6: h = 5p -> 1.25, 2.5, 3.75
  EXPECT_DOUBLE_EQ(quantile_sorted(x, 0.25, QuantileDefinition::kHyndmanFan6), 1.25);
  EXPECT_DOUBLE_EQ(quantile_sorted(x, 0.5, QuantileDefinition::kHyndmanFan6), 2.5);
  EXPECT_DOUBLE_EQ(quantile_sorted(x, 0.75, QuantileDefinition::kHyndmanFan6), 3.75);
  // HF7: h = 1 + 3p -> 1.75, 2.5, 3.25
  EXPECT_DOUBLE_EQ(quantile_sorted(x, 0.25, QuantileDefinition::kHyndmanFan7), 1.75);
  EXPECT_DOUBLE_EQ(quantile_sorted(x, 0.75, QuantileDefinition::kHyndmanFan7), 3.25);
  // HF6 positions below 1 or above n clamp to the extremes (h = 0.05 and 4.95)
  EXPECT_DOUBLE_EQ(quantile_sorted(x, 0.01), 1);
  EXPECT_DOUBLE_EQ(quantile_sorted(x, 0.99), 4);
  EXPECT_DOUBLE_EQ(quantile_sorted(x, 0), 1);
  EXPECT_DOUBLE_EQ(quantile_sorted(x, 1), 4);
  EXPECT_THROW(quantile_sorted(x, 1.5), std::invalid_argument);
  EXPECT_THROW(quantile_sorted({}, 0.5), std::invalid_argument);
}

// The default is the e-Handbook's definition (HF6).
TEST(DescriptiveQuantiles, DefaultIsHyndmanFan6) {
  const Description d = describe({4, 1, 3, 2});
  EXPECT_DOUBLE_EQ(d.q1, 1.25);
  EXPECT_DOUBLE_EQ(d.q3, 3.75);
  EXPECT_DOUBLE_EQ(d.iqr, 2.5);
  EXPECT_STREQ(quantile_definition_name(QuantileDefinition::kHyndmanFan6), "hyndman_fan_6");
}

TEST(DescriptiveHardCases, EmptyAndNonFiniteAreRejected) {
  EXPECT_THROW(describe({}), std::invalid_argument);
  EXPECT_THROW(mean({}), std::invalid_argument);
  EXPECT_THROW(describe({1, NAN, 3}), std::invalid_argument);
  EXPECT_THROW(describe({1, INFINITY}), std::invalid_argument);
  EXPECT_THROW(box_plot({-INFINITY}), std::invalid_argument);
  EXPECT_THROW(trimmed_mean({}, 0.1), std::invalid_argument);
  EXPECT_THROW(trimmed_mean({1, 2}, 0.5), std::invalid_argument);
  try {
    describe({1, 2, NAN});
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("value 3 of 3"), std::string::npos) << e.what();
  }
}

// n = 1: no spread can be estimated; sd is reported as 0 (documented), never NaN.
TEST(DescriptiveHardCases, SingleValue) {
  const Description d = describe({7.5});
  EXPECT_EQ(d.n, 1u);
  EXPECT_EQ(d.mean, 7.5);
  EXPECT_EQ(d.sd, 0);
  EXPECT_EQ(d.median, 7.5);
  EXPECT_EQ(d.q1, 7.5);
  EXPECT_EQ(d.q3, 7.5);
  EXPECT_EQ(d.iqr, 0);
  EXPECT_EQ(d.min, 7.5);
  EXPECT_EQ(d.max, 7.5);
}

// n = 2: sd = |a - b| / sqrt(2); HF6 quartiles clamp to the two values (h = 0.75, 2.25).
TEST(DescriptiveHardCases, TwoValues) {
  const Description d = describe({3, 1});
  EXPECT_DOUBLE_EQ(d.mean, 2);
  EXPECT_DOUBLE_EQ(d.sd, std::sqrt(2.0));
  EXPECT_DOUBLE_EQ(d.q1, 1);
  EXPECT_DOUBLE_EQ(d.median, 2);
  EXPECT_DOUBLE_EQ(d.q3, 3);
}

// Constant data: exactly zero spread, even at a huge magnitude where a one-pass sum of squares
// would go negative.
TEST(DescriptiveHardCases, ConstantData) {
  const Description d = describe(std::vector<double>(1000, 123456789.123));
  EXPECT_EQ(d.sd, 0);
  EXPECT_EQ(d.iqr, 0);
  EXPECT_EQ(d.mean, 123456789.123);
}

TEST(DescriptiveTrimmedMean, CutsFloorOfProportionTimesN) {
  // n = 10, 10 %: one value from each end
  EXPECT_DOUBLE_EQ(trimmed_mean({100, 1, 2, 3, 4, 5, 6, 7, 8, -100}, 0.1), 4.5);
  // n = 9: floor(0.9) = 0, nothing cut
  EXPECT_DOUBLE_EQ(trimmed_mean({1, 2, 3, 4, 5, 6, 7, 8, 90}, 0.1), 14);
  EXPECT_EQ(trimmed_count(20, 0.1), 2u);
  EXPECT_DOUBLE_EQ(trimmed_mean({5}, 0.25), 5);
}

// Box plot on a hand-made sample: 1..9 and an outlier 30 (HF6 quartiles of n = 10:
// q1 at h = 2.75 -> 2.75, q3 at h = 8.25 -> 8.25; IQR 5.5; fences -5.5 and 16.5).
TEST(DescriptiveBoxPlot, FencesWhiskersOutliers) {
  const BoxPlotData b = box_plot({30, 1, 2, 3, 4, 5, 6, 7, 8, 9});
  EXPECT_DOUBLE_EQ(b.q1, 2.75);
  EXPECT_DOUBLE_EQ(b.q3, 8.25);
  EXPECT_DOUBLE_EQ(b.median, 5.5);
  EXPECT_DOUBLE_EQ(b.lower_fence, -5.5);
  EXPECT_DOUBLE_EQ(b.upper_fence, 16.5);
  EXPECT_DOUBLE_EQ(b.lower_whisker, 1);
  EXPECT_DOUBLE_EQ(b.upper_whisker, 9);
  EXPECT_EQ(b.n_outliers_low, 0u);
  EXPECT_EQ(b.n_outliers_high, 1u);
  ASSERT_EQ(b.outliers.size(), 1u);
  EXPECT_EQ(b.outliers[0], 30);
  EXPECT_FALSE(b.outliers_truncated);
}

// A sample with many outliers keeps only the most extreme ones, from both ends.
TEST(DescriptiveBoxPlot, OutlierListIsCapped) {
  std::vector<double> v(100, 0.0);
  for (int i = 1; i <= 10; ++i) {
    v.push_back(100.0 + i);
    v.push_back(-100.0 - i);
  }
  const BoxPlotData b = box_plot(v, QuantileDefinition::kHyndmanFan6, 4);
  EXPECT_EQ(b.n_outliers_low, 10u);
  EXPECT_EQ(b.n_outliers_high, 10u);
  EXPECT_TRUE(b.outliers_truncated);
  EXPECT_EQ(b.outliers, (std::vector<double>{-110, -109, 109, 110}));
  EXPECT_EQ(b.lower_whisker, 0);
  EXPECT_EQ(b.upper_whisker, 0);
}

// NumPy / SciPy on the same data: mean, sd (ddof = 1), percentiles by method 'weibull' (HF6) and
// 'linear' (HF7), scipy.stats.trim_mean. Same definitions, so agreement to 1e-10 relative.
TEST(DescriptiveScipy, AgreesWithNumpyAndScipy) {
  std::vector<std::vector<double>> samples{
      testing::normal_sample(101, 10, 2, 1),   testing::lognormal_sample(250, 0, 1, 2),
      testing::exponential_sample(37, 3, 3),   testing::normal_sample(2, 0, 1, 4),
      testing::normal_sample(3, 0, 1, 5),      testing::lognormal_sample(1000, -3, 0.5, 6),
      testing::normal_sample(7, -50, 1e-3, 7),
  };
  const nlohmann::json ref = testing::run_scipy(R"(
out = []
for x in inp:
    x = np.array(x)
    out.append({
        'mean': float(np.mean(x)), 'sd': float(np.std(x, ddof=1)),
        'hf6': [float(v) for v in np.percentile(x, [25, 50, 75], method='weibull')],
        'hf7': [float(v) for v in np.percentile(x, [25, 50, 75], method='linear')],
        'trim10': float(scipy.stats.trim_mean(x, 0.1)),
        'trim25': float(scipy.stats.trim_mean(x, 0.25)),
    })
)",
                                                samples);
  double worst = 0;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const auto& r = ref.at(i);
    const Description d6 = describe(samples[i], QuantileDefinition::kHyndmanFan6);
    const Description d7 = describe(samples[i], QuantileDefinition::kHyndmanFan7);
    const std::vector<std::pair<double, double>> pairs{
        {d6.mean, r["mean"]},
        {d6.sd, r["sd"]},
        {d6.q1, r["hf6"][0]},
        {d6.median, r["hf6"][1]},
        {d6.q3, r["hf6"][2]},
        {d7.q1, r["hf7"][0]},
        {d7.median, r["hf7"][1]},
        {d7.q3, r["hf7"][2]},
        {trimmed_mean(samples[i], 0.1), r["trim10"]},
        {trimmed_mean(samples[i], 0.25), r["trim25"]},
    };
    for (std::size_t k = 0; k < pairs.size(); ++k) {
      const double diff = relative_difference(pairs[k].first, pairs[k].second);
      worst = std::max(worst, diff);
      EXPECT_LT(diff, 1e-10) << "sample " << i << ", statistic " << k << ": " << pairs[k].first
                             << " vs SciPy " << pairs[k].second;
    }
  }
  std::printf("  descriptive vs NumPy/SciPy: worst relative difference %.2g\n", worst);
}

// The median of odd and even counts, as numpy.median gives them (/usr/bin/python3), and NaN for
// no values where median_or_nan is asked.
TEST(Descriptive, MedianOrNan) {
  EXPECT_EQ(median({5, 1, 3}), 3.0);
  EXPECT_EQ(median({4, 1, 3, 2}), 2.5);
  EXPECT_DOUBLE_EQ(median({0.1, 0.7, 0.2, 1e-17}), 0.15000000000000002);
  EXPECT_THROW(median({}), std::invalid_argument);
  EXPECT_EQ(median_or_nan({4, 1, 3, 2}), 2.5);
  EXPECT_TRUE(std::isnan(median_or_nan({})));
}

// Scaling by a power of two is a multiplication where 2^-e is a normal double and std::ldexp
// otherwise: either way every value must equal std::ldexp's, subnormal results (rounded once)
// and the ends of the exponent range included.
TEST(DescriptiveScaling, EqualsLdexpBitForBit) {
  const std::vector<double> values = {1.0,
                                      -3.0,
                                      0.1,
                                      -0.0,
                                      std::numeric_limits<double>::max(),
                                      std::numeric_limits<double>::min(),
                                      std::numeric_limits<double>::denorm_min(),
                                      0x1.fffffffffffffp-1,
                                      0x1.0000000000001p-1020,
                                      0x1.3456789abcdefp+700,
                                      -0x1.fedcba9876543p-900};
  for (int e : {0, 1, -1, 60, -60, 1021, 1022, 1023, 1024, 1074, -1021, -1022, -1023, -1074}) {
    const std::vector<double> got = scaled(values, e);
    ASSERT_EQ(got.size(), values.size());
    for (std::size_t i = 0; i < values.size(); ++i) {
      const double want = std::ldexp(values[i], -e);
      EXPECT_EQ(std::signbit(got[i]), std::signbit(want)) << values[i] << " e " << e;
      EXPECT_TRUE(got[i] == want || (std::isnan(got[i]) && std::isnan(want)))
          << std::hexfloat << values[i] << " x 2^" << -e << ": " << got[i] << ", ldexp " << want;
    }
  }
}

// The mean and sd of data whose scale exponent lies outside the normal range of 2^-e (values of
// 1e-310, subnormal) take the ldexp path and still hold.
TEST(DescriptiveScaling, SubnormalDataKeepTheirMeanAndSd) {
  const double u = std::numeric_limits<double>::denorm_min();
  const MeanVariance m = mean_and_variance({2 * u, 4 * u, 6 * u});
  EXPECT_EQ(m.mean, 4 * u);
  EXPECT_EQ(m.sd, 2 * u);  // sqrt(((2u)^2 + 0 + (2u)^2) / 2), computed on the scaled values
}

// Two ascending samples are merged, others sorted: either way the values of both, ascending, as a
// sort of their concatenation gives them.
TEST(DescriptiveSorting, MergedAscendingEqualsSortingTheConcatenation) {
  const std::vector<double> a = {-2, 0, 0.5, 0.5, 7}, b = {-3, 0.5, 1, 9, 10, 11};
  const std::vector<double> unsorted = {3, -1, 2};
  for (const auto& [x, y] : {std::pair{a, b}, std::pair{b, a}, std::pair{a, unsorted},
                             std::pair{unsorted, b}, std::pair{std::vector<double>{}, a}}) {
    std::vector<double> want = x;
    want.insert(want.end(), y.begin(), y.end());
    std::sort(want.begin(), want.end());
    EXPECT_EQ(merged_ascending(x, y), want);
  }
  std::vector<double> v = {5, 1, 3};
  sort_ascending(v);
  EXPECT_EQ(v, (std::vector<double>{1, 3, 5}));
}

}  // namespace
}  // namespace ra::stats
