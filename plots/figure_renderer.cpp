// FigureRenderer: VTK charts (vtkChartXY for the axes, this file's ShapesPlot for every mark),
// PNG through vtkWindowToImageFilter + vtkPNGWriter, vector PDF through vtkPDFExporter.
// The marks of each kind of figure: chart_marks.h; the VTK items: chart_items.h.
#include "plots/figure_renderer.h"

#include <vtkAxis.h>
#include <vtkBrush.h>
#include <vtkChart.h>
#include <vtkChartXY.h>
#include <vtkContextScene.h>
#include <vtkContextView.h>
#include <vtkDoubleArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPDFExporter.h>
#include <vtkPNGReader.h>
#include <vtkPNGWriter.h>
#include <vtkPen.h>
#include <vtkRect.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>
#include <vtkStringArray.h>
#include <vtkTextProperty.h>
#include <vtkWindowToImageFilter.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "plots/chart_items.h"
#include "plots/chart_marks.h"
#include "util/errors.h"

namespace ra::plots {

using namespace chart;

void series_color(std::size_t i, unsigned char rgb[3]) {
  const Color c = palette(i);
  rgb[0] = c[0], rgb[1] = c[1], rgb[2] = c[2];
}

struct FigureRenderer::Impl {
  vtkSmartPointer<vtkContextView> view;
  int width = 0, height = 0;
};

namespace {

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

// Every tick mark is kTickLength px long and its label starts kTickLabelGap px beyond its end, so
// that no tick reaches into a label (VTK's 5 and 7 left 1 px: "35-" read as one word).
constexpr float kTickLength = 5, kTickLabelGap = 6;
// Automatic ticks of a linear axis: at least this many pixels apart (x labels are wider).
constexpr float kXTickSpacing = 80, kYTickSpacing = 36;

// The ranges and ticks the figure's drawing chose, on VTK's axes of w x h pixels. A linear axis
// without ticks of its own gets them here (linear_ticks), never VTK's: VTK labels 0.1 beside 0.12,
// one label with the decimals of the step for every tick of the axis reads as one scale.
void fix_axes(const ChartMarks& marks, vtkAxis* xa, vtkAxis* ya, float w, float h) {
  auto apply_range = [](vtkAxis* ax, double lo, double hi) {
    if (std::isnan(lo)) return;
    ax->SetBehavior(vtkAxis::FIXED);
    ax->SetUnscaledRange(lo, hi);
    ax->SetRange(lo, hi);
  };
  apply_range(xa, marks.x_lo, marks.x_hi);
  apply_range(ya, marks.y_lo, marks.y_hi);
  auto ticks = [](vtkAxis* ax, std::vector<double> at, std::vector<std::string> text, double lo,
                  double hi, bool log, float pixels, float spacing) {
    ax->SetTickLength(kTickLength);
    ax->SetLabelOffset(kTickLength + kTickLabelGap);
    if (at.empty() && !log && !std::isnan(lo)) linear_ticks(lo, hi, pixels, spacing, &at, &text);
    if (at.empty()) return;
    vtkNew<vtkDoubleArray> pos;
    vtkNew<vtkStringArray> lab;
    for (std::size_t i = 0; i < at.size(); ++i) {
      pos->InsertNextValue(at[i]);
      lab->InsertNextValue(text[i]);
    }
    ax->SetCustomTickPositions(pos, lab);
  };
  ticks(xa, marks.x_ticks, marks.x_tick_labels, marks.x_lo, marks.x_hi, marks.x_log10, w,
        kXTickSpacing);
  // equal axes (Q-Q) get equal ticks
  ticks(ya, marks.y_ticks, marks.y_tick_labels, marks.y_lo, marks.y_hi, marks.y_log10, h,
        marks.square ? kXTickSpacing : kYTickSpacing);
  if (!marks.x_ticks.empty() && !marks.x_grid_at_ticks) xa->SetGridVisible(false);
  if (marks.x_categories) xa->SetTicksVisible(false);
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

namespace {

// The charts a figure is drawn in: one, or one per panel (HistogramContent::panels), top first.
struct Panel {
  vtkSmartPointer<vtkChartXY> chart;
  ChartMarks marks;
  std::string label;  // inside the panel, top left; empty for a single chart
};

std::vector<Panel> draw_panels(const Figure& figure) {
  std::vector<Panel> panels;
  const auto* hist = std::get_if<HistogramContent>(&figure.content);
  if (hist && hist->panels && hist->series.size() > 1) {
    for (std::size_t s = 0; s < hist->series.size(); ++s) {
      const HistogramSeries& se = hist->series[s];
      Panel p;
      p.chart = new_chart();
      p.marks.chart = p.chart;
      HistogramContent one;
      one.density = hist->density;
      one.series = {se};
      draw_marks(one, p.marks);
      // this panel's colour, as the group has in every other figure; room above for the label
      for (vtkIdType i = 0; i < p.chart->GetNumberOfPlots(); ++i)
        if (auto* shapes = ShapesPlot::SafeDownCast(p.chart->GetPlot(i)))
          shapes->fill = palette(s, 200), shapes->stroke = palette(s);
      p.marks.y_hi = p.marks.y_hi / 1.05 * 1.35;
      p.label = se.name + " (n = " + std::to_string(se.n) + ")";
      panels.push_back(std::move(p));
    }
    panels.front().marks.note = figure.note;
    return panels;
  }
  Panel p;
  p.chart = new_chart();
  p.marks.chart = p.chart;
  p.marks.note = figure.note;
  std::visit([&](const auto& content) { draw_marks(content, p.marks); }, figure.content);
  panels.push_back(std::move(p));
  return panels;
}

}  // namespace

RenderedFigure FigureRenderer::render(const Figure& figure, const std::string& stem) {
  const float W = float(impl_->width), H = float(impl_->height);
  vtkContextScene* scene = impl_->view->GetScene();
  scene->ClearItems();

  RenderedFigure out;
  std::vector<Panel> panels = draw_panels(figure);
  const ChartMarks& marks = panels.front().marks;
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
  // Panels stacked from the top, each with its x tick labels in the gap under it.
  const float gap = 34;
  const float n_panels = float(panels.size());
  const float panel_h = (plot_h - (n_panels - 1) * gap) / n_panels;
  for (std::size_t i = 0; i < panels.size(); ++i) {
    Panel& p = panels[i];
    const float y0 = bottom + plot_h - float(i + 1) * panel_h - float(i) * gap;
    p.chart->SetLayoutStrategy(vtkChart::AXES_TO_RECT);
    p.chart->SetSize(vtkRectf(plot_x, y0, plot_w, panel_h));
    fix_axes(p.marks, p.chart->GetAxis(vtkAxis::BOTTOM), p.chart->GetAxis(vtkAxis::LEFT), plot_w,
             panel_h);
    scene->AddItem(p.chart);
    if (!p.label.empty()) {
      auto label = vtkSmartPointer<TextItem>::New();
      label->lines = {p.label};
      label->size = kLegendFont;
      label->bold = true;
      label->justification = VTK_TEXT_LEFT;
      label->x = plot_x + 10;
      label->y = y0 + panel_h - 6;
      scene->AddItem(label);
    }
  }

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

  // Where each plot area ended up, in PNG pixels (rows from the top).
  for (const Panel& p : panels) {
    vtkAxis* xa = p.chart->GetAxis(vtkAxis::BOTTOM);
    vtkAxis* ya = p.chart->GetAxis(vtkAxis::LEFT);
    const vtkVector2f p1 = xa->GetPosition1(), p2 = xa->GetPosition2();
    const vtkVector2f q1 = ya->GetPosition1(), q2 = ya->GetPosition2();
    FigureLayout L = out.layout;
    L.width = impl_->width;
    L.height = impl_->height;
    L.plot_left = p1.GetX();
    L.plot_right = p2.GetX();
    L.plot_bottom = H - q1.GetY();
    L.plot_top = H - q2.GetY();
    L.x_min = xa->GetMinimum();
    L.x_max = xa->GetMaximum();
    L.y_min = ya->GetMinimum();
    L.y_max = ya->GetMaximum();
    L.x_ticks_visible = xa->GetTicksVisible();
    for (vtkAxis* ax : {xa, ya}) {
      std::vector<double>& at = ax == xa ? L.x_ticks : L.y_ticks;
      std::vector<std::string>& text = ax == xa ? L.x_tick_labels : L.y_tick_labels;
      vtkDoubleArray* pos = ax->GetTickPositions();
      vtkStringArray* lab = ax->GetTickLabels();
      for (vtkIdType i = 0; pos && lab && i < pos->GetNumberOfTuples(); ++i) {
        const double v = pos->GetValue(i);
        if (v < ax->GetMinimum() - 1e-9 * std::fabs(ax->GetMaximum() - ax->GetMinimum()) ||
            v > ax->GetMaximum() + 1e-9 * std::fabs(ax->GetMaximum() - ax->GetMinimum()))
          continue;  // VTK draws only the ticks in range
        at.push_back(v);
        text.push_back(i < lab->GetNumberOfValues() ? lab->GetValue(i) : "");
      }
    }
    if (panels.size() > 1) out.panels.push_back(L);
    if (&p == &panels.front()) out.layout = L;
  }
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

