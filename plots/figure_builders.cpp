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
  std::vector<double> all;
  for (const auto& s : samples) all.insert(all.end(), s.values.begin(), s.values.end());
  if (!all.empty()) {
    // Common bins: the bihistogram's rule on the combined data (sample 2 = sample 1 is harmless).
    ra::stats::BihistogramOptions opt;
    opt.max_bins = max_bins;
    const auto bins = ra::stats::relative_bihistogram(all, all, opt);
    std::vector<double> edges;
    for (double e : bins.edges) edges.push_back(e * scale);
    for (const auto& s : samples) {
      if (s.values.empty()) continue;
      HistogramSeries hs;
      hs.name = s.name;
      hs.edges = edges;
      hs.n = s.values.size();
      hs.counts.assign(edges.size() - 1, 0);
      const double lo = bins.edges.front(), hi = bins.edges.back();
      const std::size_t nb = hs.counts.size();
      for (double v : s.values) {
        std::size_t k = hi > lo ? std::size_t((v - lo) / (hi - lo) * double(nb)) : 0;
        if (k >= nb) k = nb - 1;
        ++hs.counts[k];
      }
      for (std::size_t i = 0; i < nb; ++i) {
        const double w = edges[i + 1] - edges[i];
        hs.heights.push_back(w > 0 ? double(hs.counts[i]) / (double(hs.n) * w) : 0);
      }
      c.series.push_back(std::move(hs));
    }
  }
  f.caption = "Histogram (density: each series has area 1) on common bins.";
  f.content = std::move(c);
  return f;
}


}  // namespace ra::plots
