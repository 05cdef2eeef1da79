// FigureRenderer: VTK charts (vtkChartXY for the axes, this file's ShapesPlot for every mark),
// PNG through vtkWindowToImageFilter + vtkPNGWriter, vector PDF through vtkPDFExporter.
#include "plots/figure_renderer.h"

#include <vtkAxis.h>
#include <vtkBrush.h>
#include <vtkChart.h>
#include <vtkChartXY.h>
#include <vtkContext2D.h>
#include <vtkContextItem.h>
#include <vtkContextScene.h>
#include <vtkContextView.h>
#include <vtkDoubleArray.h>
#include <vtkImageData.h>
#include <vtkMatrix3x3.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkOutputWindow.h>
#include <vtkPDFExporter.h>
#include <vtkPNGReader.h>
#include <vtkPNGWriter.h>
#include <vtkPen.h>
#include <vtkPlot.h>
#include <vtkRect.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>
#include <vtkStringArray.h>
#include <vtkTextProperty.h>
#include <vtkTextRenderer.h>
#include <vtkTransform2D.h>
#include <vtkWindowToImageFilter.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "util/errors.h"

namespace ra::plots {
namespace {

// Sizes in pixels of the figure window (= points in the PDF).
constexpr int kTitleFont = 24;
constexpr int kAxisTitleFont = 20;
constexpr int kTickFont = 17;
constexpr int kLegendFont = 17;
constexpr int kNoteFont = 15;
constexpr int kBarLabelFont = 13;

// Colour-blind-safe palette (Okabe-Ito), dark enough to print.
constexpr unsigned char kPalette[][3] = {{0, 114, 178},  {230, 159, 0},   {0, 158, 115},
                                         {204, 121, 167}, {86, 180, 233}, {213, 94, 0},
                                         {240, 228, 66},  {0, 0, 0}};
constexpr unsigned char kLineColor[3] = {213, 94, 0};  // the y = x line, the zero line

using Color = std::array<unsigned char, 4>;
// Series beyond the palette's 8 get hues stepped by the golden ratio (never the same twice),
// alternating two lightnesses, so that a history of many platforms, kinds and groups stays legible.
Color palette(std::size_t i, unsigned char alpha = 255) {
  constexpr std::size_t n = sizeof kPalette / sizeof kPalette[0];
  if (i < n) return {kPalette[i][0], kPalette[i][1], kPalette[i][2], alpha};
  const double h = std::fmod(0.07 + 0.6180339887498949 * double(i - n), 1.0) * 6.0;
  const double v = (i - n) % 2 == 0 ? 0.80 : 0.55, s = 0.85;  // HSV value and saturation
  const double c = v * s, x = c * (1 - std::fabs(std::fmod(h, 2.0) - 1)), m0 = v - c;
  double r = 0, g = 0, b = 0;
  switch (int(h)) {
    case 0: r = c, g = x; break;
    case 1: r = x, g = c; break;
    case 2: g = c, b = x; break;
    case 3: g = x, b = c; break;
    case 4: r = x, b = c; break;
    default: r = c, b = x; break;
  }
  auto u8 = [m0](double t) { return static_cast<unsigned char>(std::lround(255 * (t + m0))); };
  return {u8(r), u8(g), u8(b), alpha};
}

void style_text(vtkTextProperty* p, int size, bool bold = false) {
  p->SetFontFamilyToArial();
  p->SetFontSize(size);
  p->SetBold(bold);
  p->SetItalic(false);
  p->SetColor(0, 0, 0);
  p->SetShadow(false);
}

// --- ShapesPlot: rectangles, polylines, markers and labels in data units, drawn in screen space.
class ShapesPlot : public vtkPlot {
 public:
  static ShapesPlot* New();
  vtkTypeMacro(ShapesPlot, vtkPlot);

  struct Rect {
    double x0, x1, y0, y1;
    float min_width_px = 0;  // drawn at least this wide (e.g. a box of small n)
  };
  struct Polyline {
    std::vector<double> x, y;
  };
  struct Label {
    double x, y;
    std::string text;
    float dy_px = 4;     // offset upwards, pixels
    float dx_px = 0;     // offset to the right, pixels
    bool beside = false;  // left-justified and vertically centred at the offset point (scatter)
  };

