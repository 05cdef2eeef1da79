// The data a histogram figure is drawn from (histogram_series), on a sample whose quantiles are
// known in closed form: the integers 0 .. n-1. Hyndman-Fan 6 puts quantile p at (n + 1) p - 1, so
// the central 99 %, the Freedman-Diaconis width and the bin count follow by hand; the counts are
// checked against a brute-force count of the values between each pair of edges.
#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <vector>

#include "plots/figure_builders.h"

namespace ra::plots {
namespace {

// n even, so that no edge falls on an integer (the nearest is 0.015 away).
constexpr std::size_t kN = 100002;

NamedSample integers() {
  NamedSample s{"integers", {}};
  for (std::size_t i = 0; i < kN; ++i) s.values.push_back(double(i));
  return s;
}

double hf6(double p) { return double(kN + 1) * p - 1; }

TEST(HistogramBins, TheCentralNinetyNinePercentAndFreedmanDiaconisByHand) {
  const HistogramSeries hs = histogram_series(integers(), 1.0, 200);
  const double lo = hf6(0.005), hi = hf6(0.995);  // 499.015, 99501.985
  const double width = 2 * (hf6(0.75) - hf6(0.25)) / std::cbrt(double(kN));
  const std::size_t bins = std::size_t(std::ceil((hi - lo) / width));
  ASSERT_EQ(bins, 46u);  // (hi - lo) / width = 45.95
  ASSERT_EQ(hs.edges.size(), bins + 1);
  ASSERT_EQ(hs.counts.size(), bins);
  EXPECT_NEAR(hs.edges.front(), lo, 1e-9);
  EXPECT_NEAR(hs.edges.back(), hi, 1e-9);
  for (std::size_t k = 0; k <= bins; ++k)
    EXPECT_NEAR(hs.edges[k], lo + (hi - lo) * double(k) / double(bins), 1e-7) << k;
  EXPECT_EQ(hs.n, kN);
  EXPECT_EQ(hs.n_below, 500u);  // 0 .. 499
  EXPECT_EQ(hs.n_above, 500u);  // 99502 .. 100001
}

TEST(HistogramBins, CountsAreTheValuesBetweenEachPairOfEdges) {
  const HistogramSeries hs = histogram_series(integers(), 1.0, 200);
  std::size_t inside = 0;
  for (std::size_t k = 0; k < hs.counts.size(); ++k) {
    std::size_t brute = 0;
    for (std::size_t i = 0; i < kN; ++i)
      if (double(i) >= hs.edges[k] && double(i) < hs.edges[k + 1]) ++brute;
    EXPECT_EQ(hs.counts[k], brute) << "bin " << k;
    inside += brute;
  }
  EXPECT_EQ(inside + hs.n_below + hs.n_above, kN);
}

TEST(HistogramBins, DensitiesHaveTheAreaOfTheValuesInsideAndScaleWithTheUnit) {
  // 1e3 on the axis: edges times 1e3, heights divided by it, the area unchanged.
  const HistogramSeries a = histogram_series(integers(), 1.0, 200);
  const HistogramSeries b = histogram_series(integers(), 1e3, 200);
  ASSERT_EQ(a.heights.size(), b.heights.size());
  double area_a = 0, area_b = 0;
  for (std::size_t k = 0; k < a.heights.size(); ++k) {
    area_a += a.heights[k] * (a.edges[k + 1] - a.edges[k]);
    area_b += b.heights[k] * (b.edges[k + 1] - b.edges[k]);
    EXPECT_NEAR(b.edges[k], a.edges[k] * 1e3, 1e-6 * std::fabs(b.edges[k]) + 1e-9);
    EXPECT_NEAR(b.heights[k] * 1e3, a.heights[k], 1e-12);
  }
  const double expected = double(kN - 1000) / double(kN);
  EXPECT_NEAR(area_a, expected, 1e-12);
  EXPECT_NEAR(area_b, expected, 1e-12);
}

TEST(HistogramBins, FewBinsAreRaisedToTheMinimumAndManyCutToTheMaximum) {
  // 1001 integers: Freedman-Diaconis gives ceil(991.98 / 100.17) = 10 bins, raised to 12.
  NamedSample small{"small", {}};
  for (int i = 0; i <= 1000; ++i) small.values.push_back(i);
  EXPECT_EQ(histogram_series(small, 1.0, 200).counts.size(), kHistogramMinBins);
  // The 46 bins of the big sample, cut to 20.
  EXPECT_EQ(histogram_series(integers(), 1.0, 20).counts.size(), 20u);
}

}  // namespace
}  // namespace ra::plots
