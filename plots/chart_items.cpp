// The VTK items every figure is drawn with; see chart_items.h.
#include "plots/chart_items.h"

#include <vtkBrush.h>
#include <vtkContext2D.h>
#include <vtkMatrix3x3.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkRect.h>
#include <vtkTextRenderer.h>
#include <vtkTransform2D.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "util/number_text.h"

namespace ra::plots::chart {

Color palette(std::size_t i, unsigned char alpha) {
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


void style_text(vtkTextProperty* p, int size, bool bold) {
  p->SetFontFamilyToArial();
  p->SetFontSize(size);
  p->SetBold(bold);
  p->SetItalic(false);
  p->SetColor(0, 0, 0);
  p->SetShadow(false);
}

bool ShapesPlot::Paint(vtkContext2D* painter) {
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

void ShapesPlot::GetBounds(double b[4]) {
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

vtkStandardNewMacro(ShapesPlot);

bool TextItem::Paint(vtkContext2D* painter) {
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

vtkStandardNewMacro(TextItem);

// Width in pixels of a line of text as VTK's FreeType renderer lays it out (the PDF's Helvetica
// has the same metrics as the PNG's Arial).
float text_width(const std::string& text, int size, bool bold) {
  vtkNew<vtkTextProperty> tp;
  style_text(tp, size, bold);
  int bb[4] = {0, 0, 0, 0};
  if (!text.empty() && vtkTextRenderer::GetInstance() &&
      vtkTextRenderer::GetInstance()->GetBoundingBox(tp, text, bb, 72))
    return float(bb[1] - bb[0] + 1);
  return 0.6f * float(size) * float(text.size());
}

// Splits text (lines separated by \n) into lines of at most `max_px` pixels, at spaces.
std::vector<std::string> wrap_px(const std::string& text, float max_px, int size, bool bold) {
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


float LegendItem::entry_width(const Entry& e) { return kSwatch + kGap + text_width(e.name, kLegendFont); }

std::vector<std::vector<LegendItem::Entry>> LegendItem::layout(const std::vector<Entry>& entries,
                                                               float max_px) {
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

bool LegendItem::Paint(vtkContext2D* painter) {
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

vtkStandardNewMacro(LegendItem);

// "Nice" tick step for a range: 1, 2 or 5 x 10^k, about `target` ticks.
double nice_step(double range, int target) {
  if (!(range > 0)) return 1;
  const double raw = range / target;
  const double p = std::pow(10.0, std::floor(std::log10(raw)));
  const double f = raw / p;
  return (f < 1.5 ? 1 : f < 3.5 ? 2 : f < 7.5 ? 5 : 10) * p;
}

std::string tick_text(double v, double step) {
  if (std::fabs(v) < step * 1e-9) v = 0;
  const int decimals = std::max(0, int(std::ceil(-std::log10(step) - 1e-9)));
  return util::fixed(v, std::min(decimals, 12));
}

void linear_ticks(double lo, double hi, float pixels, float spacing_px, std::vector<double>* at,
                  std::vector<std::string>* text) {
  if (!(hi > lo) || !std::isfinite(lo) || !std::isfinite(hi)) return;
  // the smallest step of 1, 2 or 5 x 10^k that keeps the ticks spacing_px apart
  const double least = (hi - lo) * double(spacing_px) / double(std::max(pixels, spacing_px));
  double step = std::pow(10.0, std::floor(std::log10(least)));
  for (const double m : {1.0, 2.0, 5.0, 10.0})
    if (m * step >= least * (1 - 1e-9)) {
      step *= m;
      break;
    }
  // k * step rather than a running sum: no 0.30000000000000004 creeps into a position
  for (double k = std::ceil(lo / step - 1e-9); k * step <= hi + 1e-9 * step; ++k) {
    at->push_back(k * step);
    text->push_back(tick_text(k * step, step));
  }
}

// A tick label for 10^k-scale values on a log axis: plain decimals from 0.001 to 10000 ("0.002",
// "1", "50"), "10^k" / "2x10^k" beyond.
std::string log_tick_text(int mantissa, int exponent) {
  if (exponent >= -3 && exponent <= 4)
    return util::fixed(mantissa * std::pow(10.0, exponent), std::max(0, -exponent));
  const std::string power = "10^" + std::to_string(exponent);
  return mantissa == 1 ? power : std::to_string(mantissa) + "x" + power;
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

}  // namespace ra::plots::chart
