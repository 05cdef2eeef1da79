// The marks of the distribution figures (chart_marks.h): Q-Q plots, bihistograms, box plots and
// histograms.
#include "plots/chart_marks.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <string>

namespace ra::plots::chart {

void draw_marks(const QQContent& q, ChartMarks& m) {
  double lo = INFINITY, hi = -INFINITY;
  for (double v : q.x) lo = std::min(lo, v), hi = std::max(hi, v);
  for (double v : q.y) lo = std::min(lo, v), hi = std::max(hi, v);
  if (!(lo <= hi)) lo = 0, hi = 1;
  double pad = 0.04 * (hi - lo);
  if (pad == 0) pad = std::max(0.5, 0.05 * std::fabs(hi));
  m.x_lo = m.y_lo = lo - pad;
  m.x_hi = m.y_hi = hi + pad;
  m.square = true;
  auto diag = vtkSmartPointer<ShapesPlot>::New();
  diag->lines.push_back({{m.x_lo, m.x_hi}, {m.x_lo, m.x_hi}});
  diag->stroke = {kLineColor[0], kLineColor[1], kLineColor[2], 255};
  diag->line_width = 1.5f;
  auto pts = vtkSmartPointer<ShapesPlot>::New();
  for (std::size_t i = 0; i < q.x.size(); ++i) pts->markers.push_back({q.x[i], q.y[i]});
  pts->stroke = palette(0);
  pts->marker_radius = 4.0f;
  m.add_plot(pts);
  m.add_plot(diag);  // on top, so the line stays visible under dense markers
  m.legend.push_back({"quantiles: " + q.x_sample + " (n = " + std::to_string(q.n_x) + ") vs " +
                        q.y_sample + " (n = " + std::to_string(q.n_y) + ")",
                    palette(0), LegendItem::kMarker});
  m.legend.push_back({"y = x", {kLineColor[0], kLineColor[1], kLineColor[2], 255},
                    LegendItem::kLine});
}

void draw_marks(const BihistogramContent& b, ChartMarks& m) {
  auto up = vtkSmartPointer<ShapesPlot>::New();
  auto down = vtkSmartPointer<ShapesPlot>::New();
  double top = 0, bottom = 0;
  for (std::size_t i = 0; i + 1 < b.edges.size(); ++i) {
    if (b.upper_height[i] > 0)
      up->rects.push_back({b.edges[i], b.edges[i + 1], 0, b.upper_height[i]});
    if (b.lower_height[i] > 0)
      down->rects.push_back({b.edges[i], b.edges[i + 1], -b.lower_height[i], 0});
    top = std::max(top, b.upper_height[i]);
    bottom = std::max(bottom, b.lower_height[i]);
  }
  up->fill = palette(0, 200), up->stroke = palette(0), up->line_width = 1.0f;
  down->fill = palette(1, 200), down->stroke = palette(1), down->line_width = 1.0f;
  m.add_plot(up);
  m.add_plot(down);
  if (!b.edges.empty()) {
    m.x_lo = b.edges.front();
    m.x_hi = b.edges.back();
    const double pad = 0.02 * (m.x_hi - m.x_lo);
    m.x_lo -= pad, m.x_hi += pad;
    auto zero = vtkSmartPointer<ShapesPlot>::New();
    zero->lines.push_back({{m.x_lo, m.x_hi}, {0, 0}});
    zero->stroke = {0, 0, 0, 255};
    zero->line_width = 1.5f;
    m.add_plot(zero);
  }
  if (top == 0) top = 1;
  if (bottom == 0) bottom = 1;
  m.y_hi = top * 1.05, m.y_lo = -bottom * 1.05;
  // Ticks show densities on both sides as positive numbers.
  const double step = nice_step(m.y_hi - m.y_lo, 8);
  for (double t = -std::floor(bottom * 1.05 / step) * step; t <= m.y_hi + 1e-12 * step; t += step) {
    m.y_ticks.push_back(t);
    m.y_tick_labels.push_back(tick_text(std::fabs(t), step));
  }
  m.legend.push_back({"above: " + b.upper_sample + " (n = " + std::to_string(b.n_upper) + ")",
                    palette(0, 200), LegendItem::kBox});
  m.legend.push_back({"below: " + b.lower_sample + " (n = " + std::to_string(b.n_lower) + ")",
                    palette(1, 200), LegendItem::kBox});
}

void draw_marks(const BoxPlotContent& bp, ChartMarks& m) {
  const std::size_t C = std::max<std::size_t>(1, bp.categories.size());
  const std::size_t S = std::max<std::size_t>(1, bp.series.size());
  std::size_t max_n = 1;
  for (const Box& x : bp.boxes) max_n = std::max(max_n, x.n);
  const double slot = 0.8 / double(S);
  std::vector<vtkSmartPointer<ShapesPlot>> body(S), lines(S), med(S), ext(S);
  struct EdgeMarker {
    double centre, max, min;
    std::size_t series;
  };
  std::vector<EdgeMarker> edge_markers;
  for (std::size_t s = 0; s < S; ++s) {
    body[s] = vtkSmartPointer<ShapesPlot>::New();
    body[s]->fill = palette(s, 90);
    body[s]->stroke = palette(s);
    body[s]->line_width = 2.0f;
    lines[s] = vtkSmartPointer<ShapesPlot>::New();
    lines[s]->stroke = palette(s);
    lines[s]->line_width = 2.0f;
    med[s] = vtkSmartPointer<ShapesPlot>::New();
    med[s]->stroke = {0, 0, 0, 255};
    med[s]->line_width = 3.0f;
    ext[s] = vtkSmartPointer<ShapesPlot>::New();
    ext[s]->stroke = palette(s);
    ext[s]->hollow_markers = true;
    ext[s]->marker_radius = 4.5f;
  }
  for (const Box& x : bp.boxes) {
    const auto ci = std::find(bp.categories.begin(), bp.categories.end(), x.category);
    const auto si = std::find(bp.series.begin(), bp.series.end(), x.series);
    const std::size_t c = std::size_t(ci - bp.categories.begin());
    const std::size_t s = si == bp.series.end() ? 0 : std::size_t(si - bp.series.begin());
    const double centre = double(c + 1) + (double(s) - 0.5 * double(S - 1)) * slot;
    const double half = 0.5 * 0.85 * slot * double(x.n) / double(max_n);
    body[s]->rects.push_back({centre - half, centre + half, x.q1, x.q3, 3.0f});
    const double cap = std::max(half * 0.5, 0.02);
    lines[s]->lines.push_back({{centre, centre}, {x.q3, x.upper_whisker}});
    lines[s]->lines.push_back({{centre, centre}, {x.q1, x.lower_whisker}});
    lines[s]->lines.push_back({{centre - cap, centre + cap}, {x.upper_whisker, x.upper_whisker}});
    lines[s]->lines.push_back({{centre - cap, centre + cap}, {x.lower_whisker, x.lower_whisker}});
    med[s]->lines.push_back({{centre - std::max(half, 0.01), centre + std::max(half, 0.01)},
                             {x.median, x.median}});
    if (x.max > x.upper_whisker) ext[s]->markers.push_back({centre, x.max});
    if (x.min < x.lower_whisker) ext[s]->markers.push_back({centre, x.min});
    edge_markers.push_back({centre, x.max, x.min, s});
  }
  for (std::size_t s = 0; s < S; ++s) {
    m.add_plot(body[s]);
    m.add_plot(lines[s]);
    m.add_plot(med[s]);
    m.add_plot(ext[s]);
    if (bp.series.size() > 1)
      m.legend.push_back({bp.series[s], palette(s, 90), LegendItem::kBox});
  }
  box_plot_y_range(bp, &m.y_lo, &m.y_hi);
  // Extremes outside the restricted range: a triangle at the edge of the plot, pointing out.
  for (const EdgeMarker& e : edge_markers) {
    if (!(e.max > m.y_hi) && !(e.min < m.y_lo)) continue;
    auto t = vtkSmartPointer<ShapesPlot>::New();
    t->stroke = palette(e.series);
    t->marker_radius = 7.0f;
    if (e.max > m.y_hi) {
      t->marker_shape = ShapesPlot::kUpTriangle;
      t->markers.push_back({e.centre, m.y_hi});
    } else {
      t->marker_shape = ShapesPlot::kDownTriangle;
      t->markers.push_back({e.centre, m.y_lo});
    }
    m.add_plot(t);
    if (e.max > m.y_hi && e.min < m.y_lo) {
      auto d = vtkSmartPointer<ShapesPlot>::New();
      d->stroke = palette(e.series);
      d->marker_radius = 7.0f;
      d->marker_shape = ShapesPlot::kDownTriangle;
      d->markers.push_back({e.centre, m.y_lo});
      m.add_plot(d);
    }
  }
  const std::string outside = box_plot_outside_note(bp, m.y_lo, m.y_hi);
  if (!outside.empty()) m.note = outside + (m.note.empty() ? "" : "\n" + m.note);
  // The legend of the marks says only what this figure draws (a trend's boxes have no whiskers).
  bool whiskers = false, beyond_whiskers = false, beyond_plot = false;
  for (const Box& x : bp.boxes) {
    whiskers = whiskers || x.lower_whisker < x.q1 || x.upper_whisker > x.q3;
    beyond_whiskers = beyond_whiskers || x.max > x.upper_whisker || x.min < x.lower_whisker;
  }
  for (const EdgeMarker& e : edge_markers) beyond_plot = beyond_plot || e.max > m.y_hi || e.min < m.y_lo;
  std::vector<std::string> parts;
  if (bp.boxes.size() > 1) parts.push_back("box widths proportional to n");
  if (beyond_whiskers)
    parts.push_back("open circles: minimum and maximum beyond the whiskers");
  else if (whiskers)
    parts.push_back("whiskers to the minimum and maximum");
  if (beyond_plot) parts.push_back("triangles at the edge: beyond the plot");
  std::string marks;
  for (const std::string& p : parts) marks += (marks.empty() ? "" : "; ") + p;
  if (!marks.empty()) {
    marks[0] = char(std::toupper(static_cast<unsigned char>(marks[0])));
    m.note += std::string(m.note.empty() ? "" : "\n") + marks + ".";
  }
  m.x_lo = 0.5, m.x_hi = double(C) + 0.5;
  m.x_categories = true;
  for (std::size_t c = 0; c < bp.categories.size(); ++c) {
    m.x_ticks.push_back(double(c + 1));
    m.x_tick_labels.push_back(bp.categories[c]);
  }
}

void draw_marks(const HistogramContent& h, ChartMarks& m) {
  double lo = INFINITY, hi = -INFINITY, top = 0;
  const bool single = h.series.size() == 1;
  for (std::size_t s = 0; s < h.series.size(); ++s) {
    const auto& se = h.series[s];
    auto p = vtkSmartPointer<ShapesPlot>::New();
    if (single) {
      for (std::size_t i = 0; i + 1 < se.edges.size(); ++i)
        if (se.heights[i] > 0) p->rects.push_back({se.edges[i], se.edges[i + 1], 0, se.heights[i]});
      p->fill = palette(s, 200);
      p->stroke = palette(s);
      p->line_width = 1.0f;
    } else {
      ShapesPlot::Polyline l;
      for (std::size_t i = 0; i + 1 < se.edges.size(); ++i) {
        if (i == 0) l.x.push_back(se.edges[0]), l.y.push_back(0);
        l.x.push_back(se.edges[i]), l.y.push_back(se.heights[i]);
        l.x.push_back(se.edges[i + 1]), l.y.push_back(se.heights[i]);
      }
      if (!se.edges.empty()) l.x.push_back(se.edges.back()), l.y.push_back(0);
      p->lines.push_back(l);
      p->stroke = palette(s);
      p->line_width = 2.5f;
      m.legend.push_back({se.name + " (n = " + std::to_string(se.n) + ")", palette(s),
                        LegendItem::kLine});
    }
    for (double e : se.edges) lo = std::min(lo, e), hi = std::max(hi, e);
    for (double v : se.heights) top = std::max(top, v);
    m.add_plot(p);
  }
  if (lo <= hi) {
    const double pad = 0.02 * (hi - lo);
    m.x_lo = lo - pad, m.x_hi = hi + pad;
  }
  m.y_lo = 0, m.y_hi = (top > 0 ? top : 1) * 1.05;
}

}  // namespace ra::plots::chart
