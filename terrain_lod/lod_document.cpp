// The terrain LOD study's document (lod_document.h).
#include "terrain_lod/lod_document.h"

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "rundir/study_dir.h"
#include "stats/table_writer.h"
#include "terrain_lod/lod_table.h"
#include "util/atomic_file.h"
#include "util/errors.h"
#include "util/number_text.h"
#include "util/json_file.h"

namespace ra::lod {
namespace {

using nlohmann::json;

// lod.md: the study's text with its check and speed tables, from lod_summary.json and the rows.
std::string lod_document(const json& sj, const std::vector<TableRow>& rows) {
  // The first column names the row; the others are numbers.
  const auto header = [](const std::vector<std::string>& names) {
    return stats::markdown_header(names, 1);
  };
  const std::string main_lambda = sj.value("lambda", "window");
  const json lam = sj.value("lambda_px_per_rad", json::object());
  const json terrain = sj.value("terrain", json::object());
  std::ostringstream md;
  md << "# Terrain level of detail\n\n"
     << "Longest-edge bisection of a restricted quadtree with saturated (nested) object-space errors "
        "and nested bounding balls (Lindstrom and Pascucci 2001), refined top-down per tile and "
        "drawn as one triangle strip per tile. Terrain: " << terrain.value("source", "") << ", "
     << terrain.value("vertices", json::array()).dump() << " vertices in tiles of "
     << terrain.value("tile_size", 0) << " x " << terrain.value("tile_size", 0) << " (seam errors " << sj.value("seams", "")
     << ", errors " << sj.value("error_propagation", "") << "). Camera: "
     << sj.value("frames", 0) << " frames of a flight, window " << sj.value("window", json::array()).dump()
     << ", vertical field of view " << sj.value("fov_y_deg", 0.0) << " degrees, on `" << sj.value("platform", "")
     << "` (" << sj.value("gl_renderer", "") << "), measured " << sj.value("created_utc", "") << ".\n\n";
  md << "### Checks, every frame\n\n"
     << "For every frame and tau the refined mesh is checked: **conforming** (every edge has a triangle "
        "on each side or lies on the terrain's border, no vertex inside another triangle's edge, areas "
        "sum to the terrain's), **seams** (each tile edge used by the same vertices from both tiles), "
        "and the **measured screen error**: every full-resolution grid vertex and the LOD surface "
        "above it, both projected, their distance in pixels (each error segment clipped to the view "
        "frustum and its visible part measured; segments wholly outside it are left out). A lambda "
        "guarantees tau when the measured maximum stays at or below tau.\n\n"
     << header({"lambda (px/rad)", "tau px", "frames", "conforming", "seams ok", "max screen error px",
                "q90 px", "frames over tau"});
  for (const TableRow& r : rows)
    md << stats::markdown_row({"`" + r.lambda + "` (" + util::format_double_or_empty("%.0f", lam.value(r.lambda, 0.0)) + ")", util::format_double_or_empty("%g", r.tau),
               std::to_string(r.frames), std::to_string(r.conforming), std::to_string(r.seams_ok),
               (r.over_tau ? "**" + util::format_double_or_empty("%.3f", r.max_screen_error) + "**" : util::format_double_or_empty("%.3f", r.max_screen_error)),
               util::format_double_or_empty("%.3f", r.screen_error_q90), std::to_string(r.over_tau)});
  md << "\n`planar` is the paper's lambda = w / (2 tan(phi / 2)) (the focal length in pixels: pixels per "
        "radian on the viewing axis), `spherical` its w / phi, `window` the largest pixels per radian "
        "anywhere in the window, f / cos^2 of the corner angle, with rho = lambda 2 asin(eps / (2 (d - r - eps))) "
        "(the segment's own extent). Only the experiment's lambda (`" << main_lambda
     << "`) is drawn and timed; the others are refined and checked.\n\n";
  md << "### Speed against error (`" << main_lambda << "`)\n\n"
     << header({"tau px", "triangles (median)", "of full %", "indices / triangle", "frame ms (median)",
                "full ms (median)", "speed-up", "image mean abs diff", "pixels differing %"});
  const TableRow* at_one = nullptr;
  for (const TableRow& r : rows) {
    if (!r.timed()) continue;
    if (r.tau == 1) at_one = &r;
    md << stats::markdown_row({util::format_double_or_empty("%g", r.tau), util::format_double_or_empty("%.0f", r.triangles_median), util::format_double_or_empty("%.2f", 100 * r.triangles_median / r.full_triangles),
               util::format_double_or_empty("%.2f", r.indices_per_triangle), util::format_double_or_empty("%.2f", r.frame_ms), util::format_double_or_empty("%.2f", r.full_ms),
               util::format_double_or_empty("%.1f", r.full_ms / r.frame_ms), util::format_double_or_empty("%.3f", r.image_mean_abs), util::format_double_or_empty("%.3f", 100 * r.image_differing)});
  }
  md << "\nFrame time: steady clock around clear + the tiles' strips + glFinish, the median of "
     << sj.value("repetitions", 0) << " repetitions per frame, then the median over frames. Image "
        "difference against the full-resolution rendering of the same frame: mean absolute RGB "
        "difference in levels of 255, and the share of pixels whose largest channel difference "
        "exceeds 16 levels. Full resolution: " << sj.value("full_triangles", 0) << " triangles.\n\n";
  if (at_one) {
    double planar_max = std::nan(""), spherical_max = std::nan("");
    for (const TableRow& r : rows)
      if (r.tau == 1 && r.lambda == "planar") planar_max = r.max_screen_error;
      else if (r.tau == 1 && r.lambda == "spherical") spherical_max = r.max_screen_error;
    md << "### At tau = 1 pixel\n\n"
       << "- LOD triangles (median over frames): **" << util::format_double_or_empty("%.0f", at_one->triangles_median) << "** against "
       << util::format_double_or_empty("%.0f", at_one->full_triangles) << " at full resolution ("
       << util::format_double_or_empty("%.1f", 100 * at_one->triangles_median / at_one->full_triangles) << " %).\n"
       << "- Frame time (median): **" << util::format_double_or_empty("%.2f", at_one->frame_ms) << " ms** against "
       << util::format_double_or_empty("%.2f", at_one->full_ms) << " ms at full resolution.\n"
       << "- Measured maximum screen error over all frames: **" << util::format_double_or_empty("%.3f", at_one->max_screen_error)
       << " px** with lambda `" << main_lambda << "`";
    if (!std::isnan(planar_max)) md << "; " << util::format_double_or_empty("%.3f", planar_max) << " px with the paper's planar lambda";
    if (!std::isnan(spherical_max)) md << "; " << util::format_double_or_empty("%.3f", spherical_max) << " px with its spherical lambda";
    md << ".\n\n";
  }
  return md.str();
}

}  // namespace

void analyze_lod_study(const std::string& dir) {
  const std::optional<rundir::StudyInfo> info = rundir::read_study_info(dir);
  if (!info || info->kind != rundir::StudyKind::kLod)
    throw util::UserError(
        dir +
        " is not a complete LOD run (no study.json of kind lod: run `renderaudit run` "
        "on a [lod] experiment)");
  for (const char* f : {"frames.csv", "lod_summary.json"})
    if (!std::filesystem::exists(dir + "/" + f))
      throw util::UserError(dir + " is not a complete LOD run: " + f + " is missing");
  json sj;
  try {
    sj = util::parse_json_document(util::read_file(dir + "/lod_summary.json"), dir + "/lod_summary.json");
  } catch (const json::exception& e) {
    throw util::UserError(dir + "/lod_summary.json: " + e.what());
  }
  const std::vector<TableRow> rows = rows_of_frames(dir);
  util::write_file_atomic(dir + "/lod_table.csv", lod_table_csv(rows));
  util::write_file_atomic(dir + "/lod.md", lod_document(sj, rows));
  rundir::StudyInfo updated = *info;
  updated.document = "lod.md";
  updated.analysed = true;
  rundir::write_study_info(dir, updated);
}

}  // namespace ra::lod
