// The [lod] experiment table (lod_experiment.h).
#include "terrain_lod/lod_experiment.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <sstream>

#include "util/errors.h"
#include "platforms/platform.h"
#include "util/toml_locator.h"

namespace ra::lod {
namespace {

std::string show(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

template <typename Ok>
double number(const TomlLocator& loc, const toml::node& node, const std::string& key, const std::string& allowed,
              Ok ok) {
  double v = 0;
  if (const auto* i = node.as_integer())
    v = double(i->get());
  else if (const auto* f = node.as_floating_point())
    v = f->get();
  else
    loc.fail(&node, "'" + key + "' must be a number (allowed: " + allowed + ")");
  if (!std::isfinite(v) || !ok(v)) loc.fail(&node, "'" + key + "' = " + show(v) + " is out of range (allowed: " + allowed + ")");
  return v;
}

std::string string_of(const TomlLocator& loc, const toml::node& node, const std::string& key,
                      const std::vector<std::string>& allowed) {
  std::string list;
  for (const std::string& a : allowed) list += (list.empty() ? "" : ", ") + a;
  const auto* s = node.as_string();
  if (!s) loc.fail(&node, "'" + key + "' must be a string (allowed: " + (list.empty() ? "a file name" : list) + ")");
  if (!allowed.empty() && std::find(allowed.begin(), allowed.end(), s->get()) == allowed.end())
    loc.fail(&node, "'" + key + "' = \"" + s->get() + "\" is out of range (allowed: " + list + ")");
  return s->get();
}

const toml::array& array_of(const TomlLocator& loc, const toml::node& node, const std::string& key, size_t size,
                            const std::string& what) {
  const auto* a = node.as_array();
  if (!a || (size && a->size() != size) || a->empty()) loc.fail(&node, "'" + key + "' must be " + what);
  return *a;
}

}  // namespace

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
  return parse_lod_experiment(TomlLocator::read_text(path), path);
}

LodSettings parse_lod_experiment(const std::string& text, const std::string& path) {
  TomlLocator loc(path);
  const toml::table root = loc.parse(text);
  loc.reject_unknown_keys(root, "", {"name", "title", "lod"});
  LodSettings s;
  s.file = path;
  s.name = loc.experiment_name(root);
  if (const auto* n = root.get("title")) s.title = string_of(loc, *n, "title", {});
  const toml::node* lod_node = root.get("lod");
  if (!lod_node || !lod_node->is_table()) loc.fail(lod_node, "'lod' must be a table");
  const toml::table& t = *lod_node->as_table();
  loc.reject_unknown_keys(t, "lod.",
                          {"platform", "window", "fov_deg", "near", "far", "tau", "lambda", "check_lambdas",
                           "error_propagation", "seams", "tile_size", "tiles", "spacing", "height_scale", "seed",
                           "feature_size", "octaves", "persistence", "height_file", "frames", "path_seed",
                           "flight_height", "look_ahead", "repetitions"});
  if (const auto* n = t.get("platform")) {
    s.platform = string_of(loc, *n, "lod.platform", {});
    if (!is_aliased_gl_platform(s.platform))
      loc.fail(n, "'lod.platform' = \"" + s.platform + "\" is out of range (allowed: " +
                      aliased_gl_platform_names() + ")");
  }
  if (const auto* n = t.get("window")) {
    const auto& a = array_of(loc, *n, "lod.window", 2, "[width, height] in pixels");
    s.camera.width = int(loc.integer(*a.get(0), "lod.window", 16, 4096));
    s.camera.height = int(loc.integer(*a.get(1), "lod.window", 16, 4096));
  }
  if (const auto* n = t.get("fov_deg"))
    s.camera.fov_y_deg = number(loc, *n, "lod.fov_deg", "(0, 180), vertical", [](double v) { return v > 0 && v < 180; });
  if (const auto* n = t.get("near"))
    s.camera.near = number(loc, *n, "lod.near", "> 0 metres", [](double v) { return v > 0; });
  if (const auto* n = t.get("far")) {
    const double near = s.camera.near;
    s.camera.far = number(loc, *n, "lod.far", "> near = " + show(near), [&](double v) { return v > near; });
  } else if (!(s.camera.far > s.camera.near)) {
    loc.fail(t.get("near"), "'lod.near' = " + show(s.camera.near) + " is out of range (allowed: < far = " + show(s.camera.far) + ")");
  }
  if (const auto* n = t.get("tau")) {
    const auto& a = array_of(loc, *n, "lod.tau", 0, "a non-empty array of pixel thresholds");
    s.tau.clear();
    for (const auto& e : a) s.tau.push_back(number(loc, e, "lod.tau", "(0, 1000] pixels", [](double v) { return v > 0 && v <= 1000; }));
  }
  const std::vector<std::string> lambdas = {"window", "planar", "spherical"};
  if (const auto* n = t.get("lambda")) s.lambda = parse_lambda_kind(string_of(loc, *n, "lod.lambda", lambdas));
  if (const auto* n = t.get("check_lambdas")) {
    const auto* a = n->as_array();
    if (!a) loc.fail(n, "'lod.check_lambdas' must be an array of lambda names (allowed: window, planar, spherical)");
    s.check_lambdas.clear();
    for (const auto& e : *a) {
      const LambdaKind k = parse_lambda_kind(string_of(loc, e, "lod.check_lambdas", lambdas));
      if (k != s.lambda && std::find(s.check_lambdas.begin(), s.check_lambdas.end(), k) == s.check_lambdas.end())
        s.check_lambdas.push_back(k);
    }
  } else {
    s.check_lambdas.clear();
    for (LambdaKind k : {LambdaKind::kPlanar, LambdaKind::kSpherical, LambdaKind::kWindow})
      if (k != s.lambda) s.check_lambdas.push_back(k);
  }
  if (const auto* n = t.get("error_propagation"))
    s.propagation = string_of(loc, *n, "lod.error_propagation", {"nested", "unnested"}) == "nested"
                        ? ErrorPropagation::kNested : ErrorPropagation::kUnnested;
  if (const auto* n = t.get("seams"))
    s.equalise_seams = string_of(loc, *n, "lod.seams", {"equalised", "independent"}) == "equalised";
  if (const auto* n = t.get("tile_size")) {
    s.tile_size = int(loc.integer(*n, "lod.tile_size", 3, 4097));
    if (((s.tile_size - 1) & (s.tile_size - 2)) != 0)
      loc.fail(n, "'lod.tile_size' = " + std::to_string(s.tile_size) + " is out of range (allowed: 2^k + 1: 3, 5, 9, ..., 257, ..., 4097)");
  }
  if (const auto* n = t.get("tiles")) {
    const auto& a = array_of(loc, *n, "lod.tiles", 2, "[tiles along x, tiles along y]");
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
    s.terrain.spacing = number(loc, *n, "lod.spacing", "(0, 100000] metres", [](double v) { return v > 0 && v <= 1e5; });
  if (const auto* n = t.get("height_scale"))
    s.terrain.height_scale = number(loc, *n, "lod.height_scale", "[0, 100000] metres", [](double v) { return v >= 0 && v <= 1e5; });
  if (const auto* n = t.get("seed")) s.terrain.seed = uint64_t(loc.integer(*n, "lod.seed", 0, INT64_MAX));
  if (const auto* n = t.get("feature_size"))
    s.terrain.feature_size = number(loc, *n, "lod.feature_size", "(0, 1e7] metres", [](double v) { return v > 0 && v <= 1e7; });
  if (const auto* n = t.get("octaves")) s.terrain.octaves = int(loc.integer(*n, "lod.octaves", 1, 16));
  if (const auto* n = t.get("persistence"))
    s.terrain.persistence = number(loc, *n, "lod.persistence", "[0, 1]", [](double v) { return v >= 0 && v <= 1; });
  if (const auto* n = t.get("height_file")) {
    const std::string f = string_of(loc, *n, "lod.height_file", {});
    if (f.empty()) loc.fail(n, "'lod.height_file' must not be empty");
    const std::filesystem::path p(f);
    s.height_file = p.is_absolute() ? f : (std::filesystem::path(path).parent_path() / p).string();
  }
  if (const auto* n = t.get("frames")) s.frames = int(loc.integer(*n, "lod.frames", 1, 100000));
  if (const auto* n = t.get("path_seed")) s.path_seed = uint64_t(loc.integer(*n, "lod.path_seed", 0, INT64_MAX));
  if (const auto* n = t.get("flight_height"))
    s.flight_height = number(loc, *n, "lod.flight_height", "[0, 100000] metres", [](double v) { return v >= 0 && v <= 1e5; });
  if (const auto* n = t.get("look_ahead"))
    s.look_ahead = number(loc, *n, "lod.look_ahead", "(0, 100000] metres", [](double v) { return v > 0 && v <= 1e5; });
  if (const auto* n = t.get("repetitions")) s.repetitions = int(loc.integer(*n, "lod.repetitions", 1, 1000));
  return s;
}

}  // namespace ra::lod
