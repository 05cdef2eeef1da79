// The terrain LOD study's tables (lod_table.h).
#include "terrain_lod/lod_table.h"

#include <algorithm>
#include <filesystem>
#include <map>
#include <sstream>
#include <utility>

#include "stats/descriptive.h"
#include "util/atomic_file.h"
#include "util/cell_text.h"
#include "util/errors.h"
#include "util/number_text.h"

namespace ra::lod {
namespace {

double cell_number(const std::string& s) { return s.empty() ? std::nan("") : std::stod(s); }

const char* kTableHeader =
    "lambda,tau_px,frames,triangles_median,triangles_max,vertices_median,indices_per_triangle,"
    "frame_ms_median,full_frame_ms_median,full_triangles,image_mean_abs_median,image_differing_mean,"
    "max_screen_error_px,screen_error_q90_px,frames_conforming,frames_seams_ok,frames_over_tau";

}  // namespace

std::vector<TableRow> rows_of_frames(const std::string& dir) {
  std::istringstream in(util::read_file(dir + "/frames.csv"));
  std::string line;
  std::getline(in, line);
  if (line != kFramesHeader)
    throw util::UserError(dir + "/frames.csv: unexpected header (not written by this version)");
  struct Acc {
    std::vector<double> tri, vert, idx_per_tri, ms, full_ms, mean_abs, differing, err;
    double full_tri = 0;
    int conforming = 0, seams = 0, over = 0;
  };
  std::map<std::pair<std::string, double>, Acc> groups;
  std::vector<std::pair<std::string, double>> order;
  int line_no = 1;
  while (std::getline(in, line)) {
    ++line_no;
    if (line.empty()) continue;
    const auto c = util::split_csv_line(line);
    if (c.size() != 21)
      throw util::UserError(dir + "/frames.csv:" + std::to_string(line_no) + ": " +
                            std::to_string(c.size()) + " fields, not 21");
    const auto key = std::make_pair(c[0], cell_number(c[1]));
    if (!groups.count(key)) order.push_back(key);
    Acc& a = groups[key];
    const double tri = cell_number(c[3]);
    a.tri.push_back(tri);
    a.vert.push_back(cell_number(c[4]));
    a.idx_per_tri.push_back(cell_number(c[5]) / std::max(1.0, tri));
    a.conforming += c[6] == "1";
    a.seams += c[7] == "1";
    const double e = cell_number(c[8]);
    a.err.push_back(e);
    a.over += e > key.second;
    if (!c[13].empty()) {
      a.ms.push_back(cell_number(c[13]) / 1000);
      a.mean_abs.push_back(cell_number(c[17]));
      a.differing.push_back(cell_number(c[18]));
    }
    a.full_tri = cell_number(c[15]);
    a.full_ms.push_back(cell_number(c[16]) / 1000);
  }
  if (groups.empty())
    throw util::UserError(dir + "/frames.csv has no rows: the run did not complete");
  std::vector<TableRow> rows;
  for (const auto& key : order) {
    const Acc& a = groups[key];
    TableRow r;
    r.lambda = key.first;
    r.tau = key.second;
    r.frames = int(a.tri.size());
    r.triangles_median = stats::median_or_nan(a.tri);
    r.triangles_max = *std::max_element(a.tri.begin(), a.tri.end());
    r.vertices_median = stats::median_or_nan(a.vert);
    r.indices_per_triangle = stats::median_or_nan(a.idx_per_tri);
    r.frame_ms = stats::median_or_nan(a.ms);
    r.full_ms = stats::median_or_nan(a.full_ms);
    r.full_triangles = a.full_tri;
    r.image_mean_abs = stats::median_or_nan(a.mean_abs);
    double mean_diff = 0;
    for (double d : a.differing) mean_diff += d / double(a.differing.size());
    r.image_differing = a.differing.empty() ? std::nan("") : mean_diff;
    r.max_screen_error = *std::max_element(a.err.begin(), a.err.end());
    std::vector<double> e = a.err;
    std::sort(e.begin(), e.end());
    r.screen_error_q90 = stats::quantile_sorted(e, 0.9);
    r.conforming = a.conforming;
    r.seams_ok = a.seams;
    r.over_tau = a.over;
    rows.push_back(r);
  }
  return rows;
}

std::string lod_table_csv(const std::vector<TableRow>& rows) {
  std::ostringstream table;
  table << kTableHeader << "\n";
  for (const TableRow& r : rows)
    table << r.lambda << ',' << util::full_precision_or_empty(r.tau) << ',' << r.frames << ','
          << util::full_precision_or_empty(r.triangles_median) << ','
          << util::full_precision_or_empty(r.triangles_max) << ','
          << util::full_precision_or_empty(r.vertices_median) << ','
          << util::full_precision_or_empty(r.indices_per_triangle) << ','
          << util::full_precision_or_empty(r.frame_ms) << ','
          << util::full_precision_or_empty(r.full_ms) << ','
          << util::full_precision_or_empty(r.full_triangles) << ','
          << util::full_precision_or_empty(r.image_mean_abs) << ','
          << util::full_precision_or_empty(r.image_differing) << ','
          << util::full_precision_or_empty(r.max_screen_error) << ','
          << util::full_precision_or_empty(r.screen_error_q90) << ',' << r.conforming << ','
          << r.seams_ok << ',' << r.over_tau << "\n";
  return table.str();
}

std::vector<TableRow> read_table(const std::string& dir) {
  const std::string path = dir + "/lod_table.csv";
  if (!std::filesystem::exists(path))
    throw util::UserError(dir + " has no lod_table.csv: run `renderaudit analyze " + dir +
                          "` first");
  std::istringstream in(util::read_file(path));
  std::string line;
  std::getline(in, line);
  if (line != kTableHeader)
    throw util::UserError(path + ": unexpected header (not written by this version)");
  std::vector<TableRow> rows;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    const auto c = util::split_csv_line(line);
    if (c.size() != 17)
      throw util::UserError(path + ": a row has " + std::to_string(c.size()) + " fields, not 17");
    TableRow r;
    r.lambda = c[0];
    r.tau = cell_number(c[1]);
    r.frames = std::stoi(c[2]);
    r.triangles_median = cell_number(c[3]);
    r.triangles_max = cell_number(c[4]);
    r.vertices_median = cell_number(c[5]);
    r.indices_per_triangle = cell_number(c[6]);
    r.frame_ms = cell_number(c[7]);
    r.full_ms = cell_number(c[8]);
    r.full_triangles = cell_number(c[9]);
    r.image_mean_abs = cell_number(c[10]);
    r.image_differing = cell_number(c[11]);
    r.max_screen_error = cell_number(c[12]);
    r.screen_error_q90 = cell_number(c[13]);
    r.conforming = std::stoi(c[14]);
    r.seams_ok = std::stoi(c[15]);
    r.over_tau = std::stoi(c[16]);
    rows.push_back(r);
  }
  return rows;
}

}  // namespace ra::lod