  std::vector<Rect> rects;
  std::vector<Polyline> lines;
  std::vector<std::array<double, 2>> markers;
  std::vector<Label> labels;
  Color fill{0, 0, 0, 0};
  Color stroke{0, 0, 0, 255};
  float line_width = 1.5f;
  float marker_radius = 3.5f;  // pixels
  bool hollow_markers = false;
  enum Shape { kCircle, kUpTriangle, kDownTriangle };
  Shape marker_shape = kCircle;
  int pen_type = vtkPen::SOLID_LINE;
  bool vertical_labels_if_crowded = true;
  int label_font = kBarLabelFont;

  bool Paint(vtkContext2D* painter) override {
    // The chart's transform maps shifted-and-scaled data to the screen.
    const vtkRectd ss = this->GetShiftScale();
    vtkNew<vtkMatrix3x3> m;
    painter->GetTransform()->GetMatrix(m);
    const double* a = m->GetData();
    auto sx = [&](double x) { return float(a[0] * ((x + ss[0]) * ss[2]) + a[2]); };
    auto sy = [&](double y) { return float(a[4] * ((y + ss[1]) * ss[3]) + a[5]); };

    painter->PushMatrix();
    vtkNew<vtkTransform2D> identity;
    painter->SetTransform(identity);

    vtkPen* pen = painter->GetPen();
    vtkBrush* brush = painter->GetBrush();
    pen->SetColor(stroke[0], stroke[1], stroke[2], stroke[3]);
    pen->SetWidth(line_width);
    pen->SetLineType(pen_type);
    brush->SetColor(fill[0], fill[1], fill[2], fill[3]);

    for (const Rect& r : rects) {
      float x0 = sx(r.x0), x1 = sx(r.x1), y0 = sy(r.y0), y1 = sy(r.y1);
      if (x1 - x0 < r.min_width_px) {
        const float c = 0.5f * (x0 + x1);
        x0 = c - 0.5f * r.min_width_px;
        x1 = c + 0.5f * r.min_width_px;
      }
      if (y1 < y0) std::swap(y0, y1);
      // Fill and outline drawn separately: the outline as a closed polyline is exact in both PNG
      // and PDF.
      pen->SetLineType(vtkPen::NO_PEN);
      painter->DrawRect(x0, y0, x1 - x0, y1 - y0);
      pen->SetLineType(pen_type);
      if (stroke[3] > 0 && line_width > 0) {
        float xs[5] = {x0, x1, x1, x0, x0}, ys[5] = {y0, y0, y1, y1, y0};
        painter->DrawPoly(xs, ys, 5);
      }
    }
    for (const Polyline& l : lines) {
      std::vector<float> xs, ys;
      for (std::size_t i = 0; i < l.x.size(); ++i) {
        xs.push_back(sx(l.x[i]));
        ys.push_back(sy(l.y[i]));
      }
      if (xs.size() >= 2) painter->DrawPoly(xs.data(), ys.data(), int(xs.size()));
    }
    if (!markers.empty()) {
      pen->SetLineType(hollow_markers ? vtkPen::SOLID_LINE : vtkPen::NO_PEN);
      pen->SetWidth(1.5f);
      brush->SetColor(stroke[0], stroke[1], stroke[2], hollow_markers ? 0 : 255);
      // Markers are 16-gons: vtkPDFContextDevice2D fails on DrawEllipse (libharu "page out of
      // range"), polygons come out the same in both files.
      // Triangles: a vertex pointing up (or down), drawn inside the plot below (above) the point.
      const int kSides = marker_shape == kCircle ? 16 : 3;
      float ux[17], uy[17];
      for (int k = 0; k <= kSides; ++k) {
        const double a = marker_shape == kCircle ? 2 * M_PI * k / kSides
                                                  : M_PI / 2 + 2 * M_PI * k / kSides;
        const float sign = marker_shape == kDownTriangle ? -1.f : 1.f;
        const float off = marker_shape == kCircle ? 0.f : -sign * marker_radius * 1.1f;
        ux[k] = marker_radius * float(std::cos(a));
        uy[k] = sign * marker_radius * float(std::sin(a)) + off;
      }
      for (const auto& p : markers) {
        float xs[17], ys[17];
        const float cx = sx(p[0]), cy = sy(p[1]);
        for (int k = 0; k <= kSides; ++k) xs[k] = cx + ux[k], ys[k] = cy + uy[k];
        if (hollow_markers)
          painter->DrawPoly(xs, ys, kSides + 1);
        else
          painter->DrawPolygon(xs, ys, kSides);
      }
    }
    if (!labels.empty()) {
      vtkTextProperty* tp = painter->GetTextProp();
      style_text(tp, label_font);
      // Vertical labels when horizontal ones would touch their neighbours.
      float min_gap = 1e9f;
      for (std::size_t i = 1; i < labels.size(); ++i)
        min_gap = std::min(min_gap, std::fabs(sx(labels[i].x) - sx(labels[i - 1].x)));
      float widest = 0;
      for (const auto& l : labels) {
        float b[4];
        painter->ComputeStringBounds(l.text, b);
        widest = std::max(widest, b[2]);
      }
      const bool vertical = vertical_labels_if_crowded && widest + 4 > min_gap;
      for (const auto& l : labels) {
        style_text(tp, label_font);
        if (l.beside) {
          tp->SetOrientation(0);
          tp->SetJustificationToLeft();
          tp->SetVerticalJustificationToCentered();
        } else if (vertical) {
          tp->SetOrientation(90);
          tp->SetJustificationToLeft();
          tp->SetVerticalJustificationToCentered();
        } else {
          tp->SetOrientation(0);
          tp->SetJustificationToCentered();
          tp->SetVerticalJustificationToBottom();
        }
        painter->DrawString(sx(l.x) + l.dx_px, sy(l.y) + l.dy_px, l.text);
      }
      tp->SetOrientation(0);
    }
    painter->PopMatrix();
    return true;
  }

