// Tests of stats/distribution_plots.h: Q-Q pairs, relative bihistogram areas and bins, box-plot
// widths; hand-made cases with the reason for each beside it, and NumPy for the interpolation.
#include "stats/distribution_plots.h"

#include <gtest/gtest.h>

#include <numeric>
#include <stdexcept>

#include "stats/stats_testing.h"

namespace ra::stats {
namespace {

// Equal sizes: the plot pairs the order statistics.
TEST(DistributionPlotsQQ, EqualSizesPairOrderStatistics) {
  const QQPlotData q = qq_plot({3, 1, 2}, {30, 10, 20});
  EXPECT_EQ(q.x, (std::vector<double>{1, 2, 3}));
  EXPECT_EQ(q.y, (std::vector<double>{10, 20, 30}));
  EXPECT_EQ(q.p, (std::vector<double>{0.25, 0.5, 0.75}));
}

// Unequal sizes: the smaller sample (4 values) sets p_i = i/5; the larger, 1..9, is interpolated
// at h = 10 p_i = 2, 4, 6, 8 (Hyndman-Fan 6), whichever sample comes first.
TEST(DistributionPlotsQQ, UnequalSizesInterpolateTheLarger) {
  const std::vector<double> small{40, 10, 30, 20};
  const std::vector<double> large{9, 8, 7, 6, 5, 4, 3, 2, 1};
  const QQPlotData a = qq_plot(small, large);
  EXPECT_EQ(a.x, (std::vector<double>{10, 20, 30, 40}));
  EXPECT_EQ(a.y, (std::vector<double>{2, 4, 6, 8}));
  const QQPlotData b = qq_plot(large, small);  // axes swap, pairs stay
  EXPECT_EQ(b.x, (std::vector<double>{2, 4, 6, 8}));
  EXPECT_EQ(b.y, (std::vector<double>{10, 20, 30, 40}));
  // between order statistics: large {0, 10}, small {5}: p = 1/2, h = 1.5 -> 5
  EXPECT_EQ(qq_plot({0, 10}, {5}).x, std::vector<double>{5});
  EXPECT_THROW(qq_plot({}, {1}), std::invalid_argument);
  EXPECT_THROW(qq_plot({1}, {NAN}), std::invalid_argument);
}

// The larger sample's quantiles are NumPy's percentile(method='weibull') at the same p.
TEST(DistributionPlotsQQ, InterpolationAgreesWithNumpy) {
  const auto a = testing::lognormal_sample(37, 0, 1, 71);
  const auto b = testing::normal_sample(250, 1, 0.3, 72);
  const QQPlotData q = qq_plot(a, b);
  const nlohmann::json ref = testing::run_scipy(
      "out = [float(v) for v in np.percentile(np.array(inp['b']), "
      "[100.0 * p for p in inp['p']], method='weibull')]",
      {{"b", b}, {"p", q.p}});
  ASSERT_EQ(q.y.size(), 37u);
  for (std::size_t i = 0; i < q.y.size(); ++i) {
    EXPECT_LT(testing::relative_difference(q.y[i], ref[i]), 1e-12) << i;
  }
}

double area(const std::vector<double>& heights, double width) {
  return std::accumulate(heights.begin(), heights.end(), 0.0) * width;
}

// Each histogram has area 1 whatever its n; counts add up; the edges span the combined range and
// the maximum falls in the last bin.
TEST(DistributionPlotsBihistogram, RelativeHeightsHaveUnitArea) {
  const auto a = testing::exponential_sample(1000, 1, 73);
  const auto b = testing::exponential_sample(137, 1.3, 74);
  const BihistogramData h = relative_bihistogram(a, b);
  ASSERT_EQ(h.edges.size(), h.height1.size() + 1);
  EXPECT_NEAR(area(h.height1, h.bin_width), 1, 1e-12);
  EXPECT_NEAR(area(h.height2, h.bin_width), 1, 1e-12);
  EXPECT_EQ(std::accumulate(h.count1.begin(), h.count1.end(), std::size_t{0}), a.size());
  EXPECT_EQ(std::accumulate(h.count2.begin(), h.count2.end(), std::size_t{0}), b.size());
  std::vector<double> all = a;
  all.insert(all.end(), b.begin(), b.end());
  EXPECT_EQ(h.edges.front(), *std::min_element(all.begin(), all.end()));
  EXPECT_EQ(h.edges.back(), *std::max_element(all.begin(), all.end()));
  EXPECT_GT(h.count1.back() + h.count2.back(), 0u);
  // Freedman-Diaconis on 1137 values of an exponential: a few dozen bins
  EXPECT_GT(h.height1.size(), 10u);
  EXPECT_LT(h.height1.size(), 200u);
}

// A given bin count is used as is; values on an inner edge go to the bin on their right.
TEST(DistributionPlotsBihistogram, GivenBinsAndEdges) {
  BihistogramOptions o;
  o.bins = 4;
  const BihistogramData h = relative_bihistogram({0, 1, 2, 3, 4}, {2, 2}, o);
  EXPECT_EQ(h.edges, (std::vector<double>{0, 1, 2, 3, 4}));
  EXPECT_EQ(h.count1, (std::vector<std::size_t>{1, 1, 1, 2}));  // the last bin is closed: 3 and 4
  EXPECT_EQ(h.count2, (std::vector<std::size_t>{0, 0, 2, 0}));
  EXPECT_DOUBLE_EQ(h.height2[2], 1.0);  // 2 / (2 * 1)
  EXPECT_DOUBLE_EQ(h.height1[3], 0.4);  // 2 / (5 * 1)
}

// Every value the same: one bin of width 1 centred on it (no division by a zero range).
TEST(DistributionPlotsBihistogram, ConstantData) {
  const BihistogramData h = relative_bihistogram({5, 5}, {5});
  EXPECT_EQ(h.edges, (std::vector<double>{4.5, 5.5}));
  EXPECT_EQ(h.height1, std::vector<double>{1.0});
  EXPECT_EQ(h.height2, std::vector<double>{1.0});
  EXPECT_THROW(relative_bihistogram({}, {1}), std::invalid_argument);
}

// Zero IQR but a non-zero range (mostly ties): Sturges' rule instead of Freedman-Diaconis.
TEST(DistributionPlotsBihistogram, ZeroIqrFallsBackToSturges) {
  std::vector<double> a(100, 1.0);
  a.push_back(2.0);
  const BihistogramData h = relative_bihistogram(a, {1.0});
  EXPECT_EQ(h.height1.size(), 1u + 7u);  // 1 + ceil(log2 102)
  EXPECT_NEAR(area(h.height1, h.bin_width), 1, 1e-12);
}

TEST(DistributionPlotsBoxPlots, WidthsProportionalToN) {
  const auto plots = box_plots({{1, 2, 3, 4}, {1, 2}, {5, 6, 7, 8, 9, 10, 11, 12}});
  ASSERT_EQ(plots.size(), 3u);
  EXPECT_DOUBLE_EQ(plots[0].relative_width, 0.5);
  EXPECT_DOUBLE_EQ(plots[1].relative_width, 0.25);
  EXPECT_DOUBLE_EQ(plots[2].relative_width, 1.0);
  EXPECT_EQ(plots[2].box.n, 8u);
  EXPECT_DOUBLE_EQ(plots[2].box.median, 8.5);
  EXPECT_THROW(box_plots({}), std::invalid_argument);
  EXPECT_THROW(box_plots({{1}, {}}), std::invalid_argument);
}

}  // namespace
}  // namespace ra::stats
