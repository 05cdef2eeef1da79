// Bootstrap standard errors and 95% percentile intervals of the median and the interquartile
// range of one sample (units of the data), seeded and reproducible (Efron and Tibshirani 1993,
// chapters 6 and 13).
//
// A quantile of a resample needs only two of its order statistics (those on either side of the
// quantile's position), so no resample is ever drawn whole: the k-th smallest of n draws with
// replacement from the sorted sample x(1) <= ... <= x(n) is x(ceil(n U)), where U is the k-th
// smallest of n independent uniforms on (0, 1), U ~ Beta(k, n - k + 1); given U, the (k + m)-th
// smallest is U + (1 - U) V with V ~ Beta(m, n - k - m + 1) (the n - k uniforms above U are
// independent and uniform on (U, 1)). A resample costs a dozen gamma draws instead of n draws and
// a selection, and has exactly the distribution of the textbook draw-and-sort bootstrap (tested
// against it): 2,000 resamples of a 200,000-value sample take about a millisecond.
#pragma once

#include <cstdint>
#include <vector>

#include "stats/descriptive.h"

namespace ra::stats {

struct BootstrapOptions {
  int resamples = 2000;
  std::uint64_t seed = 2008;
  QuantileDefinition definition = QuantileDefinition::kHyndmanFan6;  // of median and quartiles
};

// One statistic's bootstrap: standard error (sample SD of the resampled statistic, n - 1) and the
// 2.5% and 97.5% percentiles of the resampled statistic (Hyndman-Fan 7). Units of the data.
struct BootstrapEstimate {
  double se = 0;
  double lo95 = 0, hi95 = 0;
};

struct MedianIqrBootstrap {
  BootstrapEstimate median, iqr;
  int resamples = 0;
  std::uint64_t seed = 0;
};

// `sorted`: ascending, finite, non-empty (throws std::invalid_argument otherwise; resamples >= 2).
MedianIqrBootstrap bootstrap_median_iqr(const std::vector<double>& sorted,
                                        const BootstrapOptions& options = {});

}  // namespace ra::stats