  void GetBounds(double b[4]) override {
    b[0] = b[2] = INFINITY;
    b[1] = b[3] = -INFINITY;
    auto add = [&](double x, double y) {
      b[0] = std::min(b[0], x), b[1] = std::max(b[1], x);
      b[2] = std::min(b[2], y), b[3] = std::max(b[3], y);
    };
    for (const Rect& r : rects) add(r.x0, r.y0), add(r.x1, r.y1);
    for (const Polyline& l : lines)
      for (std::size_t i = 0; i < l.x.size(); ++i) add(l.x[i], l.y[i]);
    for (const auto& p : markers) add(p[0], p[1]);
    for (const auto& l : labels) add(l.x, l.y);
    if (!(b[0] <= b[1])) b[0] = 0, b[1] = 1, b[2] = 0, b[3] = 1;
  }
};
vtkStandardNewMacro(ShapesPlot);

// --- TextItem: lines of text at a fixed screen position.
class TextItem : public vtkContextItem {
 public:
  static TextItem* New();
  vtkTypeMacro(TextItem, vtkContextItem);
  std::vector<std::string> lines;
  float x = 0, y = 0;  // anchor of the first line (top), screen pixels
  int size = 16;
  bool bold = false;
  int justification = VTK_TEXT_CENTERED;
  float line_height = 1.35f;
  float rotation = 0;

