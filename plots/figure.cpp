// Figure helpers that need no VTK: kinds, legends, the box-plot range and note, the CSV beside
// each figure.
#include "plots/figure.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

#include "util/cell_text.h"
#include "util/errors.h"
#include "util/number_text.h"

namespace ra::plots {

Rgb conformance_class_color(metrics::Conformance c) {
  switch (c) {
    case metrics::Conformance::kExact: return {8, 69, 148};         // dark blue
    case metrics::Conformance::kSnapped: return {49, 130, 189};     // blue
    case metrics::Conformance::kWithinSpec: return {140, 190, 225};  // light blue
    case metrics::Conformance::kViolation: return {215, 25, 28};    // red
    default: return {150, 150, 150};
  }
}

Rgb differs_share_color(bool lit_pixels_only) {
  return lit_pixels_only ? Rgb{213, 94, 0} : Rgb{0, 114, 178};
}

Rgb platform_shade(Rgb base, std::size_t p, std::size_t n) {
  const double white = n > 1 ? 0.55 * double(std::min(p, n - 1)) / double(n - 1) : 0;
  Rgb out{};
  for (std::size_t i = 0; i < 3; ++i)
    out[i] = static_cast<unsigned char>(std::lround(base[i] + white * (255 - base[i])));
  return out;
}

double bar_chart_log_floor(const BarChartContent& content) {
  double smallest = INFINITY;
  for (const BarSeries& s : content.series)
    for (double v : s.values)
      if (v > 0) smallest = std::min(smallest, v);
  if (!std::isfinite(smallest)) return 0.1;
  return std::min(1.0, std::pow(10.0, std::floor(std::log10(smallest)) - 1));
}

const char* figure_kind_name(const Figure& figure) {
  switch (figure.content.index()) {
    case 0: return "qq";
    case 1: return "bihistogram";
    case 2: return "boxplot";
    case 3: return "histogram";
    case 4: return "bars";
    default: return "scatter";
  }
}

void box_plot_y_range(const BoxPlotContent& content, double* y_lo, double* y_hi) {
  double lo = INFINITY, hi = -INFINITY;
  for (const Box& b : content.boxes) {
    lo = std::min(lo, b.lower_whisker);
    hi = std::max(hi, b.upper_whisker);
  }
  if (!std::isfinite(lo) || !std::isfinite(hi)) lo = 0, hi = 1;
  double pad = 0.05 * (hi - lo);
  if (pad <= 0) pad = std::max(1e-12, 0.05 * std::fabs(hi)) + (hi == 0 ? 0.5 : 0);
  *y_lo = lo - pad;
  *y_hi = hi + pad;
}

std::string box_plot_outside_note(const BoxPlotContent& content, double y_lo, double y_hi) {
  std::vector<std::string> above, below;
  for (const Box& b : content.boxes) {
    // The category's short name ("A" of "A: 30 deg, 128x128").
    const std::string cat = b.category.substr(0, b.category.find(':'));
    const std::string who = cat + (content.series.size() > 1 ? " " + b.series : "");
    if (b.max > y_hi) above.push_back(who + " (max " + util::significant(b.max, 4) + ")");
    if (b.min < y_lo) below.push_back(who + " (min " + util::significant(b.min, 4) + ")");
  }
  if (above.empty() && below.empty()) return "";
  std::string s =
      "Y range restricted to the box bodies and whiskers (1.5 IQR) so the boxes can be compared.";
  auto list = [](const std::vector<std::string>& v) {
    std::string out;
    for (std::size_t i = 0; i < v.size(); ++i) out += (i ? ", " : "") + v[i];
    return out;
  };
  if (!above.empty()) s += "\nAbove the plot: " + list(above) + ".";
  if (!below.empty()) s += "\nBelow the plot: " + list(below) + ".";
  return s;
}

std::string scatter_omitted_note(const ScatterContent& content) {
  std::vector<std::string> omitted;
  for (const ScatterSeries& s : content.series) {
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      std::string why;
      if (content.x_log10 && !(s.x[i] > 0)) why = "x = " + util::significant(s.x[i], 4);
      if (content.y_log10 && !(s.y.at(i) > 0))
        why += (why.empty() ? "" : ", ") + std::string("y = ") + util::significant(s.y.at(i), 4);
      if (why.empty()) continue;
      std::string who = i < s.labels.size() ? s.labels[i] : "";
      if (content.series.size() > 1 || who.empty()) who += (who.empty() ? "" : " ") + s.name;
      omitted.push_back(who + " (" + why + ")");
    }
  }
  if (omitted.empty()) return "";
  std::string list;
  for (std::size_t i = 0; i < omitted.size(); ++i) list += (i ? ", " : "") + omitted[i];
  return std::to_string(omitted.size()) + (omitted.size() == 1 ? " point" : " points") +
         " not drawn: a zero or negative value cannot be placed on a log axis: " + list + ".";
}

