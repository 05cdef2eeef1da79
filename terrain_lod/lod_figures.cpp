// The terrain LOD study's figures (lod_figures.h).
#include "terrain_lod/lod_figures.h"

#include <algorithm>
#include <optional>

#include "plots/figure_set.h"
#include "rundir/study_dir.h"
#include "terrain_lod/lod_table.h"
#include "util/errors.h"
#include "util/number_text.h"

namespace ra::lod {

void plot_lod_study(const std::string& dir) {
  const std::optional<rundir::StudyInfo> info = rundir::read_study_info(dir);
  if (!info || info->kind != rundir::StudyKind::kLod || !info->analysed)
    throw util::UserError(dir + " has not been analysed: run `renderaudit analyze " + dir +
                          "` first");
  const std::vector<TableRow> rows = read_table(dir);
  auto label = [](double tau) { return "tau " + util::format_double_or_empty("%g", tau); };
  plots::StudyFigures figures("lod");
  {  // speed against error
    plots::ScatterContent c;
    plots::ScatterSeries lod, fullres;
    lod.name = "LOD";
    fullres.name = "full resolution";
    for (const TableRow& r : rows)
      if (r.timed()) {
        lod.x.push_back(r.image_mean_abs);
        lod.y.push_back(r.frame_ms);
        lod.labels.push_back(label(r.tau));
        if (fullres.x.empty()) {
          fullres.x.push_back(0);
          fullres.y.push_back(r.full_ms);
          fullres.labels.push_back("full");
        }
      }
    c.series = {lod, fullres};
    figures.add("lod_speed_vs_error", "LOD: frame time against image error, one point per tau",
                "image mean absolute difference vs full resolution (levels of 255)",
                "frame time, median (ms)",
                "The speed-against-error curve of the LOD: median frame time and median image "
                "difference against the full-resolution rendering, one point per tau; the point at "
                "x = 0 is the full-resolution rendering itself.",
                c);
  }
  // One series per lambda (y against tau), then a reference series over the first lambda's taus.
  auto by_lambda = [&rows](double TableRow::*y, const std::string& reference,
                           double TableRow::*reference_y) {
    plots::SeriesInOrder by;
    plots::ScatterSeries ref;
    ref.name = reference;
    for (const TableRow& r : rows) {
      plots::ScatterSeries& s = by["lambda " + r.lambda];
      s.x.push_back(r.tau);
      s.y.push_back(r.*y);
      if (r.lambda == rows.front().lambda) {
        ref.x.push_back(r.tau);
        ref.y.push_back(r.*reference_y);
      }
    }
    plots::ScatterContent c;
    c.series = by.series();
    c.series.push_back(ref);
    return c;
  };
  {  // triangles against tau
    plots::ScatterContent c =
        by_lambda(&TableRow::triangles_median, "full resolution", &TableRow::full_triangles);
    c.x_log10 = c.y_log10 = true;
    figures.add("lod_triangles_vs_tau", "LOD: triangles against the screen-space threshold tau",
                "tau (pixels)", "triangles, median over frames",
                "Median triangle count of the refined mesh per tau and lambda, with the "
                "full-resolution count.",
                c);
  }
  {  // measured screen error against tau
    plots::ScatterContent c = by_lambda(&TableRow::max_screen_error, "y = tau", &TableRow::tau);
    c.x_log10 = true;
    // log y unless a maximum is 0 (a frame set where the LOD equals the full mesh in view), which a
    // log axis cannot show: then a linear y axis
    c.y_log10 = std::all_of(rows.begin(), rows.end(), [](const TableRow& r) { return r.max_screen_error > 0; });
    plots::Figure& f = figures.add(
        "lod_screen_error_vs_tau", "LOD: measured maximum screen error against tau", "tau (pixels)",
        "largest measured screen error over all frames (pixels)",
        "Largest on-screen distance between the full-resolution surface and the LOD surface, "
        "over every frame, per tau and lambda; points above the line y = tau break the "
        "error guarantee.",
        c);
    if (!c.y_log10) f.note = "linear y axis: a measured maximum screen error is 0";
  }
  figures.write(dir);
}

}  // namespace ra::lod