  bool Paint(vtkContext2D* painter) override {
    vtkTextProperty* tp = painter->GetTextProp();
    for (std::size_t i = 0; i < lines.size(); ++i) {
      style_text(tp, size, bold);
      tp->SetJustification(justification);
      if (rotation != 0)
        tp->SetVerticalJustificationToTop();  // rotated: the text's top faces left, at x
      else
        tp->SetVerticalJustificationToTop();
      tp->SetOrientation(rotation);
      painter->DrawString(x, y - float(i) * size * line_height, lines[i]);
    }
    tp->SetOrientation(0);
    return true;
  }
};
vtkStandardNewMacro(TextItem);

// Width in pixels of a line of text as VTK's FreeType renderer lays it out (the PDF's Helvetica
// has the same metrics as the PNG's Arial).
float text_width(const std::string& text, int size, bool bold = false) {
  vtkNew<vtkTextProperty> tp;
  style_text(tp, size, bold);
  int bb[4] = {0, 0, 0, 0};
  if (!text.empty() && vtkTextRenderer::GetInstance() &&
      vtkTextRenderer::GetInstance()->GetBoundingBox(tp, text, bb, 72))
    return float(bb[1] - bb[0] + 1);
  return 0.6f * float(size) * float(text.size());
}

// Splits text (lines separated by \n) into lines of at most `max_px` pixels, at spaces.
std::vector<std::string> wrap_px(const std::string& text, float max_px, int size, bool bold = false) {
  std::vector<std::string> out;
  std::stringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) {
    std::stringstream ws(line);
    std::string word, cur;
    while (ws >> word) {
      const std::string candidate = cur.empty() ? word : cur + " " + word;
      if (!cur.empty() && text_width(candidate, size, bold) > max_px) {
        out.push_back(cur);
        cur = word;
      } else {
        cur = candidate;
      }
    }
    if (!cur.empty()) out.push_back(cur);
  }
  return out;
}

// --- LegendItem: rows of swatches and names, each row centred at x; the first row at y.
class LegendItem : public vtkContextItem {
 public:
  static LegendItem* New();
  vtkTypeMacro(LegendItem, vtkContextItem);
  enum Style { kBox, kLine, kMarker };
  struct Entry {
    std::string name;
    Color color;
    Style style;
  };
  static constexpr float kSwatch = 28, kGap = 8, kSpacing = 34, kRowHeight = 30;
  std::vector<std::vector<Entry>> rows;
  float x = 0, y = 0;

  static float entry_width(const Entry& e) { return kSwatch + kGap + text_width(e.name, kLegendFont); }

  // Greedy rows no wider than max_px.
  static std::vector<std::vector<Entry>> layout(const std::vector<Entry>& entries, float max_px) {
    std::vector<std::vector<Entry>> rows;
    float w = 0;
    for (const Entry& e : entries) {
      const float ew = entry_width(e);
      if (rows.empty() || (w + kSpacing + ew > max_px && !rows.back().empty())) {
        rows.push_back({});
        w = ew;
      } else {
        w += kSpacing + ew;
      }
      rows.back().push_back(e);
    }
    return rows;
  }

