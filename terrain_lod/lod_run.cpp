// The terrain LOD study's run (lod_run.h).
#include "terrain_lod/lod_run.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "platforms/platform_probe.h"
#include "rundir/manifest.h"
#include "rundir/run_folder.h"
#include "scenes/camera_path.h"
#include "stats/descriptive.h"
#include "terrain_lod/lod_checks.h"
#include "terrain_lod/lod_experiment.h"
#include "terrain_lod/lod_renderer.h"
#include "terrain_lod/lod_table.h"
#include "util/atomic_file.h"
#include "util/cell_text.h"
#include "util/errors.h"
#include "util/gl_child_process.h"
#include "util/number_text.h"

namespace ra::lod {
namespace {

using nlohmann::json;

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
              first_failure = "frame " + std::to_string(fi) + ", tau " + util::format_double_or_empty("%g", tau) + ": " +
                              (!conf.conforming ? conf.first_problem
                               : !seams.ok     ? seams.first_problem
                                               : "measured screen error " + util::format_double_or_empty("%.3g", se.max_px) + " px > tau");
          }
        }
        double med = std::nan(""), mean_abs = std::nan(""), differing = std::nan("");
        std::string reps;
        if (kind == s.lambda) {  // drawn by draw_frames
          const json& drawn_lod = drawn_frame.at("lod").at(ti);
          if (drawn_lod.at("triangles").get<size_t>() != mesh.triangle_count())
            throw std::runtime_error("lod: frame " + std::to_string(fi) + ", tau " + util::format_double_or_empty("%g", tau) +
                                     ": the measuring process drew another mesh");
          const std::vector<double> us = drawn_lod.at("us").get<std::vector<double>>();
          for (size_t r = 0; r < us.size(); ++r) reps += (r ? ";" : "") + util::format_double_or_empty("%.1f", us[r]);
          med = stats::median_or_nan(us);
          mean_abs = drawn_lod.at("image_mean_abs").get<double>();
          differing = drawn_lod.at("image_differing").get<double>();
        }
        csv << lambda_kind_name(kind) << ',' << util::full_precision_or_empty(tau) << ',' << fi
            << ',' << mesh.triangle_count() << ',' << mesh.vertex_count() << ','
            << mesh.strip_index_count() << ',' << int(conf.conforming) << ',' << int(seams.ok)
            << ',' << util::full_precision_or_empty(se.max_px) << ',' << se.checked << ','
            << se.excluded << ',' << util::format_double_or_empty("%.1f", se.worst_x) << ',' << util::format_double_or_empty("%.1f", se.worst_y)
            << ',' << util::format_double_or_empty("%.1f", med) << ',' << reps << ',' << full.triangle_count() << ','
            << util::format_double_or_empty("%.1f", full_median) << ',' << util::format_double_or_empty("%.6g", mean_abs) << ','
            << util::format_double_or_empty("%.6g", differing) << ',' << se.partially_visible << ',' << se.holes << "\n";
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

}  // namespace ra::lod
