// Trend figures for `renderaudit history`: one metric's median and IQR over successive audits, one
// series per platform x kind x view group, drawn by FigureRenderer (figure_renderer.h) like every
// other figure, as PNG + vector PDF, with the numbers as CSV beside them.
//
// How a trend is drawn: as a box plot whose categories are the audits (oldest left) and whose
// series are the platform x kind x view groups. The history keeps each group's median and IQR,
// not its quartiles, so each box is an IQR band: as tall as the IQR, centred on the median (black
// line), without whiskers; its width is proportional to n, as in the run figures. The figure's
// note says so.
#pragma once

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "plots/figure.h"
#include "plots/figure_renderer.h"

namespace ra::plots {

// One metric's distribution in one audit.
struct TrendPoint {
  std::size_t audit = 0;  // index into TrendData::audits
  double median = NAN;    // record units (docs/records.md); NaN: no data, not drawn
  double iqr = NAN;       // record units
  std::uint64_t n = 0;    // values the statistics are over
};

struct TrendSeries {
  std::string name;  // legend, e.g. "osmesa-llvmpipe triangle A"
  std::vector<TrendPoint> points;
};

struct TrendData {
  std::string id;  // file stem: [a-z0-9_.-]
  // Records column, e.g. "te_u": its symbol, units and paper scale label the y axis.
  std::string metric;
  std::vector<std::string> audits;  // x categories, oldest first, e.g. "#12"
  std::vector<std::string> dates;   // the audits' dates (ISO 8601), same order
  std::vector<TrendSeries> series;
  std::string note;  // appended to the figure's note (e.g. change points found in the series)
};

// The y-axis label of a metric column and the power of ten its values are shown at: the paper's
// table scale when a table shows the metric, else display_exponent(max_abs). E.g. "TEu-norm x 10^3
// (W*H units)", 3. Unknown columns are labelled with the column name.
std::string trend_axis_label(const std::string& metric, double max_abs, int* exponent);

// The Figure FigureRenderer draws for `data` (box plot, display units; see above).
Figure trend_figure(const TrendData& data);

// Draws every trend into `out_dir` (created when missing) as ID.png, ID.pdf and ID.csv; the CSV
// holds the trend's numbers in record units: audit,date_utc,series,n,median,iqr. Starts a private
// Xvfb when there is no usable display (headless_display.h). Returns what was written, in order.
std::vector<RenderedFigure> draw_trend_figures(const std::vector<TrendData>& trends,
                                               const std::string& out_dir);

}  // namespace ra::plots
