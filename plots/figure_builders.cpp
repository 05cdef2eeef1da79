// Builders of Figures from the analysis stage's plot data (see the header).
#include "plots/figure_builders.h"

#include <algorithm>
#include <cmath>

#include "stats/descriptive.h"

namespace ra::plots {

Figure qq_figure(const std::string& id, const std::string& title, const std::string& axis_label,
                 const std::string& x_sample, const std::string& y_sample,
                 const ra::stats::QQPlotData& data, std::size_t n_x, std::size_t n_y, double scale,
                 std::size_t max_points) {
  Figure f;
  f.id = id;
  f.title = title;
  f.x_label = axis_label + ", " + x_sample;
  f.y_label = axis_label + ", " + y_sample;
  QQContent c;
  c.x_sample = x_sample;
  c.y_sample = y_sample;
  c.n_x = n_x;
  c.n_y = n_y;
  const std::size_t m = data.x.size();
  auto take = [&](std::size_t i) {
    c.x.push_back(data.x[i] * scale);
    c.y.push_back(data.y[i] * scale);
    if (i < data.p.size()) c.p.push_back(data.p[i]);
  };
  if (m <= max_points || max_points < 2) {
    for (std::size_t i = 0; i < m; ++i) take(i);
  } else {
    std::size_t last = m;
    for (std::size_t k = 0; k < max_points; ++k) {
      const std::size_t i = std::size_t(std::llround(double(k) * double(m - 1) / double(max_points - 1)));
      if (i != last) take(i);
      last = i;
    }
  }
  if (m > c.x.size())
    f.note = "Every " + std::to_string((m + c.x.size() - 1) / c.x.size()) +
             "th of " + std::to_string(m) + " quantile pairs is drawn (first and last included).";
  f.caption = "Quantile-quantile plot of " + x_sample + " (x) against " + y_sample +
              " (y): points on the line y = x mean equal distributions.";
  f.content = std::move(c);
  return f;
}

Figure bihistogram_figure(const std::string& id, const std::string& title,
                          const std::string& axis_label, const std::string& upper_sample,
                          const std::string& lower_sample, const ra::stats::BihistogramData& data,
                          double scale) {
  Figure f;
  f.id = id;
  f.title = title;
  f.x_label = axis_label;
  f.y_label = "relative frequency (density)";
  BihistogramContent c;
  c.upper_sample = upper_sample;
  c.lower_sample = lower_sample;
  c.n_upper = data.n1;
  c.n_lower = data.n2;
  for (double e : data.edges) c.edges.push_back(e * scale);
  c.upper_count = data.count1;
  c.lower_count = data.count2;
  for (std::size_t i = 0; i + 1 < c.edges.size(); ++i) {
    const double w = c.edges[i + 1] - c.edges[i];
    c.upper_height.push_back(data.n1 && w > 0 ? double(data.count1[i]) / (double(data.n1) * w) : 0);
    c.lower_height.push_back(data.n2 && w > 0 ? double(data.count2[i]) / (double(data.n2) * w) : 0);
  }
  f.caption = "Relative bihistogram: " + upper_sample + " above the axis, " + lower_sample +
              " below, on common bins, each normalised to area 1.";
  f.content = std::move(c);
  return f;
}

HistogramSeries histogram_series(const NamedSample& sample, double scale, std::size_t max_bins) {
  HistogramSeries hs;
  hs.name = sample.name;
  hs.n = sample.values.size();
  if (sample.values.empty()) return hs;
  std::vector<double> sorted = sample.values;
  std::sort(sorted.begin(), sorted.end());
  // the central 99 %: a few extreme values must not stretch the axis until the body of the
  // distribution falls into a few bins
  double lo = ra::stats::quantile_sorted(sorted, 0.005), hi = ra::stats::quantile_sorted(sorted, 0.995);
  if (!(hi > lo)) lo = sorted.front(), hi = sorted.back();
  const double iqr = ra::stats::quantile_sorted(sorted, 0.75) - ra::stats::quantile_sorted(sorted, 0.25);
  const double n = double(sorted.size());
  std::size_t bins;
  if (!(hi > lo)) {
    bins = 1, lo -= 0.5, hi += 0.5;  // one value: one bin of width 1 centred on it
  } else {
    const double width = iqr > 0 ? 2 * iqr / std::cbrt(n) : 0;
    bins = width > 0 ? std::size_t(std::ceil((hi - lo) / width))
                     : std::size_t(1 + std::ceil(std::log2(n)));
    bins = std::clamp<std::size_t>(bins, kHistogramMinBins, std::max<std::size_t>(max_bins, 1));
  }
  hs.counts.assign(bins, 0);
  for (double v : sorted) {
    if (v < lo) {
      ++hs.n_below;
      continue;
    }
    if (v > hi) {
      ++hs.n_above;
      continue;
    }
    std::size_t k = std::size_t((v - lo) / (hi - lo) * double(bins));
    if (k >= bins) k = bins - 1;
    ++hs.counts[k];
  }
  for (std::size_t i = 0; i <= bins; ++i)
    hs.edges.push_back((lo + (hi - lo) * double(i) / double(bins)) * scale);
  for (std::size_t i = 0; i < bins; ++i) {
    const double w = hs.edges[i + 1] - hs.edges[i];
    hs.heights.push_back(w > 0 ? double(hs.counts[i]) / (n * w) : 0);
  }
  return hs;
}

Figure histogram_figure(const std::string& id, const std::string& title,
                        const std::string& axis_label, const std::vector<NamedSample>& samples,
                        double scale, std::size_t max_bins) {
  Figure f;
  f.id = id;
  f.title = title;
  f.x_label = axis_label;
  f.y_label = "relative frequency (density)";
  HistogramContent c;
  c.density = true;
  std::string beyond;
  for (const auto& s : samples) {
    if (s.values.empty()) continue;
    HistogramSeries hs = histogram_series(s, scale, max_bins);
    if (hs.n_below + hs.n_above > 0)
      beyond += (beyond.empty() ? "" : "; ") + hs.name.substr(0, hs.name.find(':')) + " " +
                std::to_string(hs.n_below) + " below, " + std::to_string(hs.n_above) + " above";
    c.series.push_back(std::move(hs));
  }
  c.panels = c.series.size() > 1;
  if (!beyond.empty())
    f.note = "Bins over each group's central 99 % (Freedman-Diaconis on its own spread); values "
             "beyond, not drawn: " + beyond + ".";
  f.caption = c.panels ? "Histograms (density: each has area 1), one panel per series, each on "
                         "bins of its own spread."
                       : "Histogram (density: area 1) on bins of the sample's own spread.";
  f.content = std::move(c);
  return f;
}

}  // namespace ra::plots
