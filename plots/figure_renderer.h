// Draws a Figure (figure.h) with VTK charts and writes it as PNG and as vector PDF.
//
// - PNG: VTK itself (vtkWindowToImageFilter of the off-screen render window -> vtkPNGWriter).
// - PDF: vtkPDFExporter (libharu), vector: lines, rectangles and text stay vectors. One page per
//   figure, page size = window size in points (default 1123 x 794 pt: A4 landscape at 96 dpi, so a
//   figure printed on A4 is scaled by 0.75: its 17 px tick labels print at 12.75 pt, its 24 px
//   title at 18 pt).
// - Every plotted shape is drawn by this file's own chart item in screen coordinates: VTK 9.1's
//   PDF exporter scales point markers (vtkPlotPoints) by the data transform, which fills the plot
//   area with black; drawing in screen space avoids it and gives the same picture in both files.
//
// Needs an X display (Debian's VTK is X11-only): construct a HeadlessDisplay first. VTK headers
// stay inside the .cpp.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "plots/figure.h"

namespace ra::plots {

// Where a figure was drawn, for checks that read the PNG back: the plot area in PNG pixels
// (x to the right, y downwards from the top row) and the data range it shows; on a log10 axis
// (scatter plots) the range is in log10 of display units, and the axis is linear in those.
struct FigureLayout {
  int width = 0, height = 0;            // image size, pixels
  double plot_left = 0, plot_right = 0;  // plot area, pixel columns
  double plot_top = 0, plot_bottom = 0;  // plot area, pixel rows (top < bottom)
  double x_min = 0, x_max = 0;           // data range along x (display units)
  double y_min = 0, y_max = 0;           // data range along y
  bool x_log10 = false, y_log10 = false;  // the axis shows log10 of the values
  // The ticks as drawn: positions in the axis' units (log10 on a log axis) and their labels;
  // x_ticks_visible false: the x labels name categories and have no tick marks.
  std::vector<double> x_ticks, y_ticks;
  std::vector<std::string> x_tick_labels, y_tick_labels;
  bool x_ticks_visible = true;
};

struct RenderedFigure {
  std::string png, pdf, csv;  // paths written
  FigureLayout layout;        // the plot; of a figure of panels, the top panel
  std::vector<FigureLayout> panels;  // each panel's, top to bottom (histogram panels); else empty
  std::string note;  // the note as drawn (the figure's note plus any the renderer adds)
};

class FigureRenderer {
 public:
  // Makes the off-screen render window. Requires a usable X display (HeadlessDisplay); throws
  // ra::util::UserError when OpenGL cannot be used on it.
  explicit FigureRenderer(int width = 1123, int height = 794);
  ~FigureRenderer();
  FigureRenderer(const FigureRenderer&) = delete;
  FigureRenderer& operator=(const FigureRenderer&) = delete;

  // Draws `figure` and writes STEM.png, STEM.pdf and STEM.csv (write_figure_data).
  RenderedFigure render(const Figure& figure, const std::string& stem);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// An RGB image read back from a PNG (vtkPNGReader), rows from the top.
struct RgbImage {
  int width = 0, height = 0;
  std::vector<unsigned char> rgb;  // width * height * 3
  const unsigned char* at(int x, int y) const { return &rgb[(std::size_t(y) * width + x) * 3]; }
};
// Used by tests to read a figure back and check its pixels.
RgbImage read_png(const std::string& path);

// The colour of series i (0-based) in every figure, RGB.
// Used by tests to find a series in a figure read back.
void series_color(std::size_t i, unsigned char rgb[3]);

}  // namespace ra::plots
