// Histograms give each sample bins of its own spread, so that a narrow view group beside a wide
// one is not squeezed into a few bins, and draw several samples as panels.
#include "plots/figure_builders.h"

#include <gtest/gtest.h>

#include <random>

namespace ra::plots {
namespace {

std::size_t occupied(const HistogramSeries& s) {
  std::size_t n = 0;
  for (std::size_t c : s.counts) n += c > 0;
  return n;
}

// Why: histogram.line.lse_u_norm put view groups C and D (errors about 50 times smaller than A's)
// into about 3 bins of common bins, C hidden under D's outline.
TEST(HistogramFigure, AWideAndANarrowGroupEachGetBinsOfTheirOwnSpread) {
  std::mt19937_64 rng(3);
  std::normal_distribution<double> wide(0.5, 0.2), narrow(0.01, 0.002);
  NamedSample a{"A: 30 deg, 128x128", {}}, c{"C: 30 deg, 907x907", {}};
  for (int i = 0; i < 4000; ++i) a.values.push_back(wide(rng)), c.values.push_back(narrow(rng));
  a.values.push_back(40.0);  // one far outlier must not stretch the bins either
  const Figure f = histogram_figure("histogram.test", "t", "x", {a, c}, 1e3);
  const auto& h = std::get<HistogramContent>(f.content);
  ASSERT_EQ(h.series.size(), 2u);
  EXPECT_TRUE(h.panels) << "two groups are drawn in panels of their own, none under another";
  for (const HistogramSeries& s : h.series) {
    EXPECT_GE(occupied(s), 10u) << s.name;
    EXPECT_EQ(s.n, s.name[0] == 'A' ? 4001u : 4000u);
    std::size_t inside = 0;
    for (std::size_t k : s.counts) inside += k;
    EXPECT_EQ(inside + s.n_below + s.n_above, s.n) << s.name;
  }
  // each on its own axis: the narrow group's bins span its own values (x 10^3), not A's
  EXPECT_LT(h.series[1].edges.back() - h.series[1].edges.front(), 40.0);
  EXPECT_GT(h.series[0].edges.back() - h.series[0].edges.front(), 400.0);
  EXPECT_GE(h.series[0].n_above, 1u);  // beyond the 99.5 % quantile, the outlier among them
  EXPECT_NE(f.note.find("values beyond, not drawn: A "), std::string::npos) << f.note;

  // one sample: shared axes (no panels), still at least kHistogramMinBins bins
  NamedSample same{"A", std::vector<double>(50, 1.0)};
  same.values.push_back(2.0);
  const Figure single = histogram_figure("h", "t", "x", {same});
  const auto& one = std::get<HistogramContent>(single.content);
  EXPECT_FALSE(one.panels);
  ASSERT_EQ(one.series.size(), 1u);
  EXPECT_GE(one.series[0].counts.size(), kHistogramMinBins);
}

}  // namespace
}  // namespace ra::plots