  bool Paint(vtkContext2D* painter) override {
    vtkTextProperty* tp = painter->GetTextProp();
    for (std::size_t r = 0; r < rows.size(); ++r) {
      const float ry = y - float(r) * kRowHeight;
      float total = 0;
      for (const auto& e : rows[r]) total += entry_width(e);
      total += kSpacing * float(rows[r].size() - 1);
      float cx = x - 0.5f * total;
      for (const auto& e : rows[r]) {
        vtkPen* pen = painter->GetPen();
        vtkBrush* brush = painter->GetBrush();
        pen->SetColor(e.color[0], e.color[1], e.color[2], 255);
        pen->SetWidth(2.5f);
        pen->SetLineType(vtkPen::SOLID_LINE);
        brush->SetColor(e.color[0], e.color[1], e.color[2], e.color[3]);
        if (e.style == kBox) {
          painter->DrawRect(cx, ry - 8, kSwatch, 16);
        } else if (e.style == kLine) {
          painter->DrawLine(cx, ry, cx + kSwatch, ry);
        } else {
          pen->SetLineType(vtkPen::NO_PEN);
          brush->SetColor(e.color[0], e.color[1], e.color[2], 255);
          float xs[16], ys[16];
          for (int k = 0; k < 16; ++k) {
            xs[k] = cx + kSwatch / 2 + 5.5f * float(std::cos(2 * M_PI * k / 16));
            ys[k] = ry + 5.5f * float(std::sin(2 * M_PI * k / 16));
          }
          painter->DrawPolygon(xs, ys, 16);
        }
        style_text(tp, kLegendFont);
        tp->SetJustificationToLeft();
        tp->SetVerticalJustificationToCentered();
        painter->DrawString(cx + kSwatch + kGap, ry, e.name);
        cx += entry_width(e) + kSpacing;
      }
    }
    return true;
  }
};
vtkStandardNewMacro(LegendItem);

// "Nice" tick step for a range: 1, 2 or 5 x 10^k, about `target` ticks.
double nice_step(double range, int target = 7) {
  if (!(range > 0)) return 1;
  const double raw = range / target;
  const double p = std::pow(10.0, std::floor(std::log10(raw)));
  const double f = raw / p;
  return (f < 1.5 ? 1 : f < 3.5 ? 2 : f < 7.5 ? 5 : 10) * p;
}

std::string tick_text(double v, double step) {
  if (std::fabs(v) < step * 1e-9) v = 0;
  char buf[32];
  const int decimals = std::max(0, int(std::ceil(-std::log10(step) - 1e-9)));
  std::snprintf(buf, sizeof buf, "%.*f", std::min(decimals, 12), v);
  return buf;
}

// A tick label for 10^k-scale values on a log axis: plain decimals from 0.001 to 10000 ("0.002",
// "1", "50"), "10^k" / "2x10^k" beyond.
std::string log_tick_text(int mantissa, int exponent) {
  char buf[40];
  if (exponent >= -3 && exponent <= 4) {
    std::snprintf(buf, sizeof buf, "%.*f", std::max(0, -exponent),
                  mantissa * std::pow(10.0, exponent));
  } else if (mantissa == 1) {
    std::snprintf(buf, sizeof buf, "10^%d", exponent);
  } else {
    std::snprintf(buf, sizeof buf, "%dx10^%d", mantissa, exponent);
  }
  return buf;
}

// Ticks of a log10 axis showing [lo, hi] (log10 of display units): every power of ten; with 2 and
// 5 x 10^k as well when the range spans at most 3 decades, and 2, 3, 5 x 10^k up to 1.5 decades,
// so a narrow range still has labelled ticks. Positions in log10 units.
void log_ticks(double lo, double hi, std::vector<double>* at, std::vector<std::string>* text) {
  const double span = hi - lo;
  std::vector<int> mantissas = {1};
  if (span <= 1.5)
    mantissas = {1, 2, 3, 5};
  else if (span <= 3.2)
    mantissas = {1, 2, 5};
  for (int k = int(std::floor(lo)) - 1; k <= int(std::ceil(hi)); ++k)
    for (int m : mantissas) {
      const double v = k + std::log10(double(m));
      if (v < lo - 1e-9 || v > hi + 1e-9) continue;
      at->push_back(v);
      text->push_back(log_tick_text(m, k));
    }
}

}  // namespace

void series_color(std::size_t i, unsigned char rgb[3]) {
  const Color c = palette(i);
  rgb[0] = c[0], rgb[1] = c[1], rgb[2] = c[2];
}

struct FigureRenderer::Impl {
  vtkSmartPointer<vtkContextView> view;
  int width = 0, height = 0;
};

namespace {

// What drawing one kind of figure decides: the marks (added to the chart), the legend, the axis
// ranges and ticks (data units; NaN range: automatic) and the note under the figure.
struct ChartMarks {
  vtkChartXY* chart = nullptr;
  std::vector<LegendItem::Entry> legend;
  double x_lo = NAN, x_hi = NAN, y_lo = NAN, y_hi = NAN;
  bool square = false;           // equal axes (Q-Q plots)
  bool x_grid_at_ticks = false;  // custom x ticks keep their grid lines (log axes)
  std::vector<double> x_ticks, y_ticks;
  std::vector<std::string> x_tick_labels, y_tick_labels;
  std::string note;  // the figure's note and what the drawing adds to it
  bool x_log10 = false, y_log10 = false;
  void add_plot(vtkSmartPointer<ShapesPlot> p) { chart->AddPlot(p); }
};

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
  std::string marks = "Box widths proportional to n";
  if (beyond_whiskers) marks += "; open circles: minimum and maximum beyond the whiskers";
  else if (whiskers) marks += "; whiskers to the minimum and maximum";
  if (beyond_plot) marks += "; triangles at the edge: beyond the plot";
  m.note += std::string(m.note.empty() ? "" : "\n") + marks + ".";
  m.x_lo = 0.5, m.x_hi = double(C) + 0.5;
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
  double top = 0;
  bool any_label = false;
  for (std::size_t s = 0; s < c.series.size(); ++s) {
    auto p = vtkSmartPointer<ShapesPlot>::New();
    p->fill = palette(s, 220);
    p->stroke = palette(s);
    p->line_width = 1.0f;
    for (std::size_t i = 0; i < c.categories.size(); ++i) {
      const double v = c.series[s].values.at(i);
      const double centre = double(i + 1) + (double(s) - 0.5 * double(S - 1)) * slot;
      p->rects.push_back({centre - 0.45 * slot, centre + 0.45 * slot, 0, v});
      top = std::max(top, v);
      if (i < c.series[s].labels.size() && !c.series[s].labels[i].empty()) {
        p->labels.push_back({centre, std::max(v, 0.0), c.series[s].labels[i]});
        any_label = true;
      }
    }
    m.add_plot(p);
    if (c.series.size() > 1 || !c.series[s].name.empty())
      m.legend.push_back({c.series[s].name, palette(s, 220), LegendItem::kBox});
  }
  if (c.series.size() == 1 && m.legend.size() == 1) m.legend.clear();
  m.x_lo = 0.5, m.x_hi = double(C) + 0.5;
  for (std::size_t i = 0; i < c.categories.size(); ++i) {
    m.x_ticks.push_back(double(i + 1));
    m.x_tick_labels.push_back(c.categories[i]);
  }
  m.y_lo = 0;
  const double y_top = c.y_max > 0 ? c.y_max : (top > 0 ? top : 1);
  m.y_hi = any_label ? y_top * 1.22 : y_top * 1.05;  // room for the labels above the bars
  // Ticks only up to the top of the scale (no "120 %").
  const double step = nice_step(y_top, 8);
  for (double t = 0; t <= y_top * (1 + 1e-9); t += step) {
    m.y_ticks.push_back(t);
    m.y_tick_labels.push_back(tick_text(t, step));
  }
}


