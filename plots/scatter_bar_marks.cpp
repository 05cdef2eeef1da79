// The marks of scatter plots (log axes, error bars, labels beside the markers) and bar charts
// (chart_marks.h).
#include "plots/chart_marks.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace ra::plots::chart {

void draw_marks(const ScatterContent& sc, ChartMarks& m) {
  // Values to axis units: log10 on a log axis (NaN: cannot be placed).
  const auto to_x = [&](double v) { return sc.x_log10 ? (v > 0 ? std::log10(v) : NAN) : v; };
  const auto to_y = [&](double v) { return sc.y_log10 ? (v > 0 ? std::log10(v) : NAN) : v; };
  // The range: every drawable marker and bar end.
  double xl = INFINITY, xh = -INFINITY, yl = INFINITY, yh = -INFINITY;
  const auto extend = [](double v, double* l, double* h) {
    if (std::isfinite(v)) *l = std::min(*l, v), *h = std::max(*h, v);
  };
  const auto bar_end = [](const std::vector<double>& v, std::size_t i) {
    return i < v.size() ? v[i] : NAN;
  };
  for (const ScatterSeries& se : sc.series)
    for (std::size_t i = 0; i < se.x.size(); ++i) {
      const double x = to_x(se.x[i]), y = to_y(se.y.at(i));
      if (!std::isfinite(x) || !std::isfinite(y)) continue;
      extend(x, &xl, &xh), extend(y, &yl, &yh);
      extend(to_x(bar_end(se.x_lo, i)), &xl, &xh), extend(to_x(bar_end(se.x_hi, i)), &xl, &xh);
      extend(to_y(bar_end(se.y_lo, i)), &yl, &yh), extend(to_y(bar_end(se.y_hi, i)), &yl, &yh);
    }
  // Padding: 6 % of the range, at least 0.12 decades on a log axis (room for the labels).
  const auto pad_range = [](double* l, double* h, bool log) {
    if (!(*l <= *h)) *l = 0, *h = 1;
    double pad = 0.06 * (*h - *l);
    if (log) pad = std::max(pad, 0.12);
    if (pad <= 0) pad = std::max(0.5, 0.05 * std::fabs(*h));
    *l -= pad, *h += pad;
  };
  pad_range(&xl, &xh, sc.x_log10);
  pad_range(&yl, &yh, sc.y_log10);
  m.x_lo = xl, m.x_hi = xh, m.y_lo = yl, m.y_hi = yh;
  // Marks: every series' IQR bars first, then the markers with their labels on top (a bar of one
  // platform never hides another's marker).
  std::size_t clipped = 0;
  std::vector<vtkSmartPointer<ShapesPlot>> marker_plots;
  for (std::size_t s = 0; s < sc.series.size(); ++s) {
    const ScatterSeries& se = sc.series[s];
    auto bars = vtkSmartPointer<ShapesPlot>::New();
    bars->stroke = palette(s, 200);
    bars->line_width = 2.0f;
    auto pts = vtkSmartPointer<ShapesPlot>::New();
    pts->stroke = palette(s);
    pts->marker_radius = 6.0f;
    pts->label_font = 16;
    pts->vertical_labels_if_crowded = false;
    // A bar between two ends; an end that a log axis cannot place goes to the plot's edge.
    const auto bar = [&](double a, double b, double at, bool along_x) {
      if (std::isnan(a) && std::isnan(b)) return;
      double u = along_x ? to_x(a) : to_y(a), v = along_x ? to_x(b) : to_y(b);
      const double edge = along_x ? m.x_lo : m.y_lo;
      if (std::isnan(u)) u = edge, ++clipped;
      if (std::isnan(v)) v = edge, ++clipped;
      if (along_x)
        bars->lines.push_back({{u, v}, {at, at}});
      else
        bars->lines.push_back({{at, at}, {u, v}});
    };
    for (std::size_t i = 0; i < se.x.size(); ++i) {
      const double x = to_x(se.x[i]), y = to_y(se.y.at(i));
      if (!std::isfinite(x) || !std::isfinite(y)) continue;  // in the note
      bar(bar_end(se.x_lo, i), bar_end(se.x_hi, i), y, true);
      bar(bar_end(se.y_lo, i), bar_end(se.y_hi, i), x, false);
      pts->markers.push_back({x, y});
      if (i < se.labels.size() && !se.labels[i].empty()) {
        ShapesPlot::Label l{x, y, se.labels[i]};
        // upper right of the marker, clear of the horizontal bar through it
        l.dx_px = pts->marker_radius + 2;
        l.dy_px = pts->marker_radius + 5;
        l.beside = true;
        pts->labels.push_back(l);
      }
    }
    m.add_plot(bars);
    marker_plots.push_back(pts);
    m.legend.push_back({se.name, palette(s), LegendItem::kMarker});
  }
  for (auto& pts : marker_plots) m.add_plot(pts);
  m.x_grid_at_ticks = true;
  m.x_log10 = sc.x_log10;
  m.y_log10 = sc.y_log10;
  if (sc.x_log10) log_ticks(m.x_lo, m.x_hi, &m.x_ticks, &m.x_tick_labels);
  if (sc.y_log10) log_ticks(m.y_lo, m.y_hi, &m.y_ticks, &m.y_tick_labels);
  std::string extra = scatter_omitted_note(sc);
  if (clipped)
    extra += std::string(extra.empty() ? "" : "\n") + std::to_string(clipped) +
             (clipped == 1 ? " bar end" : " bar ends") +
             " at zero or below drawn to the edge of the log axis.";
  if (!extra.empty()) m.note = extra + (m.note.empty() ? "" : "\n" + m.note);
}

