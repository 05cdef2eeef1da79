// The terrain LOD study: run, analyze, plot (lod_study.h).
#include "terrain_lod/lod_study.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "platforms/platform_probe.h"
#include "plots/figure_set.h"
#include "rundir/manifest.h"
#include "rundir/run_folder.h"
#include "scenes/camera_path.h"
#include "stats/descriptive.h"
#include "stats/table_writer.h"
#include "terrain_lod/lod_checks.h"
#include "terrain_lod/lod_experiment.h"
#include "terrain_lod/lod_renderer.h"
#include "util/atomic_file.h"
#include "util/cell_text.h"
#include "util/errors.h"
#include "util/gl_child_process.h"
#include "util/number_text.h"

namespace ra::lod {
namespace {

using nlohmann::json;

// frames.csv columns, fixed: analyze rejects a file whose header differs.
const char* kFramesHeader =
    "lambda,tau_px,frame,triangles,vertices,strip_indices,conforming,seams_ok,max_screen_error_px,"
    "screen_checked,screen_excluded,worst_x_px,worst_y_px,frame_us_median,frame_us_repetitions,"
    "full_triangles,full_us_median,image_mean_abs,image_differing,screen_partially_visible,screen_holes";

// A printf format of v, "" for NaN.
std::string fmt(double v, const char* f) {
  return std::isnan(v) ? std::string() : util::format_double(f, v);
}

scenes::Scene layout_scene(const HeightField& f) {
  scenes::Scene s;
  s.kind = "terrain";
  scenes::SceneLayout& l = s.layout;
  l.ground_nx = f.nx;
  l.ground_ny = f.ny;
  l.ground_spacing = f.spacing;
  double zmin = 1e300, zmax = -1e300;
  for (double z : f.z) {
    l.ground_z.push_back(float(z));
    zmin = std::min(zmin, z);
    zmax = std::max(zmax, z);
  }
  l.box_min = {0, 0, zmin};
  l.box_max = {(f.nx - 1) * f.spacing, (f.ny - 1) * f.spacing, zmax};
  return s;
}

double cell_number(const std::string& s) { return s.empty() ? std::nan("") : std::stod(s); }

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

const char* kTableHeader =
    "lambda,tau_px,frames,triangles_median,triangles_max,vertices_median,indices_per_triangle,"
    "frame_ms_median,full_frame_ms_median,full_triangles,image_mean_abs_median,image_differing_mean,"
    "max_screen_error_px,screen_error_q90_px,frames_conforming,frames_seams_ok,frames_over_tau";

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

// The GL part of the run, in a child process (Mesa picks its driver once per process;
// gl_child_process.h): per frame of the path, the full-resolution mesh drawn `repetitions` times,
// then per tau the experiment's own lambda's mesh (refined here as the parent refines it) drawn
// `repetitions` times and its last image compared with the full mesh's. Returns
//   {"gl_renderer", "gl_version",
//    "frames": [{"full_us": [..], "lod": [per tau {"triangles", "us": [..], "image_mean_abs",
//                                                  "image_differing"}]}]}
json draw_frames(const LodSettings& s, const HeightField& field, const TerrainHierarchy& hierarchy,
                 const std::vector<scenes::Viewpoint>& path, const LodMesh& full, bool progress) {
  LodRenderer renderer(s.platform, s.camera, field);
  json frames = json::array();
  for (size_t fi = 0; fi < path.size(); ++fi) {
    const scenes::Viewpoint& vp = path[fi];
    renderer.set_viewpoint(vp);
    renderer.upload(full);
    std::vector<double> full_us;
    for (int r = 0; r < s.repetitions; ++r) full_us.push_back(renderer.draw());
    const std::vector<uint8_t> full_image = renderer.image();
    json lod = json::array();
    for (double tau : s.tau) {
      const LodMesh mesh = refine(hierarchy, make_metric(s.lambda, s.camera, tau, vp.eye));
      renderer.upload(mesh);
      std::vector<double> us;
      for (int r = 0; r < s.repetitions; ++r) us.push_back(renderer.draw());
      const ImageDifference d = image_difference(renderer.image(), full_image);
      lod.push_back({{"triangles", mesh.triangle_count()},
                     {"us", us},
                     {"image_mean_abs", d.mean_abs},
                     {"image_differing", d.differing}});
    }
    frames.push_back({{"full_us", full_us}, {"lod", std::move(lod)}});
    if (progress && (fi % 10 == 0 || fi + 1 == path.size()))
      std::cerr << "lod: drawn frame " << fi + 1 << "/" << path.size() << "\n";
  }
  return {{"gl_renderer", renderer.gl_renderer()}, {"gl_version", renderer.gl_version()},
          {"frames", std::move(frames)}};
}

// The study's folder, emptied of what an earlier run and its analyze / plot stages wrote.
void prepare_output_dir(const std::string& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (!std::filesystem::is_directory(dir))
    throw util::UserError("cannot create the output directory " + dir + ": " + ec.message());
  // a rerun is incomplete until it ends
  std::filesystem::remove(rundir::run_folder::study(dir), ec);
  // and what analyze / plot derived from an earlier run no longer describes this one
  std::filesystem::remove(dir + "/lod_table.csv", ec);
  std::filesystem::remove(dir + "/lod.md", ec);
  std::filesystem::remove_all(rundir::run_folder::figures(dir), ec);
  for (const std::string& f :
       {dir + "/lod_table.csv", dir + "/lod.md", rundir::run_folder::figures(dir)})
    if (std::filesystem::exists(f))
      throw util::UserError("cannot remove the stale " + f + " of an earlier run");
}

// The height field of the experiment: generated, or read from its file and cropped to whole tiles.
HeightField load_terrain(const LodSettings& s) {
  HeightField field = s.height_file.empty()
                          ? generate_height_field(s.terrain, s.tiles_x * (s.tile_size - 1) + 1, s.tiles_y * (s.tile_size - 1) + 1)
                          : crop_to_tiles(read_height_file(s.height_file, s.terrain.spacing, s.terrain.height_scale),
                                          s.tile_size, s.tiles_x, s.tiles_y);
  if (int64_t(field.nx) * field.ny > kMaxTerrainVertices)  // crop_to_tiles caps the tiles; kept as a guard
    throw util::UserError(
        s.height_file + ": cropped to " + std::to_string(field.nx) + " x " +
        std::to_string(field.ny) + " vertices, more than the allowed maximum of " +
        std::to_string(kMaxTerrainVertices) + " (2^24): lower 'lod.tiles' or 'lod.tile_size'");
  return field;
}

// What the frames' checks found, per lambda.
struct FrameChecks {
  std::map<std::string, int> failures;  // lambda -> (frame, tau) with a failed check
  int main_failures = 0;                // of them, with the experiment's own lambda
  std::string first_failure;            // the first of those, described
};

// Every frame and tau refined with every lambda and checked (conformity, seams, screen error <=
// tau); the experiment's lambda with the drawing times and image differences the measuring process
// gave. Writes DIR/frames.csv.
FrameChecks check_frames(const LodSettings& s, const HeightField& field,
                         const TerrainHierarchy& hierarchy,
                         const std::vector<scenes::Viewpoint>& path, const LodMesh& full,
                         const json& drawn_frames, const std::string& dir, bool progress) {
  std::vector<LambdaKind> lambdas = {s.lambda};
  lambdas.insert(lambdas.end(), s.check_lambdas.begin(), s.check_lambdas.end());

  std::ostringstream csv;
  csv << kFramesHeader << "\n";
  FrameChecks out;
  std::map<std::string, int>& failures = out.failures;
  int& main_failures = out.main_failures;
  std::string& first_failure = out.first_failure;
  for (size_t fi = 0; fi < path.size(); ++fi) {
    const scenes::Viewpoint& vp = path[fi];
    const json& drawn_frame = drawn_frames.at(fi);
    const double full_median =
        stats::median_or_nan(drawn_frame.at("full_us").get<std::vector<double>>());
    for (LambdaKind kind : lambdas)
      for (size_t ti = 0; ti < s.tau.size(); ++ti) {
        const double tau = s.tau[ti];
        const LodMesh mesh = refine(hierarchy, make_metric(kind, s.camera, tau, vp.eye));
        const ConformityResult conf = check_conformity(all_triangles(mesh), field.nx, field.ny);
        const SeamResult seams = check_seams(mesh, hierarchy);
        const ScreenErrorResult se = measure_screen_error(lod_surface_heights(mesh, field), field, s.camera, vp);
        const bool ok = conf.conforming && seams.ok && se.max_px <= tau;
        if (!ok) {
          ++failures[lambda_kind_name(kind)];
          if (kind == s.lambda) {
            ++main_failures;
            if (first_failure.empty())
              first_failure = "frame " + std::to_string(fi) + ", tau " + fmt(tau, "%g") + ": " +
                              (!conf.conforming ? conf.first_problem
                               : !seams.ok     ? seams.first_problem
                                               : "measured screen error " + fmt(se.max_px, "%.3g") + " px > tau");
          }
        }
        double med = std::nan(""), mean_abs = std::nan(""), differing = std::nan("");
        std::string reps;
        if (kind == s.lambda) {  // drawn by draw_frames
          const json& drawn_lod = drawn_frame.at("lod").at(ti);
          if (drawn_lod.at("triangles").get<size_t>() != mesh.triangle_count())
            throw std::runtime_error("lod: frame " + std::to_string(fi) + ", tau " + fmt(tau, "%g") +
                                     ": the measuring process drew another mesh");
          const std::vector<double> us = drawn_lod.at("us").get<std::vector<double>>();
          for (size_t r = 0; r < us.size(); ++r) reps += (r ? ";" : "") + fmt(us[r], "%.1f");
          med = stats::median_or_nan(us);
          mean_abs = drawn_lod.at("image_mean_abs").get<double>();
          differing = drawn_lod.at("image_differing").get<double>();
        }
        csv << lambda_kind_name(kind) << ',' << util::full_precision_or_empty(tau) << ',' << fi
            << ',' << mesh.triangle_count() << ',' << mesh.vertex_count() << ','
            << mesh.strip_index_count() << ',' << int(conf.conforming) << ',' << int(seams.ok)
            << ',' << util::full_precision_or_empty(se.max_px) << ',' << se.checked << ','
            << se.excluded << ',' << fmt(se.worst_x, "%.1f") << ',' << fmt(se.worst_y, "%.1f")
            << ',' << fmt(med, "%.1f") << ',' << reps << ',' << full.triangle_count() << ','
            << fmt(full_median, "%.1f") << ',' << fmt(mean_abs, "%.6g") << ','
            << fmt(differing, "%.6g") << ',' << se.partially_visible << ',' << se.holes << "\n";
      }
    if (progress && (fi % 10 == 0 || fi + 1 == path.size()))
      std::cerr << "lod: frame " << fi + 1 << "/" << path.size() << "\n";
  }
  util::write_file_atomic(dir + "/frames.csv", csv.str());
  return out;
}

}  // namespace

rundir::StudyRunResult run_lod_study(const rundir::StudyRunOptions& options) {
  const auto wall0 = std::chrono::steady_clock::now();
  const LodSettings s = read_lod_experiment(options.experiment);
  if (!options.platforms.empty() &&
      std::find(options.platforms.begin(), options.platforms.end(), s.platform) == options.platforms.end())
    throw util::UserError(options.experiment + ": the LOD study draws on " + s.platform +
                          ", which --platform leaves out");
  platforms::require_platforms_draw({s.platform},
                                    options.experiment);  // before anything is written
  rundir::StudyRunResult result;
  result.dir = options.out_dir.empty() ? "outputs/" + s.name : options.out_dir;
  prepare_output_dir(result.dir);

  const HeightField field = load_terrain(s);
  const auto h0 = std::chrono::steady_clock::now();
  const TerrainHierarchy hierarchy(field, s.tile_size, s.propagation, s.equalise_seams);
  const double hierarchy_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - h0).count();