// An empty chart in the report's style: white, no legend or title of its own (this file draws
// them), black axes with light grid lines.
vtkSmartPointer<vtkChartXY> new_chart() {
  auto chart = vtkSmartPointer<vtkChartXY>::New();
  chart->SetShowLegend(false);
  chart->SetTitle("");
  chart->GetBackgroundBrush()->SetColor(255, 255, 255, 255);
  chart->SetRenderEmpty(true);
  vtkAxis* xa = chart->GetAxis(vtkAxis::BOTTOM);
  vtkAxis* ya = chart->GetAxis(vtkAxis::LEFT);
  for (vtkAxis* ax : {xa, ya}) {
    style_text(ax->GetTitleProperties(), kAxisTitleFont, true);
    style_text(ax->GetLabelProperties(), kTickFont);
    ax->GetGridPen()->SetColor(225, 225, 225, 255);
    ax->GetPen()->SetColor(0, 0, 0, 255);
    ax->GetPen()->SetWidth(1.5f);
  }
  // Axis titles are this file's TextItems (placed below the tick labels with a fixed gap; VTK's
  // own put the x title against the labels).
  xa->SetTitle("");
  ya->SetTitle("");
  return chart;
}

// The ranges and ticks the figure's drawing chose, on VTK's axes.
void fix_axes(const ChartMarks& marks, vtkAxis* xa, vtkAxis* ya) {
  auto apply_range = [](vtkAxis* ax, double lo, double hi) {
    if (std::isnan(lo)) return;
    ax->SetBehavior(vtkAxis::FIXED);
    ax->SetUnscaledRange(lo, hi);
    ax->SetRange(lo, hi);
  };
  apply_range(xa, marks.x_lo, marks.x_hi);
  apply_range(ya, marks.y_lo, marks.y_hi);
  auto custom_ticks = [](vtkAxis* ax, const std::vector<double>& at,
                         const std::vector<std::string>& text) {
    if (at.empty()) return;
    vtkNew<vtkDoubleArray> pos;
    vtkNew<vtkStringArray> lab;
    for (std::size_t i = 0; i < at.size(); ++i) {
      pos->InsertNextValue(at[i]);
      lab->InsertNextValue(text[i]);
    }
    ax->SetCustomTickPositions(pos, lab);
  };
  custom_ticks(xa, marks.x_ticks, marks.x_tick_labels);
  custom_ticks(ya, marks.y_ticks, marks.y_tick_labels);
  if (!marks.x_ticks.empty() && !marks.x_grid_at_ticks) xa->SetGridVisible(false);
}

