// The terrain LOD study's tables between its steps: frames.csv, which the run writes (lod_run.h)
// and analyze reads, and lod_table.csv, one row per (lambda, tau), which analyze writes
// (lod_document.h) and plot reads (lod_figures.h).
#pragma once

#include <cmath>
#include <string>
#include <vector>

namespace ra::lod {

// frames.csv columns, fixed: analyze rejects a file whose header differs.
inline constexpr char kFramesHeader[] =
    "lambda,tau_px,frame,triangles,vertices,strip_indices,conforming,seams_ok,max_screen_error_px,"
    "screen_checked,screen_excluded,worst_x_px,worst_y_px,frame_us_median,frame_us_repetitions,"
    "full_triangles,full_us_median,image_mean_abs,image_differing,screen_partially_visible,screen_holes";

// One (lambda, tau) row of lod_table.csv.
struct TableRow {
  std::string lambda;
  double tau = 0;
  int frames = 0;
  double triangles_median = 0, triangles_max = 0, vertices_median = 0, indices_per_triangle = 0;
  double frame_ms = std::nan(""), full_ms = std::nan(""), full_triangles = 0;
  double image_mean_abs = std::nan(""), image_differing = std::nan("");
  double max_screen_error = 0, screen_error_q90 = 0;
  int conforming = 0, seams_ok = 0, over_tau = 0;
  bool timed() const { return !std::isnan(frame_ms); }
};

// frames.csv of the run in `dir`, one row per (lambda, tau) in the order of the file: medians over
// the frames, the q90 and maximum of the measured screen error, the checks' counts. Throws
// UserError for a file this version did not write or one without rows.
std::vector<TableRow> rows_of_frames(const std::string& dir);

// lod_table.csv's text: its header, then `rows`.
std::string lod_table_csv(const std::vector<TableRow>& rows);

// DIR/lod_table.csv read back. Throws UserError when it is missing or not of this version.
std::vector<TableRow> read_table(const std::string& dir);


}  // namespace ra::lod