void draw_marks(const BarChartContent& c, ChartMarks& m) {
  const std::size_t C = std::max<std::size_t>(1, c.categories.size());
  const std::size_t S = std::max<std::size_t>(1, c.series.size());
  const double slot = 0.8 / double(S);
  // On a log axis the bars rise from the floor (log10 units); a value of 0 has its label only.
  const double floor = c.y_log10 ? std::log10(bar_chart_log_floor(c)) : 0;
  const auto to_y = [&](double v) { return c.y_log10 ? (v > 0 ? std::log10(v) : floor) : v; };
  double top = 0;
  bool any_label = false;
  for (std::size_t s = 0; s < c.series.size(); ++s) {
    const BarSeries& se = c.series[s];
    const auto colour = [&](unsigned char alpha) {
      return se.color ? Color{(*se.color)[0], (*se.color)[1], (*se.color)[2], alpha}
                      : palette(s, alpha);
    };
    auto p = vtkSmartPointer<ShapesPlot>::New();
    p->fill = colour(220);
    p->stroke = colour(255);
    p->line_width = 1.0f;
    for (std::size_t i = 0; i < c.categories.size(); ++i) {
      const double v = se.values.at(i);
      const double centre = double(i + 1) + (double(s) - 0.5 * double(S - 1)) * slot;
      if (!c.y_log10 || v > 0)
        p->rects.push_back({centre - 0.45 * slot, centre + 0.45 * slot, floor, to_y(v)});
      top = std::max(top, v);
      if (i < se.labels.size() && !se.labels[i].empty()) {
        p->labels.push_back({centre, c.y_log10 ? to_y(v) : std::max(v, 0.0), se.labels[i]});
        any_label = true;
      }
    }
    m.add_plot(p);
    if (c.series.size() > 1 || !se.name.empty())
      m.legend.push_back({se.name, colour(220), LegendItem::kBox});
  }
  if (c.series.size() == 1 && m.legend.size() == 1) m.legend.clear();
  m.x_lo = 0.5, m.x_hi = double(C) + 0.5;
  m.x_categories = true;
  for (std::size_t i = 0; i < c.categories.size(); ++i) {
    m.x_ticks.push_back(double(i + 1));
    m.x_tick_labels.push_back(c.categories[i]);
  }
  const double y_top = c.y_max > 0 ? c.y_max : (top > 0 ? top : 1);
  if (c.y_log10) {
    // room for the labels above the bars: a fifth of the decades shown
    const double hi = std::log10(y_top);
    m.y_lo = floor;
    m.y_hi = hi + (any_label ? 0.22 : 0.05) * (hi - floor);
    m.y_log10 = true;
    m.x_grid_at_ticks = false;
    std::vector<double> at;
    std::vector<std::string> text;
    log_ticks(floor, hi, &at, &text);
    for (std::size_t i = 0; i < at.size(); ++i)
      if (at[i] >= floor - 1e-9 && at[i] <= hi + 1e-9)
        m.y_ticks.push_back(at[i]), m.y_tick_labels.push_back(text[i]);
    return;
  }
  m.y_lo = 0;
  m.y_hi = any_label ? y_top * 1.22 : y_top * 1.05;  // room for the labels above the bars
  // Ticks only up to the top of the scale (no "120 %").
  const double step = nice_step(y_top, 8);
  for (double t = 0; t <= y_top * (1 + 1e-9); t += step) {
    m.y_ticks.push_back(t);
    m.y_tick_labels.push_back(tick_text(t, step));
  }
}

}  // namespace ra::plots::chart