void write_figure_data(const Figure& figure, const std::string& path) {
  std::ostringstream o;
  if (auto* q = std::get_if<QQContent>(&figure.content)) {
    o << "p,x,y\n";
    for (std::size_t i = 0; i < q->x.size(); ++i)
      o << (i < q->p.size() ? util::full_precision_or_empty(q->p[i]) : "") << ','
        << util::full_precision_or_empty(q->x[i]) << ',' << util::full_precision_or_empty(q->y[i])
        << '\n';
  } else if (auto* b = std::get_if<BihistogramContent>(&figure.content)) {
    o << "bin_lo,bin_hi,upper_count,lower_count,upper_height,lower_height\n";
    for (std::size_t i = 0; i + 1 < b->edges.size(); ++i)
      o << util::full_precision_or_empty(b->edges[i]) << ','
        << util::full_precision_or_empty(b->edges[i + 1]) << ',' << b->upper_count.at(i) << ','
        << b->lower_count.at(i) << ',' << util::full_precision_or_empty(b->upper_height.at(i))
        << ',' << util::full_precision_or_empty(b->lower_height.at(i)) << '\n';
  } else if (auto* bp = std::get_if<BoxPlotContent>(&figure.content)) {
    std::size_t max_n = 1;
    for (const Box& x : bp->boxes) max_n = std::max(max_n, x.n);
    o << "category,series,n,min,lower_whisker,q1,median,q3,upper_whisker,max,n_outliers_low,"
         "n_outliers_high,relative_width\n";
    for (const Box& x : bp->boxes)
      o << util::csv_escape(x.category) << ',' << util::csv_escape(x.series) << ',' << x.n << ','
        << util::full_precision_or_empty(x.min) << ','
        << util::full_precision_or_empty(x.lower_whisker) << ','
        << util::full_precision_or_empty(x.q1) << ',' << util::full_precision_or_empty(x.median)
        << ',' << util::full_precision_or_empty(x.q3) << ','
        << util::full_precision_or_empty(x.upper_whisker) << ','
        << util::full_precision_or_empty(x.max) << ',' << x.n_outliers_low << ','
        << x.n_outliers_high << ',' << util::full_precision_or_empty(double(x.n) / double(max_n))
        << '\n';
  } else if (auto* h = std::get_if<HistogramContent>(&figure.content)) {
    o << "series,bin_lo,bin_hi,count,height\n";
    for (const auto& s : h->series)
      for (std::size_t i = 0; i + 1 < s.edges.size(); ++i)
        o << util::csv_escape(s.name) << ',' << util::full_precision_or_empty(s.edges[i]) << ','
          << util::full_precision_or_empty(s.edges[i + 1]) << ',' << s.counts.at(i) << ','
          << util::full_precision_or_empty(s.heights.at(i)) << '\n';
  } else if (auto* sc = std::get_if<ScatterContent>(&figure.content)) {
    o << "series,label,x,y,x_lo,x_hi,y_lo,y_hi\n";
    const auto at = [](const std::vector<double>& v, std::size_t i) {
      return i < v.size() ? util::full_precision_or_empty(v[i]) : std::string();
    };
    for (const ScatterSeries& s : sc->series)
      for (std::size_t i = 0; i < s.x.size(); ++i)
        o << util::csv_escape(s.name) << ','
          << util::csv_escape(i < s.labels.size() ? s.labels[i] : "") << ','
          << util::full_precision_or_empty(s.x[i]) << ','
          << util::full_precision_or_empty(s.y.at(i)) << ',' << at(s.x_lo, i) << ','
          << at(s.x_hi, i) << ',' << at(s.y_lo, i) << ',' << at(s.y_hi, i) << '\n';
  } else {
    const auto& c = std::get<BarChartContent>(figure.content);
    o << "category,series,value,label\n";
    for (const auto& s : c.series)
      for (std::size_t i = 0; i < c.categories.size(); ++i)
        o << util::csv_escape(c.categories[i]) << ',' << util::csv_escape(s.name) << ','
          << util::full_precision_or_empty(s.values.at(i)) << ','
          << util::csv_escape(i < s.labels.size() ? s.labels[i] : "") << '\n';
  }
  std::ofstream f(path, std::ios::binary);
  f << o.str();
  if (!f) throw util::UserError("cannot write " + path);
}

int display_exponent(double max_abs) {
  if (!(max_abs > 0) || !std::isfinite(max_abs) || max_abs >= 0.1) return 0;
  int e = 0;
  while (max_abs * std::pow(10.0, e) < 0.1 && e < 30) e += 3;
  return e;
}

}  // namespace ra::plots
