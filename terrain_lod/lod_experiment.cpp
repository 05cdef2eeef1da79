// The [lod] experiment table (lod_experiment.h).
#include "terrain_lod/lod_experiment.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <sstream>

#include "scenes/study_settings.h"
#include "util/errors.h"
#include "util/toml_locator.h"

namespace ra::lod {

// The camera defaults of the LOD study: window 1024 x 768, fov_y 60, near 1, far 50000.
LodSettings::LodSettings() {
  camera.width = 1024;
  camera.height = 768;
  camera.fov_y_deg = 60;
  camera.near = 1;
  camera.far = 50000;
  terrain.seed = 1;
  terrain.spacing = 10;
  terrain.height_scale = 300;
  terrain.feature_size = 800;
  terrain.octaves = 6;
  terrain.persistence = 0.5;
}

LodSettings read_lod_experiment(const std::string& path) {
  return parse_lod_experiment(util::TomlLocator::read_text(path), path);
}

LodSettings parse_lod_experiment(const std::string& text, const std::string& path) {
  util::TomlLocator loc(path);
  LodSettings s;
  const scenes::StudyFile file = scenes::read_study_file(loc, text, "lod", {"title"}, true, &s);
  if (const auto* n = file.root.get("title")) s.title = loc.string(*n, "title", {});
  const toml::table& t = file.table();
  loc.reject_unknown_keys(t, "lod.",
                          {"platform", "window", "fov_deg", "near", "far", "tau", "lambda", "check_lambdas",
                           "error_propagation", "seams", "tile_size", "tiles", "spacing", "height_scale", "seed",
                           "feature_size", "octaves", "persistence", "height_file", "frames", "path_seed",
                           "flight_height", "look_ahead", "repetitions"});
  if (const auto* n = t.get("platform"))
    s.platform = scenes::read_study_platform(loc, *n, "lod.platform");
  scenes::read_camera_block(loc, t, "lod", &s.camera);
  if (const auto* n = t.get("tau")) {
    const auto& a = loc.array(*n, "lod.tau", 1, SIZE_MAX, "a non-empty array of pixel thresholds");
    s.tau.clear();
    for (const auto& e : a)
      s.tau.push_back(loc.number(e, "lod.tau", "(0, 1000] pixels",
                                 [](double v) { return v > 0 && v <= 1000; }));
  }
  const std::vector<std::string> lambdas = {"window", "planar", "spherical"};
  if (const auto* n = t.get("lambda"))
    s.lambda = parse_lambda_kind(loc.string(*n, "lod.lambda", lambdas));
  if (const auto* n = t.get("check_lambdas")) {
    const auto* a = n->as_array();
    if (!a) loc.fail(n, "'lod.check_lambdas' must be an array of lambda names (allowed: window, planar, spherical)");
    s.check_lambdas.clear();
    for (const auto& e : *a) {
      const LambdaKind k = parse_lambda_kind(loc.string(e, "lod.check_lambdas", lambdas));
      if (k != s.lambda && std::find(s.check_lambdas.begin(), s.check_lambdas.end(), k) == s.check_lambdas.end())
        s.check_lambdas.push_back(k);
    }
  } else {
    s.check_lambdas.clear();
    for (LambdaKind k : {LambdaKind::kPlanar, LambdaKind::kSpherical, LambdaKind::kWindow})
      if (k != s.lambda) s.check_lambdas.push_back(k);
  }
  if (const auto* n = t.get("error_propagation"))
    s.propagation = loc.string(*n, "lod.error_propagation", {"nested", "unnested"}) == "nested"
                        ? ErrorPropagation::kNested
                        : ErrorPropagation::kUnnested;
  if (const auto* n = t.get("seams"))
    s.equalise_seams = loc.string(*n, "lod.seams", {"equalised", "independent"}) == "equalised";
  if (const auto* n = t.get("tile_size")) {
    s.tile_size = int(loc.integer(*n, "lod.tile_size", 3, 4097));
    if (((s.tile_size - 1) & (s.tile_size - 2)) != 0)
      loc.fail(n, "'lod.tile_size' = " + std::to_string(s.tile_size) + " is out of range (allowed: 2^k + 1: 3, 5, 9, ..., 257, ..., 4097)");
  }
  if (const auto* n = t.get("tiles")) {
    const auto& a = loc.array(*n, "lod.tiles", 2, 2, "[tiles along x, tiles along y]");
    s.tiles_x = int(loc.integer(*a.get(0), "lod.tiles", 1, 64));
    s.tiles_y = int(loc.integer(*a.get(1), "lod.tiles", 1, 64));
  }
  {
    const int64_t vx = int64_t(s.tiles_x) * (s.tile_size - 1) + 1, vy = int64_t(s.tiles_y) * (s.tile_size - 1) + 1;
    if (vx * vy > kMaxTerrainVertices) {
      const toml::node* at = t.get("tiles") ? t.get("tiles") : t.get("tile_size");
      loc.fail(at, "'lod.tiles' = [" + std::to_string(s.tiles_x) + ", " + std::to_string(s.tiles_y) +
                       "] x 'lod.tile_size' = " + std::to_string(s.tile_size) + " is " + std::to_string(vx) + " x " +
                       std::to_string(vy) + " = " + std::to_string(vx * vy) +
                       " vertices, out of range (allowed: at most " + std::to_string(kMaxTerrainVertices) +
                       " = 2^24 vertices, e.g. tiles [15, 15] of 257 or [3, 3] of 1025)");
    }
  }
  if (const auto* n = t.get("spacing"))
    s.terrain.spacing = loc.number(*n, "lod.spacing", "(0, 100000] metres",
                                   [](double v) { return v > 0 && v <= 1e5; });
  if (const auto* n = t.get("height_scale"))
    s.terrain.height_scale = loc.number(*n, "lod.height_scale", "[0, 100000] metres",
                                        [](double v) { return v >= 0 && v <= 1e5; });
  if (const auto* n = t.get("seed")) s.terrain.seed = uint64_t(loc.integer(*n, "lod.seed", 0, INT64_MAX));
  if (const auto* n = t.get("feature_size"))
    s.terrain.feature_size = loc.number(*n, "lod.feature_size", "(0, 1e7] metres",
                                        [](double v) { return v > 0 && v <= 1e7; });
  if (const auto* n = t.get("octaves")) s.terrain.octaves = int(loc.integer(*n, "lod.octaves", 1, 16));
  if (const auto* n = t.get("persistence"))
    s.terrain.persistence =
        loc.number(*n, "lod.persistence", "[0, 1]", [](double v) { return v >= 0 && v <= 1; });
  if (const auto* n = t.get("height_file")) {
    const std::string f = loc.string(*n, "lod.height_file", {});
    if (f.empty()) loc.fail(n, "'lod.height_file' must not be empty");
    const std::filesystem::path p(f);
    s.height_file = p.is_absolute() ? f : (std::filesystem::path(path).parent_path() / p).string();
  }
  if (const auto* n = t.get("frames")) s.frames = int(loc.integer(*n, "lod.frames", 1, 100000));
  if (const auto* n = t.get("path_seed")) s.path_seed = uint64_t(loc.integer(*n, "lod.path_seed", 0, INT64_MAX));
  if (const auto* n = t.get("flight_height"))
    s.flight_height = loc.number(*n, "lod.flight_height", "[0, 100000] metres",
                                 [](double v) { return v >= 0 && v <= 1e5; });
  if (const auto* n = t.get("look_ahead"))
    s.look_ahead = loc.number(*n, "lod.look_ahead", "(0, 100000] metres",
                              [](double v) { return v > 0 && v <= 1e5; });
  if (const auto* n = t.get("repetitions")) s.repetitions = int(loc.integer(*n, "lod.repetitions", 1, 1000));
  return s;
}

}  // namespace ra::lod
