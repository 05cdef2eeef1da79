// The VTK items every figure is drawn with (internal to plots/): ShapesPlot (rectangles,
// polylines, markers and labels in data units, drawn in screen space), TextItem (lines of text at
// a screen position), LegendItem (rows of swatches and names), the palette, the fonts' sizes and
// the tick helpers. figure_renderer.cpp lays them out; *_marks.cpp fill them per kind of figure.
#pragma once

#include <vtkContextItem.h>
#include <vtkPen.h>
#include <vtkPlot.h>
#include <vtkTextProperty.h>

#include <array>
#include <cstddef>
#include <string>
#include <vector>

class vtkContext2D;

namespace ra::plots::chart {

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

// Colour i of the palette; beyond its 8: hues stepped by the golden ratio (never the same twice),
// alternating two lightnesses, so that a history of many platforms, kinds and groups stays legible.
Color palette(std::size_t i, unsigned char alpha = 255);
// Arial (Helvetica in the PDF), black, upright, no shadow.
void style_text(vtkTextProperty* p, int size, bool bold = false);
// Width in pixels of a line of text as VTK's FreeType renderer lays it out (the PDF's Helvetica
// has the same metrics as the PNG's Arial).
float text_width(const std::string& text, int size, bool bold = false);
// Splits text (lines separated by \n) into lines of at most `max_px` pixels, at spaces.
std::vector<std::string> wrap_px(const std::string& text, float max_px, int size, bool bold = false);

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

  bool Paint(vtkContext2D* painter) override;

  void GetBounds(double b[4]) override;
};

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

  bool Paint(vtkContext2D* painter) override;
};

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

  static float entry_width(const Entry& e);

  // Greedy rows no wider than max_px.
  static std::vector<std::vector<Entry>> layout(const std::vector<Entry>& entries, float max_px);

  bool Paint(vtkContext2D* painter) override;
};

// "Nice" tick step for a range: 1, 2 or 5 x 10^k, about `target` ticks.
double nice_step(double range, int target = 7);
// A tick label of v with as many decimals as the step needs: every tick of an axis alike
// ("0.00", "0.05", "0.10").
std::string tick_text(double v, double step);
// Ticks of a linear axis showing [lo, hi], `pixels` long: the multiples of the smallest step of 1,
// 2 or 5 x 10^k that keeps them at least `spacing_px` apart, each labelled by tick_text with the
// step's decimals.
void linear_ticks(double lo, double hi, float pixels, float spacing_px, std::vector<double>* at,
                  std::vector<std::string>* text);
// A tick label for 10^k-scale values on a log axis: plain decimals from 0.001 to 10000 ("0.002",
// "1", "50"), "10^k" / "2x10^k" beyond.
std::string log_tick_text(int mantissa, int exponent);
// Ticks of a log10 axis showing [lo, hi] (log10 of display units): every power of ten; with 2 and
// 5 x 10^k as well when the range spans at most 3 decades, and 2, 3, 5 x 10^k up to 1.5 decades,
// so a narrow range still has labelled ticks. Positions in log10 units.
void log_ticks(double lo, double hi, std::vector<double>* at, std::vector<std::string>* text);

}  // namespace ra::plots::chart
