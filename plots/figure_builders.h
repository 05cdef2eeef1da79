// Figures from the analysis stage's numbers (stats/distribution_plots.h): each builder takes
// data in record units and a display scale, and returns a Figure in display units (figure.h).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "stats/distribution_plots.h"
#include "plots/figure.h"

namespace ra::plots {

// Q-Q plot (paper Fig. 4). `scale` multiplies every quantile (e.g. 1e3 for "x 10^-3" units).
// At most `max_points` markers are drawn: more are thinned to evenly spaced plotting positions,
// always keeping the first and last (the CSV beside the figure holds the points drawn).
Figure qq_figure(const std::string& id, const std::string& title, const std::string& axis_label,
                 const std::string& x_sample, const std::string& y_sample,
                 const ra::stats::QQPlotData& data, std::size_t n_x, std::size_t n_y,
                 double scale = 1.0, std::size_t max_points = 2000);

// Relative bihistogram (paper Figs. 5, 7, 9, 11, 13). Edges are multiplied by `scale` and the
// heights divided by it, so each side keeps area 1 in display units.
Figure bihistogram_figure(const std::string& id, const std::string& title,
                          const std::string& axis_label, const std::string& upper_sample,
                          const std::string& lower_sample, const ra::stats::BihistogramData& data,
                          double scale = 1.0);

// A histogram of one or more samples, as densities. Each sample gets bins of its own spread:
// Freedman-Diaconis, width = 2 IQR / n^(1/3) (IQR by Hyndman-Fan 6), over its central 99% (the
// quantiles 0.005 and 0.995; the values beyond are counted in n_below / n_above and in the note),
// at least kHistogramMinBins and at most `max_bins` bins; Sturges' 1 + ceil(log2 n) when the IQR is
// 0. Several samples are drawn as panels, one each, so that a narrow group keeps its bins and none
// hides under another. Empty samples are skipped; returns a figure with no series when every
// sample is empty.
struct NamedSample {
  std::string name;
  std::vector<double> values;  // record units
};
constexpr std::size_t kHistogramMinBins = 12;
Figure histogram_figure(const std::string& id, const std::string& title,
                        const std::string& axis_label, const std::vector<NamedSample>& samples,
                        double scale = 1.0, std::size_t max_bins = 200);
// One sample's series of histogram_figure (record units times `scale` on the edges).
HistogramSeries histogram_series(const NamedSample& sample, double scale, std::size_t max_bins);


}  // namespace ra::plots