  scenes::CameraPathParams pp;
  pp.seed = s.path_seed;
  pp.frames = s.frames;
  pp.flight_height = s.flight_height;
  pp.look_ahead = s.look_ahead;
  const std::vector<scenes::Viewpoint> path = scenes::generate_camera_path(layout_scene(field), pp);

  const LodMesh full = full_resolution(hierarchy);
  json drawn;
  try {
    drawn = util::run_in_child(result.dir, "lod-render", [&] {
      return draw_frames(s, field, hierarchy, path, full, options.progress);
    });
  } catch (const util::ChildProcessError& e) {
    if (e.user_error()) throw util::UserError(e.what());
    throw std::runtime_error(std::string("lod: ") + e.what());
  }
  const json& drawn_frames = drawn.at("frames");
  if (drawn_frames.size() != path.size())
    throw std::runtime_error("lod: the measuring process drew " + std::to_string(drawn_frames.size()) +
                             " frames, not " + std::to_string(path.size()));
  const FrameChecks checks =
      check_frames(s, field, hierarchy, path, full, drawn_frames, result.dir, options.progress);
  std::map<std::string, int> failures = checks.failures;  // [] below counts a lambda without failures as 0
  const int main_failures = checks.main_failures;
  const std::string& first_failure = checks.first_failure;

