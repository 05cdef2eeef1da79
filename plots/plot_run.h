// `renderaudit plot DIR`: every figure of a run, from DIR/analysis/figures.json (written by
// `renderaudit analyze`), DIR/analysis/tally.json (its counts, for the conformance figures) and the
// records (visibility, histograms), drawn with VTK into DIR/figures/:
//
//   ID.png    raster (VTK: vtkWindowToImageFilter -> vtkPNGWriter), 1123 x 794 px
//   ID.pdf    vector (vtkPDFExporter), 1123 x 794 pt
//   ID.csv    the numbers drawn (figure.h, write_figure_data)
//   index.json  the list of figures, in report order, and the figures skipped for lack of data
//
// Figures, per kind of primitive (the paper's section 4):
//   visibility  bar chart of the visibility classes, per platform (Tables 2, 5, 8 as a picture)
//   conformance share of records whose pixel set equals the reference rasterizer's, per view
//               group and platform (all compared records; records where either lit a pixel)
//   boxplot     every metric by view group and platform (Figs. 6, 8, 10, 12)
//   histogram   every metric per platform, the view groups overlaid
//   qq          orientation views of one group (Fig. 4)
//   bihistogram platforms, view groups differing in FOV, first vs last (Figs. 5, 7, 9, 11, 13)
//   speed_error median render time per primitive against median normalised unsigned error
//               (PEnorm, LSEu-norm, TEu-norm), one point per platform x view group, IQR bars,
//               log10 axes (figures.json "speed_error")
// Metric values are shown x 10^k with the k of the paper's tables (analysis/paper_tables.h).
//
// index.json, schema "renderaudit-figure-index", schema_version 1:
//   {"schema", "schema_version", "run_dir", "png_route", "pdf_route", "display",
//    "figures": [{"id", "kind", "section", "title", "caption", "note", "png", "pdf", "csv"
//                 (paths relative to DIR/figures), "layout": {"width", "height", "plot_left",
//                 "plot_right", "plot_top", "plot_bottom", "x_min", "x_max", "y_min", "y_max",
//                 "x_log10", "y_log10" (true: that range is log10 of the values)}}],
//    "skipped": [{"section", "what", "reason"}], "seconds"}
#pragma once

#include <string>
#include <vector>

#include "plots/figure.h"
#include "plots/figure_renderer.h"

namespace ra::plots {

struct PlotOptions {
  std::string run_dir;
  bool progress = false;  // a line per figure on stderr
  unsigned jobs = 0;      // threads reading records; 0: the number of cores
};

struct IndexedFigure {
  std::string id, kind, section, title, caption, note;
  std::string png, pdf, csv;  // paths relative to DIR/figures
};

struct SkippedFigure {
  std::string section, what, reason;
};

struct PlotResult {
  std::string figures_dir;  // DIR/figures
  std::string index_path;   // DIR/figures/index.json
  std::vector<IndexedFigure> figures;
  std::vector<SkippedFigure> skipped;
  std::string display;        // X display used
  bool private_xvfb = false;  // a private Xvfb was started (and stopped)
  double seconds = 0;         // wall-clock, the whole command
};

// The Figures of a run (no drawing): what plot_run() draws. Throws ra::util::UserError when
// DIR/analysis/figures.json or tally.json is missing ("run `renderaudit analyze DIR` first"),
// malformed or of another schema version ("... again").
struct FigurePlan {
  std::vector<Figure> figures;
  std::vector<SkippedFigure> skipped;
};
FigurePlan plan_figures(const std::string& run_dir, unsigned jobs = 0);

// Plans and draws every figure, replacing DIR/figures/. Starts a private Xvfb when there is no
// usable display (headless_display.h).
PlotResult plot_run(const PlotOptions& options);

// Writes result.index_path, DIR/figures/index.json (the schema above), for the figures and skips
// `result` lists, layouts[i] the layout figures[i] was drawn with: the one writer of the figure
// index, for `plot` and for the studies (figure_set.h).
void write_figure_index(const std::string& run_dir, const PlotResult& result,
                        const std::vector<FigureLayout>& layouts);

// Reads DIR/figures/index.json back (for the report). Throws ra::util::UserError when it is missing or
// malformed.
PlotResult read_figure_index(const std::string& run_dir);

}  // namespace ra::plots
