// What drawing one kind of figure decides (internal to plots/): the marks, the legend, the axes'
// ranges and ticks and the note, and draw_marks for each kind of figure content (figure.h):
// distribution_marks.cpp (Q-Q, bihistogram, box plot, histogram), scatter_bar_marks.cpp (scatter,
// bar chart).
#pragma once

#include <vtkChartXY.h>
#include <vtkSmartPointer.h>

#include <cmath>
#include <string>
#include <vector>

#include "plots/chart_items.h"
#include "plots/figure.h"

namespace ra::plots::chart {

// What drawing one kind of figure decides: the marks (added to the chart), the legend, the axis
// ranges and ticks (data units; NaN range: automatic) and the note under the figure.
struct ChartMarks {
  vtkChartXY* chart = nullptr;
  std::vector<LegendItem::Entry> legend;
  double x_lo = NAN, x_hi = NAN, y_lo = NAN, y_hi = NAN;
  bool square = false;           // equal axes (Q-Q plots)
  bool x_grid_at_ticks = false;  // custom x ticks keep their grid lines (log axes)
  // The x ticks name categories (bars, boxes): each label sits under its slot without a tick mark,
  // which would stand between the words of a label ("P|A") and marks no value.
  bool x_categories = false;
  std::vector<double> x_ticks, y_ticks;
  std::vector<std::string> x_tick_labels, y_tick_labels;
  std::string note;  // the figure's note and what the drawing adds to it
  bool x_log10 = false, y_log10 = false;
  void add_plot(vtkSmartPointer<ShapesPlot> p) { chart->AddPlot(p); }
};

void draw_marks(const QQContent& q, ChartMarks& m);
void draw_marks(const BihistogramContent& b, ChartMarks& m);
void draw_marks(const BoxPlotContent& bp, ChartMarks& m);
void draw_marks(const HistogramContent& h, ChartMarks& m);
void draw_marks(const ScatterContent& sc, ChartMarks& m);
void draw_marks(const BarChartContent& c, ChartMarks& m);

}  // namespace ra::plots::chart
