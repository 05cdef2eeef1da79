// What a figure shows, independent of how it is drawn: the plots stage builds these from the
// analysis output, FigureRenderer (figure_renderer.h) draws them with VTK, and write_figure_data()
// writes the numbers behind each one beside its PNG, so that every figure can be checked (and
// re-plotted with another tool) without reading pixels.
//
// All numbers are in display units: the builder has already multiplied a metric by its display
// scale (e.g. LSEs-norm x 10^3, as the paper's tables do) and says so in the axis label.
// Figure kinds follow the paper (Hagedorn et al. 2008, section 4) and the NIST e-Handbook:
// quantile-quantile plot (Fig. 4; e-Handbook 1.3.3.24), relative bihistogram (Figs. 5, 7, 9, 11,
// 13; 1.3.3.2), box plots with widths proportional to n and a y range restricted to the box bodies
// (Figs. 6, 8, 10, 12; 1.3.3.7), histograms, and bar charts (visibility classes, conformance).
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "metrics/records.h"

namespace ra::plots {

using Rgb = std::array<unsigned char, 3>;

// The one colour of each GL conformance class (docs/conformance.md) in every figure, whichever
// classes a figure shows: exact, snapped and within-spec in calm blues from dark to light (best to
// worst), violation red, the alarming one. kNotCompared: grey.
Rgb conformance_class_color(metrics::Conformance c);

// The two shares of the conformance figures (conformance.KIND, conformance.overview) that differ
// from the reference rasterizer: of all compared cases in Okabe-Ito blue, of the cases with lit
// pixels in its vermillion.
Rgb differs_share_color(bool lit_pixels_only);

// Platform p of n in a class's colour `base`: the first platform (the experiment's baseline) in
// `base` itself, each further one lighter, mixed with up to 55 % white. Mixing with white keeps
// the hue: one class is one family of colours across the platforms of a figure, and the legend is
// needed only to tell the platforms apart.
Rgb platform_shade(Rgb base, std::size_t p, std::size_t n);

// Q-Q plot of sample 1 (x) against sample 2 (y), with the line y = x.
struct QQContent {
  std::string x_sample, y_sample;  // legend names of the samples, e.g. "view 1", "view 2"
  std::vector<double> x, y;        // matching quantiles, ascending
  std::vector<double> p;           // plotting positions (may be empty)
  std::size_t n_x = 0, n_y = 0;    // sizes of the samples the quantiles come from
};

// Relative bihistogram: common bins, sample 1 above the axis, sample 2 below, each histogram with
// area 1 (height = count / (n * bin width), 1 / display unit).
struct BihistogramContent {
  std::string upper_sample, lower_sample;  // legend names
  std::vector<double> edges;               // bins + 1 ascending edges
  std::vector<std::size_t> upper_count, lower_count;
  std::vector<double> upper_height, lower_height;  // densities, both >= 0 (lower drawn negated)
  std::size_t n_upper = 0, n_lower = 0;
};

// One box of a box plot (Tukey): box q1..q3, median line, whiskers to the most extreme values
// within the 1.5 IQR fences; min and max marked when they are outside the whiskers.
struct Box {
  std::string category;  // x-axis category, e.g. "A"
  std::string series;    // legend series (colour), e.g. a platform
  double lower_whisker = 0, q1 = 0, median = 0, q3 = 0, upper_whisker = 0;
  double min = 0, max = 0;
  std::size_t n = 0;
  std::size_t n_outliers_low = 0, n_outliers_high = 0;
};

// Box plots by category and series. Box width is proportional to n (the largest n gets the full
// width of its slot). The y range covers the boxes and whiskers only ("restricted to the bodies
// of the boxes"); values outside it are counted in the figure's note.
struct BoxPlotContent {
  std::vector<std::string> categories;  // x order
  std::vector<std::string> series;      // legend order
  std::vector<Box> boxes;
};

// Histograms: on shared axes, one series draws filled bars and several draw step outlines; as
// panels (small multiples), each series has a panel of its own, stacked top to bottom, with its own
// bins and x axis, so that a narrow group is not squeezed into a few bins of a wide one's axis and
// no group's outline hides under another's.
struct HistogramSeries {
  std::string name;
  std::vector<double> edges;         // bins + 1 ascending edges
  std::vector<std::size_t> counts;   // values per bin
  std::vector<double> heights;       // count / (n * width) when density, else count
  std::size_t n = 0;                 // values of the series, inside the bins or not
  std::size_t n_below = 0, n_above = 0;  // values left of the first edge, right of the last
};
struct HistogramContent {
  bool density = true;  // heights are densities (area 1 each) rather than counts
  bool panels = false;  // one panel per series (above) rather than shared axes
  std::vector<HistogramSeries> series;
};

// Grouped bars: for each category one bar per series, optionally labelled (e.g. counts).
struct BarSeries {
  std::string name;
  std::vector<double> values;       // one per category
  std::vector<std::string> labels;  // text above each bar; empty = none
  std::optional<Rgb> color;         // a colour of its own (a conformance class); none: the palette's
};
// On a log10 axis (y_log10) the bars rise from a floor at least a decade below the smallest
// positive value (at most 1), so that a share of 2 in 10,000 beside one of 99.9 % has a bar a reader sees; a
// value of 0 has no bar, only its label.
struct BarChartContent {
  std::vector<std::string> categories;
  std::vector<BarSeries> series;
  double y_max = 0;      // fixed top of the y axis when > 0 (e.g. 100 for percentages)
  bool y_log10 = false;  // a log10 y axis (display units; ticks at powers of ten)
};
// The floor the bars of a log10 bar chart rise from: the power of ten at or below the smallest
// positive value, divided by 10, at most 1 (display units): 0.001 for 0.02. 0.1 when no value is
// positive.
double bar_chart_log_floor(const BarChartContent& content);

// Scatter plot: one marker per point, coloured by series (legend), labelled beside the marker, with
// optional error bars (e.g. the interquartile range [q1, q3] around a median). Either axis may be
// log10: ticks at powers of ten (and 2, 5 x 10^k when the range spans few decades); a point with
// a non-positive coordinate on a log axis cannot be placed and is omitted, and the figure's note
// says which (scatter_omitted_note()); a bar end <= 0 on a log axis is drawn to the plot's edge.
struct ScatterSeries {
  std::string name;                 // legend entry, e.g. a platform
  std::vector<double> x, y;         // display units, one per point
  std::vector<std::string> labels;  // text beside each marker (e.g. "A"); empty = none
  // Error bars, one per point or empty (none); NaN in both ends of a pair = no bar for that point.
  std::vector<double> x_lo, x_hi, y_lo, y_hi;
};
struct ScatterContent {
  std::vector<ScatterSeries> series;
  bool x_log10 = false, y_log10 = false;  // log10 axes
};

using FigureContent = std::variant<QQContent, BihistogramContent, BoxPlotContent, HistogramContent,
                                   BarChartContent, ScatterContent>;

struct Figure {
  std::string id;       // file stem: [a-z0-9_.-] only, unique in a run directory
  std::string title;    // names the platform(s), view (group) and metric
  std::string x_label;  // with units
  std::string y_label;  // with units
  std::string note;     // printed on the figure under the plot (may be empty; lines split by \n)
  std::string caption;  // a sentence for the report: what is compared and how
  std::string section;  // report grouping, e.g. "points"
  int height = 0;       // image pixels; 0: a page's (FigureRenderer's default); the width is a page's
  FigureContent content;
};

// "qq", "bihistogram", "boxplot", "histogram", "bars", "scatter".
const char* figure_kind_name(const Figure& figure);

// The note a box plot must carry: which boxes have values outside the restricted y range
// [y_lo, y_hi] (the range FigureRenderer uses: box_plot_y_range()). Empty when none.
std::string box_plot_outside_note(const BoxPlotContent& content, double y_lo, double y_hi);

// The y range of a box plot restricted to the bodies (whiskers) of the boxes, padded by 5 %.
void box_plot_y_range(const BoxPlotContent& content, double* y_lo, double* y_hi);

// The note a scatter plot must carry when a point has a non-positive coordinate on a log10 axis:
// how many points are omitted and which ("A osmesa-llvmpipe (y = 0)"). Empty when none.
std::string scatter_omitted_note(const ScatterContent& content);

// Writes the numbers a figure shows, as CSV (header row, full precision), to `path`:
//   qq:          p,x,y
//   bihistogram: bin_lo,bin_hi,upper_count,lower_count,upper_height,lower_height
//                (the lower bars are drawn at -lower_height)
//   boxplot:     category,series,n,min,lower_whisker,q1,median,q3,upper_whisker,max,
//                n_outliers_low,n_outliers_high,relative_width
//   histogram:   series,bin_lo,bin_hi,count,height
//   bars:        category,series,value,label
//   scatter:     series,label,x,y,x_lo,x_hi,y_lo,y_hi (every point given, also those a log axis
//                omits; empty cells: no error bar)
void write_figure_data(const Figure& figure, const std::string& path);

// Display scale for values of magnitude up to `max_abs`: a power of 1000 (1, 10^3, 10^6, ...)
// that brings them to at least 0.1, so that axis numbers read like the paper's "x 10^3" tables.
// Returns the exponent (0, 3, 6, ...); 0 for max_abs >= 0.1 or max_abs == 0.
int display_exponent(double max_abs);

}  // namespace ra::plots
