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

// A histogram of one or more samples on common bins (Freedman-Diaconis on the combined data, as
// relative_bihistogram chooses them), as densities. Empty samples are skipped; returns a figure
// with no series when every sample is empty.
struct NamedSample {
  std::string name;
  std::vector<double> values;  // record units
};
Figure histogram_figure(const std::string& id, const std::string& title,
                        const std::string& axis_label, const std::vector<NamedSample>& samples,
                        double scale = 1.0, std::size_t max_bins = 200);


}  // namespace ra::plots
