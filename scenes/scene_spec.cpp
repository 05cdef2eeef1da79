// [[scene]] tables of an experiment file -> scenes and camera paths. Every key is checked, with
// the file, line and column of the offending value (the project's experiment-file convention).
#include "scenes/scene_spec.h"

#include <filesystem>
#include <functional>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

#include "util/errors.h"
#include "util/number_text.h"
#include "util/toml_locator.h"

namespace ra::scenes {
namespace {

// A table of the file: errors at its nodes (util/toml_locator.h), keys named "scene[i].key".
class Located {
 public:
  Located(std::string file, std::string where) : at_(std::move(file)), where_(std::move(where)) {}

  [[noreturn]] void fail(const toml::node* node, const std::string& message) const {
    at_.fail(node, message);
  }
  [[noreturn]] void fail_at(toml::source_position at, const std::string& message) const {
    at_.fail_at(at, message);
  }
  std::string key(const std::string& k) const { return where_ + "." + k; }

 private:
  util::TomlLocator at_;
  std::string where_;
};

std::string join(const std::set<std::string>& keys) {
  std::string s;
  for (const auto& k : keys) s += (s.empty() ? "" : ", ") + k;
  return s;
}

// One table's keys: each reader consumes its key; leftovers are unknown keys.
class KeyReader {
 public:
  KeyReader(const Located& loc, const toml::table& t) : loc_(loc), t_(t) {}

  template <typename Int>
  void integer(const std::string& k, Int& out, int64_t lo, int64_t hi) {
    const toml::node* n = take(k);
    if (!n) return;
    const auto* v = n->as_integer();
    if (!v)
      loc_.fail(n, loc_.key(k) + " must be an integer (allowed: " + std::to_string(lo) + " to " +
                       std::to_string(hi) + ")");
    if (v->get() < lo || v->get() > hi)
      loc_.fail(n, loc_.key(k) + " = " + std::to_string(v->get()) + " is out of range (allowed: " +
                       std::to_string(lo) + " to " + std::to_string(hi) + ")");
    out = static_cast<Int>(v->get());
  }

  // lo_open: the value must be > lo rather than >= lo.
  void real(const std::string& k, double& out, double lo, double hi, bool lo_open = false) {
    const toml::node* n = take(k);
    if (!n) return;
    double v = 0;
    if (const auto* i = n->as_integer())
      v = static_cast<double>(i->get());
    else if (const auto* f = n->as_floating_point())
      v = f->get();
    else
      loc_.fail(n, loc_.key(k) + " must be a number");
    const std::string allowed = (lo_open ? "> " : "") + util::significant(lo, 6) + " to " + util::significant(hi, 6);
    if (!(lo_open ? v > lo : v >= lo) || !(v <= hi))
      loc_.fail(n, loc_.key(k) + " = " + util::significant(v, 6) + " is out of range (allowed: " + allowed + ")");
    out = v;
  }

  void seed(const std::string& k, uint64_t& out) {
    int64_t v = 0;
    const toml::node* n = t_.get(k);
    if (!n) return;
    integer(k, v, 0, INT64_MAX);
    out = static_cast<uint64_t>(v);
  }

  bool string(const std::string& k, std::string& out) {
    const toml::node* n = take(k);
    if (!n) return false;
    const auto* s = n->as_string();
    if (!s) loc_.fail(n, loc_.key(k) + " must be a string");
    out = s->get();
    return true;
  }

  const toml::node* take(const std::string& k) {
    used_.insert(k);
    return t_.get(k);
  }
  bool has(const std::string& k) const { return t_.get(k) != nullptr; }

  // Every key not read is a typo or a key of another kind: an error, never silently ignored.
  void reject_unknown(const std::set<std::string>& allowed, const std::string& what) const {
    for (const auto& [key, node] : t_) {
      const std::string k(key.str());
      if (!used_.count(k) && !allowed.count(k))
        loc_.fail_at(key.source().begin, "unknown key " + loc_.key(k) + " " + what + " (allowed: " + join(allowed) + ")");
    }
  }