// STEM.png (the window as rendered), STEM.pdf (the same scene, vector) and STEM.csv (the data).
void write_figure_files(vtkRenderWindow* win, const Figure& figure, const std::string& stem,
                        RenderedFigure* out) {
  const std::filesystem::path dir = std::filesystem::path(stem).parent_path();
  if (!dir.empty()) std::filesystem::create_directories(dir);
  out->png = stem + ".png";
  out->pdf = stem + ".pdf";
  out->csv = stem + ".csv";

  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(win);
  grab->SetInputBufferTypeToRGB();
  grab->ReadFrontBufferOff();
  grab->ShouldRerenderOff();  // the frame just rendered
  grab->Update();
  vtkNew<vtkPNGWriter> png;
  png->SetFileName(out->png.c_str());
  png->SetInputConnection(grab->GetOutputPort());
  png->Write();

  vtkNew<vtkPDFExporter> pdf;
  pdf->SetRenderWindow(win);
  pdf->SetFileName(out->pdf.c_str());
  pdf->SetTitle(figure.title.c_str());
  pdf->Write();

  write_figure_data(figure, out->csv);
  if (!std::filesystem::exists(out->png) || !std::filesystem::exists(out->pdf))
    throw util::UserError("VTK did not write " + out->png + " / " + out->pdf);
}

}  // namespace

FigureRenderer::FigureRenderer(int width, int height) : impl_(new Impl) {
  impl_->width = width;
  impl_->height = height;
  impl_->view = vtkSmartPointer<vtkContextView>::New();
  vtkRenderWindow* win = impl_->view->GetRenderWindow();
  win->SetOffScreenRendering(1);
  win->SetSize(width, height);
  // No multisampling: llvmpipe under Xvfb takes 4x longer with it; the PDF is the print version.
  win->SetMultiSamples(0);
  impl_->view->GetRenderer()->SetBackground(1, 1, 1);
  if (!win->SupportsOpenGL())
    throw util::UserError(
        "VTK cannot create an OpenGL context on display " +
        std::string(std::getenv("DISPLAY") ? std::getenv("DISPLAY") : "(none)") +
        ": install Mesa's GLX (apt-get install libgl1-mesa-dri libglx-mesa0) or use another "
        "display");
}

FigureRenderer::~FigureRenderer() = default;

