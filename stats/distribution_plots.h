// Data behind the plots that compare distributions: quantile-quantile plot of two samples,
// relative bihistogram, and box plots of several samples. Only numbers here; drawing is plots/'s.
// NIST/SEMATECH e-Handbook of Statistical Methods: 1.3.3.24 (quantile-quantile plot), 1.3.3.2
// (bihistogram), 1.3.3.7 (box plot); the audit paper's Figs. 4, 5 and 6.
#pragma once

#include <cstddef>
#include <vector>

#include "stats/descriptive.h"

namespace ra::stats {

// Points of a quantile-quantile plot of sample 1 (x axis) against sample 2 (y axis), units of the
// data. Dataplot convention (e-Handbook 1.3.3.24): the smaller sample, of size m, gives its sorted
// values, the order statistics at plotting positions p_i = i / (m + 1), i = 1..m (Weibull,
// Hyndman-Fan 6, like the quartiles); the larger sample gives its Hyndman-Fan 6 quantiles at the
// same p_i, interpolated between its order statistics. Equal sizes pair the order statistics.
struct QQPlotData {
  std::vector<double> x;  // quantiles of sample 1, ascending
  std::vector<double> y;  // quantiles of sample 2 at the same probabilities, ascending
  std::vector<double> p;  // the plotting positions p_i, in (0, 1)
};

// Q-Q plot points of two non-empty finite samples (m = min(n1, n2) points).
// Throws std::invalid_argument on an empty sample or non-finite values.
QQPlotData qq_plot(std::vector<double> sample1, std::vector<double> sample2);

// Relative bihistogram (e-Handbook 1.3.3.2): both samples binned on common bins, each sample's
// heights divided by (its n x bin width) so that each histogram has area 1 whatever its n.
// Sample 1 is drawn above the axis, sample 2 below.
struct BihistogramData {
  std::vector<double> edges;        // bins + 1 ascending edges, units of the data
  std::vector<std::size_t> count1;  // values of sample 1 in each bin
  std::vector<std::size_t> count2;
  std::vector<double> height1;  // count1 / (n1 * width): density, 1 / units of the data
  std::vector<double> height2;
  std::size_t n1 = 0;
  std::size_t n2 = 0;
  double bin_width = 0;  // units of the data
};

// Bin count rule when none is given: Freedman-Diaconis on the combined sample,
// width = 2 IQR / N^(1/3) (IQR by Hyndman-Fan 6), bins = ceil(range / width), clamped to
// [1, max_bins]; Sturges' 1 + ceil(log2 N) when the IQR is 0. Bins are equal, span [min, max] of
// the combined data, are closed on the left and open on the right except the last (closed). When
// every value is the same, one bin of width 1 centred on it.
struct BihistogramOptions {
  std::size_t bins = 0;         // 0: the rule above
  std::size_t max_bins = 1000;  // cap for the rule
};

// Relative bihistogram of two non-empty finite samples.
// Throws std::invalid_argument on an empty sample or non-finite values.
BihistogramData relative_bihistogram(const std::vector<double>& sample1,
                                     const std::vector<double>& sample2,
                                     const BihistogramOptions& options = {});

// One box of a multi-sample box plot.
struct SampleBoxPlot {
  BoxPlotData box;            // quartiles, whiskers, fences, outliers (see descriptive.h)
  double relative_width = 0;  // n / (largest n among the samples), in (0, 1]
};

// Box-plot data of each sample, with box widths proportional to the sample sizes
// (e-Handbook 1.3.3.7 lists width proportional to n as a common variant; the largest box has width
// 1). Throws std::invalid_argument when `samples` or one sample is empty, or on non-finite values.
std::vector<SampleBoxPlot> box_plots(
    const std::vector<std::vector<double>>& samples,
    QuantileDefinition definition = QuantileDefinition::kHyndmanFan6,
    std::size_t max_outliers = 1000);

}  // namespace ra::stats