 private:
  const Located& loc_;
  const toml::table& t_;
  std::set<std::string> used_;
};

const std::set<std::string> kCommonKeys = {"kind", "name", "seed", "camera_path"};
const std::map<std::string, std::set<std::string>> kKindKeys = {
    {"city", {"blocks_x", "blocks_y", "buildings_per_block", "textures", "texture_size", "block_size",
              "street_width", "floors_min", "floors_max", "floor_height", "bay_width", "tiers_max"}},
    {"terrain", {"size", "spacing", "height_scale", "feature_size", "octaves", "persistence", "texture_size"}},
    {"forest", {"trees", "area", "slices_min", "slices_max", "height_min", "height_max", "texture_size"}},
};
const std::set<std::string> kPathKeys = {"frames", "seed", "waypoints", "eye_height", "flight_height",
                                         "look_ahead", "file"};

void read_city(KeyReader& r, CityParams& c) {
  r.integer("blocks_x", c.blocks_x, 1, 1000);
  r.integer("blocks_y", c.blocks_y, 1, 1000);
  r.integer("buildings_per_block", c.buildings_per_block, 1, 64);
  r.integer("textures", c.textures, 3, 256);
  r.integer("texture_size", c.texture_size, 1, 4096);
  r.real("block_size", c.block_size, 10, 1000);
  r.real("street_width", c.street_width, 2, 200);
  r.integer("floors_min", c.floors_min, 1, 500);
  r.integer("floors_max", c.floors_max, 1, 500);
  r.real("floor_height", c.floor_height, 1, 20);
  r.real("bay_width", c.bay_width, 0.5, 100);
  r.integer("tiers_max", c.tiers_max, 1, 8);
}

void read_terrain(KeyReader& r, TerrainParams& t) {
  r.integer("size", t.size, 2, 4097);
  r.real("spacing", t.spacing, 0, 1e5, true);
  r.real("height_scale", t.height_scale, 0, 1e5);
  r.real("feature_size", t.feature_size, 0, 1e7, true);
  r.integer("octaves", t.octaves, 1, 16);
  r.real("persistence", t.persistence, 0, 1);
  r.integer("texture_size", t.texture_size, 1, 4096);
}

void read_forest(KeyReader& r, ForestParams& f) {
  r.integer("trees", f.trees, 1, 100000);
  r.real("area", f.area, 0, 1e6, true);
  r.integer("slices_min", f.slices_min, 3, 1024);
  r.integer("slices_max", f.slices_max, 3, 1024);
  r.real("height_min", f.height_min, 0, 1000, true);
  r.real("height_max", f.height_max, 0, 1000, true);
  r.integer("texture_size", f.texture_size, 1, 4096);
}

void read_path(const Located& scene_loc, const toml::node& node, const std::string& file_name,
               const std::string& where, SceneSpec& spec) {
  const toml::table* t = node.as_table();
  if (!t) scene_loc.fail(&node, where + " must be a table (keys: " + join(kPathKeys) + ")");
  Located loc(file_name, where);
  KeyReader r(loc, *t);
  std::string file;
  if (r.string("file", file)) {
    // a recorded path replaces the generated one: its keys would be silently unused
    for (const char* k : {"frames", "seed", "waypoints", "eye_height", "flight_height", "look_ahead"})
      if (r.has(k)) loc.fail(t->get(k), loc.key(k) + " cannot be combined with " + loc.key("file") + " (a recorded path)");
    if (file.empty()) loc.fail(t->get("file"), loc.key("file") + " must not be empty");
    std::filesystem::path p(file);
    if (p.is_relative()) p = std::filesystem::path(file_name).parent_path() / p;
    spec.path_file = p.lexically_normal().string();
  }
  r.integer("frames", spec.path.frames, 1, 1000000);
  r.seed("seed", spec.path.seed);
  r.integer("waypoints", spec.path.waypoints, 2, 10000);
  r.real("eye_height", spec.path.eye_height, 0, 10000, true);
  r.real("flight_height", spec.path.flight_height, 0, 100000, true);
  r.real("look_ahead", spec.path.look_ahead, 0, 100000, true);
  r.reject_unknown({}, "");
}

}  // namespace

std::vector<SceneSpec> parse_scene_specs(const toml::table& root, const std::string& file_name) {
  std::vector<SceneSpec> out;
  const toml::node* node = root.get("scene");
  if (!node) return out;
  const Located top(file_name, "scene");
  const toml::array* arr = node->as_array();
  if (!arr) top.fail(node, "scene must be an array of tables ([[scene]])");
  std::map<std::string, size_t> names;
  for (size_t k = 0; k < arr->size(); ++k) {
    const toml::node& e = *arr->get(k);
    const std::string where = "scene[" + std::to_string(k) + "]";
    const toml::table* t = e.as_table();
    if (!t) top.fail(&e, where + " must be a table ([[scene]])");
    const Located loc(file_name, where);
    KeyReader r(loc, *t);
    SceneSpec spec;
    if (!r.string("kind", spec.kind)) loc.fail(&e, "missing key " + loc.key("kind") + " (allowed: city, terrain, forest)");
    if (!kKindKeys.count(spec.kind))
      loc.fail(t->get("kind"), loc.key("kind") + " = \"" + spec.kind + "\" is not a scene kind (allowed: city, terrain, forest)");
    spec.name = spec.kind;
    r.string("name", spec.name);
    if (spec.name.empty()) loc.fail(t->get("name"), loc.key("name") + " must not be empty");
    if (names.count(spec.name))
      loc.fail(t->get("name") ? t->get("name") : &e,
               loc.key("name") + " = \"" + spec.name + "\" is already used by scene[" +
                   std::to_string(names[spec.name]) + "] (names must be unique; set name)");
    names[spec.name] = k;
    uint64_t seed = 1;
    r.seed("seed", seed);
    spec.city.seed = spec.terrain.seed = spec.forest.seed = seed;
    if (spec.kind == "city") read_city(r, spec.city);
    if (spec.kind == "terrain") read_terrain(r, spec.terrain);
    if (spec.kind == "forest") read_forest(r, spec.forest);
    if (const toml::node* p = r.take("camera_path")) read_path(loc, *p, file_name, loc.key("camera_path"), spec);
    std::set<std::string> allowed = kCommonKeys;
    allowed.insert(kKindKeys.at(spec.kind).begin(), kKindKeys.at(spec.kind).end());
    r.reject_unknown(allowed, "for kind \"" + spec.kind + "\"");
    // the constraints between keys (floors_min <= floors_max, ...), with the generators' words
    try {
      if (spec.kind == "city") validate(spec.city);
      if (spec.kind == "terrain") validate(spec.terrain);
      if (spec.kind == "forest") validate(spec.forest);
    } catch (const std::invalid_argument& err) {
      loc.fail(&e, where + ": " + err.what());
    }
    out.push_back(std::move(spec));
  }
  return out;
}

Scene build_scene(const SceneSpec& spec) {
  if (spec.kind == "city") return generate_city(spec.city);
  if (spec.kind == "terrain") return generate_terrain(spec.terrain);
  if (spec.kind == "forest") return generate_forest(spec.forest);
  throw std::invalid_argument("scene '" + spec.name + "': unknown kind '" + spec.kind + "' (allowed: city, terrain, forest)");
}

std::vector<Viewpoint> build_camera_path(const SceneSpec& spec, const Scene& scene) {
  if (!spec.path_file.empty()) return read_camera_path_csv(spec.path_file);
  return generate_camera_path(scene, spec.path);
}

}  // namespace ra::scenes
