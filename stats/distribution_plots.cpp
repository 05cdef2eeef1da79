// Q-Q plot, relative bihistogram and box-plot data; see distribution_plots.h. e-Handbook 1.3.3.24,
// 1.3.3.2, 1.3.3.7.
#include "stats/distribution_plots.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace ra::stats {
namespace {

void require_sample(const std::vector<double>& sample, const char* what) {
  if (sample.empty()) throw std::invalid_argument(std::string(what) + ": empty sample");
  require_finite(sample, what);
}

}  // namespace

QQPlotData qq_plot(std::vector<double> sample1, std::vector<double> sample2) {
  require_sample(sample1, "qq_plot, sample 1");
  require_sample(sample2, "qq_plot, sample 2");
  sort_ascending(sample1);
  sort_ascending(sample2);
  const bool first_is_smaller = sample1.size() <= sample2.size();
  const std::vector<double>& smaller = first_is_smaller ? sample1 : sample2;
  const std::vector<double>& larger = first_is_smaller ? sample2 : sample1;

  QQPlotData q;
  const std::size_t m = smaller.size();
  q.p.reserve(m);
  std::vector<double> matched;
  matched.reserve(m);
  for (std::size_t i = 1; i <= m; ++i) {
    const double p = static_cast<double>(i) / static_cast<double>(m + 1);
    q.p.push_back(p);
    // note: for equal sizes HF6 at i / (n + 1) is exactly the i-th order statistic
    matched.push_back(larger.size() == m
                          ? larger[i - 1]
                          : quantile_sorted(larger, p, QuantileDefinition::kHyndmanFan6));
  }
  q.x = first_is_smaller ? smaller : matched;
  q.y = first_is_smaller ? matched : smaller;
  return q;
}

BihistogramData relative_bihistogram(const std::vector<double>& sample1,
                                     const std::vector<double>& sample2,
                                     const BihistogramOptions& options) {
  require_sample(sample1, "relative_bihistogram, sample 1");
  require_sample(sample2, "relative_bihistogram, sample 2");
  const std::vector<double> combined = merged_ascending(sample1, sample2);
  const double lo = combined.front();
  const double hi = combined.back();
  const double n = static_cast<double>(combined.size());
  if (!std::isfinite(hi - lo)) {
    throw std::invalid_argument("relative_bihistogram: the range of the data overflows a double");
  }

  BihistogramData h;
  h.n1 = sample1.size();
  h.n2 = sample2.size();
  std::size_t bins = options.bins;
  double low_edge = lo;
  if (lo == hi) {
    // one value only: one bin of width 1 around it
    bins = 1;
    low_edge = lo - 0.5;
    h.bin_width = 1;
  } else {
    if (bins == 0) {
      const double iqr = quantile_sorted(combined, 0.75) - quantile_sorted(combined, 0.25);
      double rule_bins = 0;
      if (iqr > 0) {
        const double width = 2 * iqr / std::cbrt(n);
        rule_bins = std::ceil((hi - lo) / width);
      } else {
        rule_bins = 1 + std::ceil(std::log2(n));
      }
      const double cap = static_cast<double>(std::max<std::size_t>(1, options.max_bins));
      bins = static_cast<std::size_t>(std::clamp(rule_bins, 1.0, cap));
    }
    h.bin_width = (hi - lo) / static_cast<double>(bins);
  }
  h.edges.resize(bins + 1);
  for (std::size_t i = 0; i <= bins; ++i) {
    h.edges[i] = low_edge + h.bin_width * static_cast<double>(i);
  }
  h.edges.back() = lo == hi ? lo + 0.5 : hi;  // the last edge is the maximum exactly

  auto bin_of = [&](double x) {
    // the index by division, then corrected against the stored edges so that rounding never puts a
    // value on the wrong side of an edge
    auto i = static_cast<std::size_t>(std::floor((x - low_edge) / h.bin_width));
    i = std::min(i, bins - 1);
    while (i > 0 && x < h.edges[i]) --i;
    while (i + 1 < bins && x >= h.edges[i + 1]) ++i;
    return i;
  };
  h.count1.assign(bins, 0);
  h.count2.assign(bins, 0);
  for (double x : sample1) ++h.count1[bin_of(x)];
  for (double x : sample2) ++h.count2[bin_of(x)];
  h.height1.resize(bins);
  h.height2.resize(bins);
  for (std::size_t i = 0; i < bins; ++i) {
    h.height1[i] = static_cast<double>(h.count1[i]) / (static_cast<double>(h.n1) * h.bin_width);
    h.height2[i] = static_cast<double>(h.count2[i]) / (static_cast<double>(h.n2) * h.bin_width);
  }
  return h;
}

std::vector<SampleBoxPlot> box_plots(const std::vector<std::vector<double>>& samples,
                                     QuantileDefinition definition, std::size_t max_outliers) {
  if (samples.empty()) throw std::invalid_argument("box_plots: no samples");
  std::size_t largest = 0;
  for (const auto& s : samples) {
    require_sample(s, "box_plots");
    largest = std::max(largest, s.size());
  }
  std::vector<SampleBoxPlot> out;
  out.reserve(samples.size());
  for (const auto& s : samples) {
    SampleBoxPlot b;
    b.box = box_plot(s, definition, max_outliers);
    b.relative_width = static_cast<double>(s.size()) / static_cast<double>(largest);
    out.push_back(std::move(b));
  }
  return out;
}

}  // namespace ra::stats