  json lj = json::object();
  for (LambdaKind k : {LambdaKind::kWindow, LambdaKind::kPlanar, LambdaKind::kSpherical})
    lj[lambda_kind_name(k)] = lambda_for(k, s.camera);
  json summary = {
      {"experiment", {{"file", s.file}, {"name", s.name}}},
      {"platform", s.platform},
      {"gl_renderer", drawn.at("gl_renderer")},
      {"gl_version", drawn.at("gl_version")},
      {"window", {s.camera.width, s.camera.height}},
      {"fov_y_deg", s.camera.fov_y_deg},
      {"near", s.camera.near},
      {"far", s.camera.far},
      {"tau_px", s.tau},
      {"lambda", lambda_kind_name(s.lambda)},
      {"lambda_px_per_rad", lj},
      {"error_propagation", s.propagation == ErrorPropagation::kNested ? "nested" : "unnested"},
      {"seams", s.equalise_seams ? "equalised" : "independent"},
      {"terrain", {{"source", field.source}, {"vertices", {field.nx, field.ny}}, {"spacing_m", field.spacing},
                   {"tile_size", s.tile_size}, {"tiles", {hierarchy.tiles_x(), hierarchy.tiles_y()}},
                   {"hierarchy_s", hierarchy_s}, {"seam_passes", hierarchy.seam_passes()}}},
      {"frames", path.size()},
      {"repetitions", s.repetitions},
      {"full_triangles", full.triangle_count()},
      {"failed_frames", failures},
      {"first_failure", first_failure},
      {"wall_s", std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count()}};
  summary.update(rundir::document_header("lod", 1));
  util::write_file_atomic(result.dir + "/lod_summary.json", summary.dump(2) + "\n");

