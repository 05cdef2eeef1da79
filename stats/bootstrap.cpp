// Bootstrap of the median and the IQR through resampled order statistics (see the header).
#include "stats/bootstrap.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

namespace ra::stats {
namespace {

// 1-based position h of quantile p among n order statistics, as descriptive.cpp places it.
double position(double p, std::size_t n, QuantileDefinition d) {
  return d == QuantileDefinition::kHyndmanFan6 ? p * double(n + 1) : 1 + p * double(n - 1);
}

double beta(std::mt19937_64& rng, double a, double b) {
  const double x = std::gamma_distribution<double>(a, 1.0)(rng);
  const double y = std::gamma_distribution<double>(b, 1.0)(rng);
  return x / (x + y);
}

BootstrapEstimate summarise(std::vector<double> values) {
  BootstrapEstimate e;
  e.se = mean_and_variance(values).sd;
  sort_ascending(values);
  e.lo95 = quantile_sorted(values, 0.025, QuantileDefinition::kHyndmanFan7);
  e.hi95 = quantile_sorted(values, 0.975, QuantileDefinition::kHyndmanFan7);
  return e;
}

}  // namespace

MedianIqrBootstrap bootstrap_median_iqr(const std::vector<double>& sorted,
                                        const BootstrapOptions& options) {
  const std::size_t n = sorted.size();
  if (n == 0) throw std::invalid_argument("bootstrap_median_iqr: empty sample");
  if (options.resamples < 2) throw std::invalid_argument("bootstrap_median_iqr: resamples < 2");
  require_finite(sorted, "bootstrap_median_iqr");
  if (!std::is_sorted(sorted.begin(), sorted.end()))
    throw std::invalid_argument("bootstrap_median_iqr: sample not sorted");

  // The ranks a resample's quartiles and median interpolate between (clamped to [1, n], as
  // quantile_sorted clamps positions), ascending and distinct.
  const double p[3] = {0.25, 0.5, 0.75};
  std::size_t lower[3];
  double frac[3];
  std::vector<std::size_t> ranks;
  for (int i = 0; i < 3; ++i) {
    const double h = std::clamp(position(p[i], n, options.definition), 1.0, double(n));
    lower[i] = std::size_t(std::floor(h));
    frac[i] = h - double(lower[i]);
    ranks.push_back(lower[i]);
    ranks.push_back(std::min(lower[i] + 1, n));
  }
  std::sort(ranks.begin(), ranks.end());
  ranks.erase(std::unique(ranks.begin(), ranks.end()), ranks.end());

  std::mt19937_64 rng(options.seed);
  std::vector<double> at(n + 2);  // at[k]: the resample's k-th order statistic (for k in ranks)
  std::vector<double> medians, iqrs;
  medians.reserve(options.resamples);
  iqrs.reserve(options.resamples);
  for (int r = 0; r < options.resamples; ++r) {
    double u = 0;
    std::size_t k = 0;
    for (std::size_t next : ranks) {
      const double m = double(next - k);  // steps above the last rank drawn
      u = u + (1 - u) * beta(rng, m, double(n - next + 1));
      k = next;
      const std::size_t index =
          std::clamp<std::size_t>(std::size_t(std::ceil(u * double(n))), 1, n);
      at[next] = sorted[index - 1];
    }
    double q[3];
    for (int i = 0; i < 3; ++i) {
      const double a = at[lower[i]], b = at[std::min(lower[i] + 1, n)];
      q[i] = a + frac[i] * (b - a);
    }
    medians.push_back(q[1]);
    iqrs.push_back(q[2] - q[0]);
  }
  return {summarise(std::move(medians)), summarise(std::move(iqrs)), options.resamples,
          options.seed};
}

}  // namespace ra::stats