RenderedFigure FigureRenderer::render(const Figure& figure, const std::string& stem) {
  const float W = float(impl_->width), H = float(impl_->height);
  vtkContextScene* scene = impl_->view->GetScene();
  scene->ClearItems();

  RenderedFigure out;
  vtkSmartPointer<vtkChartXY> chart = new_chart();
  vtkAxis* xa = chart->GetAxis(vtkAxis::BOTTOM);
  vtkAxis* ya = chart->GetAxis(vtkAxis::LEFT);

  ChartMarks marks;
  marks.chart = chart;
  marks.note = figure.note;
  std::visit([&](const auto& content) { draw_marks(content, marks); }, figure.content);
  out.note = marks.note;
  out.layout.x_log10 = marks.x_log10;
  out.layout.y_log10 = marks.y_log10;

  // Layout (VTK screen coordinates: y up). From the top: title, plot; from the bottom: note,
  // marks.legend, x-axis title and tick labels.
  int title_size = kTitleFont;
  std::vector<std::string> title_lines = {figure.title};
  while (title_size > 18 && text_width(figure.title, title_size, true) > W - 40) --title_size;
  if (text_width(figure.title, title_size, true) > W - 40)
    title_lines = wrap_px(figure.title, W - 40, title_size, true);
  const float title_line_h = float(title_size) * 1.3f;
  const float title_h = 24 + float(title_lines.size()) * title_line_h;
  const std::vector<std::string> note_lines = wrap_px(out.note, W - 48, kNoteFont);
  const auto legend_rows = LegendItem::layout(marks.legend, W - 60);
  const float legend_h = legend_rows.empty() ? 0.f : float(legend_rows.size()) * LegendItem::kRowHeight + 6;
  const float note_h = note_lines.empty() ? 0.f : float(note_lines.size()) * kNoteFont * 1.35f + 8;
  const float axis_h = 78;  // tick labels and the x-axis title
  const float bottom = axis_h + legend_h + note_h;
  const float left = 118, right = 36;
  float plot_w = W - left - right, plot_h = H - title_h - bottom;
  float plot_x = left;
  if (marks.square) {
    const float side = std::min(plot_w, plot_h);
    plot_x = left + 0.5f * (plot_w - side);
    plot_w = plot_h = side;
  }
  chart->SetLayoutStrategy(vtkChart::AXES_TO_RECT);
  chart->SetSize(vtkRectf(plot_x, bottom, plot_w, plot_h));

  fix_axes(marks, xa, ya);
  scene->AddItem(chart);

  // Title: shrunk to fit the width (down to 18 px), wrapped when still too long.
  auto title = vtkSmartPointer<TextItem>::New();
  title->size = title_size;
  title->bold = true;
  title->lines = title_lines;
  title->line_height = 1.3f;
  title->x = 0.5f * W;
  title->y = H - 14;
  scene->AddItem(title);

  auto x_title = vtkSmartPointer<TextItem>::New();
  x_title->lines = {figure.x_label};
  x_title->size = kAxisTitleFont;
  x_title->bold = true;
  x_title->x = plot_x + 0.5f * plot_w;
  x_title->y = bottom - 42;
  scene->AddItem(x_title);
  auto y_title = vtkSmartPointer<TextItem>::New();
  y_title->lines = {figure.y_label};
  y_title->size = kAxisTitleFont;
  y_title->bold = true;
  y_title->rotation = 90;
  y_title->x = plot_x - 96;  // left of tick labels up to ~70 px wide
  y_title->y = bottom + 0.5f * plot_h;
  scene->AddItem(y_title);

  if (!legend_rows.empty()) {
    auto li = vtkSmartPointer<LegendItem>::New();
    li->rows = legend_rows;
    li->x = plot_x + 0.5f * plot_w;
    li->y = note_h + legend_h - 0.5f * LegendItem::kRowHeight;
    scene->AddItem(li);
  }
  if (!note_lines.empty()) {
    auto ni = vtkSmartPointer<TextItem>::New();
    ni->lines = note_lines;
    ni->size = kNoteFont;
    ni->justification = VTK_TEXT_LEFT;
    ni->x = 24;
    ni->y = note_h - 4;
    scene->AddItem(ni);
  }

  vtkRenderWindow* win = impl_->view->GetRenderWindow();
  win->Render();

  write_figure_files(win, figure, stem, &out);

  // Where the plot area ended up, in PNG pixels (rows from the top).
  const vtkVector2f p1 = xa->GetPosition1(), p2 = xa->GetPosition2();
  const vtkVector2f q1 = ya->GetPosition1(), q2 = ya->GetPosition2();
  out.layout.width = impl_->width;
  out.layout.height = impl_->height;
  out.layout.plot_left = p1.GetX();
  out.layout.plot_right = p2.GetX();
  out.layout.plot_bottom = H - q1.GetY();
  out.layout.plot_top = H - q2.GetY();
  out.layout.x_min = xa->GetMinimum();
  out.layout.x_max = xa->GetMaximum();
  out.layout.y_min = ya->GetMinimum();
  out.layout.y_max = ya->GetMaximum();
  return out;
}

RgbImage read_png(const std::string& path) {
  if (!std::filesystem::exists(path)) throw util::UserError("no such PNG: " + path);
  vtkNew<vtkPNGReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkImageData* img = reader->GetOutput();
  int dims[3];
  img->GetDimensions(dims);
  const int comps = img->GetNumberOfScalarComponents();
  RgbImage out;
  out.width = dims[0];
  out.height = dims[1];
  out.rgb.resize(std::size_t(dims[0]) * dims[1] * 3);
  for (int y = 0; y < dims[1]; ++y)
    for (int x = 0; x < dims[0]; ++x) {
      // VTK images have row 0 at the bottom.
      auto* src = static_cast<unsigned char*>(img->GetScalarPointer(x, dims[1] - 1 - y, 0));
      for (int c = 0; c < 3; ++c) out.rgb[(std::size_t(y) * dims[0] + x) * 3 + c] = src[std::min(c, comps - 1)];
    }
  return out;
}

}  // namespace ra::plots