  rundir::StudyInfo info;
  info.kind = rundir::StudyKind::kLod;
  info.name = s.name;
  info.title = s.title;
  info.subtitle = "Longest-edge bisection with nested errors and balls on " + field.source + ", " +
                  std::to_string(path.size()) + " frames at " + std::to_string(s.camera.width) + " x " +
                  std::to_string(s.camera.height) + " on " + s.platform + ".";
  rundir::write_study_info(result.dir, info);  // last: a complete run

  std::ostringstream sum;
  sum << "lod: " << path.size() << " frames x " << s.tau.size() << " tau, lambda " << lambda_kind_name(s.lambda)
      << ": " << (main_failures ? std::to_string(main_failures) + " (frame, tau) failed a check; first: " + first_failure
                                : std::string("every check passed (conforming, seams, screen error <= tau)"));
  for (LambdaKind k : s.check_lambdas)
    sum << "\n  lambda " << lambda_kind_name(k) << " (checked only): " << failures[lambda_kind_name(k)]
        << " (frame, tau) with a failed check";
  sum << "\n  written to " << result.dir;
  result.summary = sum.str();
  result.findings = main_failures > 0;
  return result;
}

// frames.csv of the run in `dir`, one row per (lambda, tau) in the order of the file: medians over
// the frames, the q90 and maximum of the measured screen error, the checks' counts.
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
    md << stats::markdown_row({"`" + r.lambda + "` (" + fmt(lam.value(r.lambda, 0.0), "%.0f") + ")", fmt(r.tau, "%g"),
               std::to_string(r.frames), std::to_string(r.conforming), std::to_string(r.seams_ok),
               (r.over_tau ? "**" + fmt(r.max_screen_error, "%.3f") + "**" : fmt(r.max_screen_error, "%.3f")),
               fmt(r.screen_error_q90, "%.3f"), std::to_string(r.over_tau)});
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
    md << stats::markdown_row({fmt(r.tau, "%g"), fmt(r.triangles_median, "%.0f"), fmt(100 * r.triangles_median / r.full_triangles, "%.2f"),
               fmt(r.indices_per_triangle, "%.2f"), fmt(r.frame_ms, "%.2f"), fmt(r.full_ms, "%.2f"),
               fmt(r.full_ms / r.frame_ms, "%.1f"), fmt(r.image_mean_abs, "%.3f"), fmt(100 * r.image_differing, "%.3f")});
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
       << "- LOD triangles (median over frames): **" << fmt(at_one->triangles_median, "%.0f") << "** against "
       << fmt(at_one->full_triangles, "%.0f") << " at full resolution ("
       << fmt(100 * at_one->triangles_median / at_one->full_triangles, "%.1f") << " %).\n"
       << "- Frame time (median): **" << fmt(at_one->frame_ms, "%.2f") << " ms** against "
       << fmt(at_one->full_ms, "%.2f") << " ms at full resolution.\n"
       << "- Measured maximum screen error over all frames: **" << fmt(at_one->max_screen_error, "%.3f")
       << " px** with lambda `" << main_lambda << "`";
    if (!std::isnan(planar_max)) md << "; " << fmt(planar_max, "%.3f") << " px with the paper's planar lambda";
    if (!std::isnan(spherical_max)) md << "; " << fmt(spherical_max, "%.3f") << " px with its spherical lambda";
    md << ".\n\n";
  }
  return md.str();
}

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
    sj = json::parse(util::read_file(dir + "/lod_summary.json"));
  } catch (const json::exception& e) {
    throw util::UserError(dir + "/lod_summary.json: " + e.what());
  }
  const std::vector<TableRow> rows = rows_of_frames(dir);
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
  util::write_file_atomic(dir + "/lod_table.csv", table.str());
  util::write_file_atomic(dir + "/lod.md", lod_document(sj, rows));
  rundir::StudyInfo updated = *info;
  updated.document = "lod.md";
  updated.analysed = true;
  rundir::write_study_info(dir, updated);
}

void plot_lod_study(const std::string& dir) {
  const std::optional<rundir::StudyInfo> info = rundir::read_study_info(dir);
  if (!info || info->kind != rundir::StudyKind::kLod || !info->analysed)
    throw util::UserError(dir + " has not been analysed: run `renderaudit analyze " + dir +
                          "` first");
  const std::vector<TableRow> rows = read_table(dir);
  auto label = [](double tau) { return "tau " + fmt(tau, "%g"); };
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
