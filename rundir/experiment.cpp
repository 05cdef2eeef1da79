#include "rundir/experiment.h"

#include <cmath>
#include <cstdlib>
#include <set>
#include <sstream>

#define TOML_EXCEPTIONS 1
#include <toml++/toml.h>

#include "geometry/projection_range.h"
#include "rundir/build_record.h"
#include "rundir/platform_spec.h"
#include "util/errors.h"
#include "util/fnv1a.h"
#include "util/toml_locator.h"

namespace ra::rundir {
namespace {

// A key that may hold one value or an array of values.
std::vector<const toml::node*> one_or_many(const toml::node& node) {
  std::vector<const toml::node*> out;
  if (auto arr = node.as_array()) {
    for (const auto& e : *arr) out.push_back(&e);
  } else {
    out.push_back(&node);
  }
  return out;
}

// Hash of what determines the results: the canonical TOML without comments, layout or the [run]
// table (shard size and timeout change how the work is cut, never a record).
std::string canonical_hash(toml::table root) {
  root.erase("run");
  std::ostringstream canon;
  canon << root;
  util::Fnv1a64 h;
  h.add(canon.str());
  return util::hex64(h.value);
}

std::vector<uint64_t> index_list(const util::TomlLocator& loc, const toml::node& node,
                                 const std::string& key) {
  std::vector<uint64_t> out;
  const auto* arr = node.as_array();
  if (!arr) loc.fail(&node, "'" + key + "' must be an array of primitive indices");
  for (const auto& e : *arr)
    out.push_back(uint64_t(loc.integer(e, key, 0, int64_t(kMaxPrimitives) - 1)));
  return out;
}

void parse_views(const util::TomlLocator& loc, const toml::table& root, Experiment& exp) {
  const toml::node* views_node = root.get("views");
  if (!views_node || !views_node->is_table())
    loc.fail(views_node, "missing table [views] (keys: orientations, fov_deg, windows, near, far)");
  const toml::table& t = *views_node->as_table();
  loc.reject_unknown_keys(t, "views.", {"orientations", "fov_deg", "windows", "near", "far"});

  // Orientations: a count drawn from the seed, or explicit [yaw, pitch, roll] in degrees.
  std::vector<geometry::Mat4> rotations;
  const toml::node* o = t.get("orientations");
  if (!o) loc.fail(views_node, "missing key 'views.orientations' (a count, or [[yaw, pitch, roll], ...])");
  if (o->is_integer()) {
    const int64_t n = loc.integer(*o, "views.orientations", 1, kMaxOrientations);
    for (int i = 1; i <= n; ++i) rotations.push_back(geometry::random_rotation(exp.seed, i));
  } else if (const auto* arr = o->as_array(); arr && !arr->empty()) {
    for (const auto& e : *arr) {
      const auto* triple = e.as_array();
      if (!triple || triple->size() != 3)
        loc.fail(&e, "each explicit orientation must be [yaw, pitch, roll] in degrees");
      double a[3];
      for (int k = 0; k < 3; ++k) {
        a[k] = loc.number(*triple->get(k), "views.orientations");
        if (!std::isfinite(a[k]) || std::fabs(a[k]) > 360)
          loc.fail(triple->get(k), "orientation angle out of range (allowed: -360 to 360 degrees)");
      }
      rotations.push_back(geometry::rotation_from_euler_deg(a[0], a[1], a[2]));
    }
  } else {
    loc.fail(o, "'views.orientations' must be a count (1 to " + std::to_string(kMaxOrientations) +
                    ") or a non-empty array of [yaw, pitch, roll]");
  }

  auto required = [&](const char* key) -> const toml::node& {
    const toml::node* n = t.get(key);
    if (!n) loc.fail(views_node, std::string("missing key 'views.") + key + "'");
    if (const auto* arr = n->as_array(); arr && arr->empty())
      loc.fail(n, std::string("'views.") + key + "' must not be empty");
    return *n;
  };

  std::vector<double> fovs;
  const std::vector<const toml::node*> fov_nodes = one_or_many(required("fov_deg"));
  for (const toml::node* n : fov_nodes) {
    const double f = loc.number(*n, "views.fov_deg");
    if (!(f > 0 && f < 180)) loc.fail(n, "field of view out of range (allowed: 0 < fov_deg < 180)");
    fovs.push_back(f);
  }

  std::vector<std::pair<int, int>> windows;
  for (const toml::node* n : one_or_many(required("windows"))) {
    int w, h;
    if (const auto* pair = n->as_array()) {
      if (pair->size() != 2) loc.fail(n, "a window is a size N or a pair [width, height]");
      w = int(loc.integer(*pair->get(0), "views.windows", 1, kMaxWindow));
      h = int(loc.integer(*pair->get(1), "views.windows", 1, kMaxWindow));
    } else {
      w = h = int(loc.integer(*n, "views.windows", 1, kMaxWindow));
    }
    windows.emplace_back(w, h);
  }
  // The projection must be finite in double and in float (drivers transform in float). Its entries
  // are f/aspect and f (f = 1/tan(fov/2)), A = (far+near)/(near-far) and B = 2*far*near/(near-far);
  // the primitives lie in the unit sphere around the camera, |x|, |y|, |z| <= 1 in eye space, so
  // clip x, y and z are at most f/aspect, f and |A| + |B|: each entry must be finite in double (B
  // is computed as 2*far*near/(near-far), whose first products overflow past DBL_MAX/2) and each
  // bound at most FLT_MAX (geometry::lateral_projection_problem, depth_projection_problem).
  for (size_t i = 0; i < fovs.size(); ++i)
    for (auto [w, h] : windows) {
      const std::string why = geometry::lateral_projection_problem(fovs[i], double(w) / h, 1.0);
      if (!why.empty()) {
        std::ostringstream s;
        s << "'views.fov_deg' = " << fovs[i] << " with window " << w << " x " << h
          << " is out of range: " << why
          << " (allowed: 0 < fov_deg < 180 with 1/tan(fov_deg/2) * max(1, height/width) at most "
             "3.40282e+38, the float range)";
        loc.fail(fov_nodes[i], s.str());
      }
    }

  std::vector<const toml::node*> nears = one_or_many(required("near"));
  std::vector<const toml::node*> fars = one_or_many(required("far"));
  std::vector<std::pair<double, double>> planes;
  for (const toml::node* nn : nears) {
    const double nv = loc.number(*nn, "views.near");
    if (!(nv > 0) || !std::isfinite(nv)) loc.fail(nn, "near plane must be > 0 (allowed: 0 < near < far)");
    for (const toml::node* fn : fars) {
      const double fv = loc.number(*fn, "views.far");
      if (!(fv > nv) || !std::isfinite(fv))
        loc.fail(fn, "far plane must be beyond the near plane (allowed: 0 < near < far < inf)");
      // The depth entries A and B, as derived above the field of view's check.
      const std::string why = geometry::depth_projection_problem(nv, fv, 1.0);
      if (!why.empty()) {
        std::ostringstream s;
        s << "'views.far' = " << fv << " with views.near = " << nv << " is out of range: " << why
          << " (allowed: 0 < near < far with 2*far and 2*far*near at most 1.79769e+308, the "
             "double range, and |(far+near)/(near-far)| + |2*far*near/(near-far)| at most "
             "3.40282e+38, the float range)";
        loc.fail(fn, s.str());
      }
      planes.emplace_back(nv, fv);
    }
  }

  // Numbered as in the paper's Table 1: window outermost, orientation innermost.
  int id = 1, group = 0;
  for (auto [w, h] : windows)
    for (double f : fovs)
      for (auto [nv, fv] : planes) {
        for (size_t r = 0; r < rotations.size(); ++r) {
          geometry::View v;
          v.id = id++;
          v.group = group;
          v.orientation = int(r) + 1;
          v.fov_deg = f;
          v.width = w;
          v.height = h;
          v.near = nv;
          v.far = fv;
          v.rotation = rotations[r];
          geometry::finish_view(v);
          exp.views.push_back(v);
        }
        ++group;
      }
}

// The plan's size, before anything is planned or written: renders = platforms x views x primitives,
// shards = platforms x views x sum over kinds of ceil(count / shard_size). Computed in 128 bits
// (1,000 orientations x 10^8 primitives overflow nothing there).
void check_plan_size(const util::TomlLocator& loc, const toml::table& root, const Experiment& exp) {
  using u128 = unsigned __int128;
  const u128 cases = u128(exp.platforms.size()) * exp.views.size();
  u128 primitives = 0, shards_per_case = 0;
  for (uint64_t c : exp.counts) {
    primitives += c;
    shards_per_case += (c + exp.shard_size - 1) / exp.shard_size;
  }
  const u128 renders = cases * primitives, shards = cases * shards_per_case;
  auto text = [](u128 v) {
    std::string s;
    do s.insert(s.begin(), char('0' + int(v % 10))), v /= 10; while (v > 0);
    return s;
  };
  const std::string plan = std::to_string(exp.platforms.size()) + " platforms x " +
                           std::to_string(exp.views.size()) + " views x " + text(primitives) +
                           " primitives per view = " + text(renders) + " renders in " +
                           text(shards) + " shards";
  const toml::node* at = root.get("primitives");
  if (renders > exp.max_renders)
    loc.fail(at, "the plan is too large: " + plan + ", above run.max_renders = " +
                     std::to_string(exp.max_renders) +
                     " (lower the counts or views, or raise run.max_renders)");
  if (shards > exp.max_shards)
    loc.fail(at, "the plan has too many shards: " + plan + ", above run.max_shards = " +
                     std::to_string(exp.max_shards) +
                     " (raise run.shard_size, or raise run.max_shards up to " +
                     std::to_string(kMaxShardsCeiling) + ")");
}

// [builds.NAME] tables: dir (absolute or ~/...), suite, origin.
void parse_builds(const util::TomlLocator& loc, const toml::table& root, Experiment& exp) {
  const toml::node* b = root.get("builds");
  if (!b) return;
  if (!b->is_table()) loc.fail(b, "'builds' must hold tables [builds.NAME] (keys: dir, suite, origin)");
  for (const auto& [key, node] : *b->as_table()) {
    const std::string name(key.str());
    if (!rundir::is_build_name(name))
      loc.fail(&node, "driver build name '" + name + "' is not valid (allowed: 1 to 64 letters, "
                      "digits, '.', '_', '-', not starting with '.' or '-')");
    if (!node.is_table()) loc.fail(&node, "'builds." + name + "' must be a table (keys: dir, suite, origin)");
    const toml::table& t = *node.as_table();
    loc.reject_unknown_keys(t, "builds." + name + ".", {"dir", "suite", "origin"});
    DriverBuildDecl d;
    d.name = name;
    for (auto [k, dst] : {std::pair{"dir", &d.dir}, std::pair{"suite", &d.suite},
                          std::pair{"origin", &d.origin}}) {
      const toml::node* n = t.get(k);
      if (!n) continue;
      const auto* v = n->as_string();
      if (!v || v->get().empty())
        loc.fail(n, "'builds." + name + "." + k + "' must be a non-empty string");
      *dst = v->get();
    }
    if (d.dir.rfind("~/", 0) == 0) {
      const char* home = std::getenv("HOME");
      d.dir = std::string(home ? home : "") + d.dir.substr(1);
    }
    if (!d.dir.empty() && d.dir[0] != '/')
      loc.fail(t.get("dir"), "'builds." + name + ".dir' must be an absolute path or start with ~/ "
                             "(the run folder's copy of this file is read from elsewhere)");
    if (!d.suite.empty() && !rundir::is_build_name(d.suite))
      loc.fail(t.get("suite"), "'builds." + name + ".suite' is not a suite name (letters, digits, ._-)");
    exp.builds[name] = d;
  }
}

// The keys of a [faults] table (an experiment's, or a faulty@BUILD folder's faults.toml).
rundir::FaultPlan parse_fault_plan(const util::TomlLocator& loc, const toml::table& t) {
  rundir::FaultPlan plan;
  loc.reject_unknown_keys(t, "faults.",
                          {"base", "crash", "hang", "hang_at_exit", "wild_pixel", "shift_fraction", "flaky_fraction",
                           "snap_bits", "snap_rounding", "drop_line_end_fraction", "slowdown",
                           "slowdown_kinds"});
  if (const toml::node* n = t.get("base")) {
    const auto* name = n->as_string();
    const std::optional<rundir::PlatformSpec> spec =
        name ? rundir::find_platform(name->get()) : std::optional<rundir::PlatformSpec>();
    if (!spec || (!spec->draws_with_gl() && name->get() != "reference"))
      loc.fail(n, "'faults.base' must name the platform that draws (allowed: reference, " +
                      rundir::aliased_gl_platform_names() + ")");
    plan.base = name->get();
  }
  if (const toml::node* n = t.get("crash")) plan.crash = index_list(loc, *n, "faults.crash");
  if (const toml::node* n = t.get("hang")) plan.hang = index_list(loc, *n, "faults.hang");
  if (const toml::node* n = t.get("hang_at_exit")) {
    const auto* b = n->as_boolean();
    if (!b) loc.fail(n, "'faults.hang_at_exit' must be true or false");
    plan.hang_at_exit = b->get();
  }
  if (const toml::node* n = t.get("wild_pixel"))
    plan.wild_pixel = index_list(loc, *n, "faults.wild_pixel");
  if (const toml::node* n = t.get("snap_bits"))
    plan.snap_bits = int(loc.integer(*n, "faults.snap_bits", 0, 12));
  if (const toml::node* n = t.get("snap_rounding")) {
    const auto* r = n->as_string();
    if (!r || (r->get() != "nearest" && r->get() != "truncation"))
      loc.fail(n, "'faults.snap_rounding' must be \"nearest\" or \"truncation\"");
    plan.snap_truncate = r->get() == "truncation";
  }
  for (auto [key, dst] : {std::pair{"shift_fraction", &plan.shift_fraction},
                          std::pair{"flaky_fraction", &plan.flaky_fraction},
                          std::pair{"drop_line_end_fraction", &plan.drop_line_end_fraction}}) {
    if (const toml::node* n = t.get(key)) {
      *dst = loc.number(*n, std::string("faults.") + key);
      if (!(*dst >= 0 && *dst <= 1)) loc.fail(n, std::string("'faults.") + key + "' out of range (allowed: 0 to 1)");
    }
  }
  if (const toml::node* n = t.get("slowdown")) {
    plan.timed = true;
    plan.slowdown = loc.number(*n, "faults.slowdown");
    if (!(plan.slowdown >= 0 && plan.slowdown <= 100))
      loc.fail(n, "'faults.slowdown' out of range (allowed: 0 to 100, the added fraction of the "
                  "drawing time)");
  }
  if (const toml::node* n = t.get("slowdown_kinds")) {
    const auto* list = n->as_array();
    if (!list) loc.fail(n, "'faults.slowdown_kinds' must be a list of kinds (allowed: point, line, triangle)");
    for (const toml::node& e : *list) {
      geometry::Kind k{};
      const auto* name = e.as_string();
      if (!name || !geometry::parse_kind(name->get(), &k))
        loc.fail(&e, "'faults.slowdown_kinds': not a kind (allowed: point, line, triangle)");
      plan.slowdown_kinds.push_back(k);
    }
    if (!t.get("slowdown"))
      loc.fail(n, "'faults.slowdown_kinds' needs 'faults.slowdown' (the fraction to slow them by)");
  }
  return plan;
}

}  // namespace

rundir::FaultPlan fault_plan_for(const Experiment& exp, const rundir::PlatformSpec& spec) {
  if (spec.backend != rundir::Backend::kFaulty || spec.build.empty()) return exp.faults;
  return load_fault_plan(spec.build_dir + "/faults.toml");
}

rundir::FaultPlan load_fault_plan(const std::string& path) {
  util::TomlLocator loc(path);
  const toml::table root = loc.parse(util::TomlLocator::read_text(path));
  const toml::node* f = root.get("faults");
  if (!f || !f->is_table()) loc.fail(f, "a faulty platform's build must hold a [faults] table");
  loc.reject_unknown_keys(root, "", {"faults"});
  return parse_fault_plan(loc, *f->as_table());
}

rundir::PlatformSpec experiment_platform(const Experiment& exp, const std::string& name) {
  std::optional<rundir::PlatformSpec> spec = rundir::find_platform(name);
  if (!spec)
    throw util::UserError("unknown platform '" + name +
                          "' (allowed: " + rundir::platform_names() + ")");
  if (spec->build.empty()) return *spec;
  const auto it = exp.builds.find(spec->build);
  if (it == exp.builds.end())
    throw util::UserError(exp.path + ": platform '" + name + "' names driver build '" +
                          spec->build + "', which the experiment does not declare ([builds." +
                          spec->build + "])");
  const DriverBuildDecl& d = it->second;
  if (!d.dir.empty()) {
    spec->build_dir = d.dir;
  } else if (!d.suite.empty()) {
    const std::string found = rundir::cached_build_of_suite(d.suite);
    if (found.empty())
      throw util::UserError(exp.path + ": driver build '" + d.name +
                            "' is the cached build of suite '" + d.suite + "', and " +
                            rundir::build_cache_dir() +
                            " holds none: fetch it with "
                            "`renderaudit builds fetch " +
                            d.suite + "`");
    spec->build_dir = found;
  }
  return *spec;
}

Experiment parse_experiment(const std::string& text, const std::string& path) {
  util::TomlLocator loc(path);
  const toml::table root = loc.parse(text);

  Experiment exp;
  exp.path = path;
  exp.text = text;
  exp.hash = canonical_hash(root);
  loc.reject_unknown_keys(root, "",
                          {"name", "seed", "platforms", "views", "primitives", "run", "faults",
                           "builds"});
  parse_builds(loc, root, exp);

  exp.name = loc.experiment_name(root);

  const toml::node* seed = root.get("seed");
  if (!seed) loc.fail(nullptr, "missing key 'seed' (a non-negative integer)");
  exp.seed = uint64_t(loc.integer(*seed, "seed", 0, INT64_MAX));

  const toml::node* plats = root.get("platforms");
  if (!plats || !plats->is_array() || plats->as_array()->empty())
    loc.fail(plats, "'platforms' must be a non-empty array (allowed: " +
                        rundir::platform_names() + ")");
  for (const auto& e : *plats->as_array()) {
    const auto* s = e.as_string();
    if (!s || !rundir::find_platform(s->get()))
      loc.fail(&e, "unknown platform '" + (s ? s->get() : std::string("?")) +
                       "' (allowed: " + rundir::platform_names() +
                       "; a build qualifies only the osmesa-* "
                       "and surfaceless egl-* platforms, its name of letters, digits and ._-)");
    if (const std::string build = rundir::split_build(s->get()).second;
        !build.empty() && !exp.builds.count(build))
      loc.fail(&e, "platform '" + s->get() + "' names driver build '" + build +
                       "', which no [builds." + build + "] table declares (declared: " +
                       (exp.builds.empty() ? std::string("none") : [&] {
                         std::string names;
                         for (const auto& [n, b] : exp.builds) names += (names.empty() ? "" : ", ") + n;
                         return names;
                       }()) + ")");
    for (const auto& seen : exp.platforms)
      if (seen == s->get()) loc.fail(&e, "platform '" + seen + "' is listed twice");
    exp.platforms.push_back(s->get());
  }

  parse_views(loc, root, exp);

  const toml::node* prims = root.get("primitives");
  if (!prims || !prims->is_table())
    loc.fail(prims, "missing table [primitives] (keys: points, lines, triangles)");
  loc.reject_unknown_keys(*prims->as_table(), "primitives.", {"points", "lines", "triangles"});
  uint64_t total = 0;
  for (geometry::Kind k :
       {geometry::Kind::kPoint, geometry::Kind::kLine, geometry::Kind::kTriangle}) {
    if (const toml::node* n = prims->as_table()->get(geometry::kind_plural(k))) {
      exp.counts[int(k)] = uint64_t(loc.integer(
          *n, std::string("primitives.") + geometry::kind_plural(k), 0, int64_t(kMaxPrimitives)));
      total += exp.counts[int(k)];
    }
  }
  if (total == 0) loc.fail(prims, "[primitives] asks for nothing: give points, lines or triangles a count > 0");

  if (const toml::node* run = root.get("run")) {
    if (!run->is_table()) loc.fail(run, "'run' must be a table");
    loc.reject_unknown_keys(*run->as_table(), "run.",
                            {"shard_size", "shard_timeout_s", "max_renders", "max_shards",
                             "records_format"});
    if (const toml::node* n = run->as_table()->get("shard_size"))
      exp.shard_size = uint64_t(loc.integer(*n, "run.shard_size", 1, int64_t(kMaxPrimitives)));
    if (const toml::node* n = run->as_table()->get("shard_timeout_s")) {
      exp.shard_timeout_s = loc.number(*n, "run.shard_timeout_s");
      if (!(exp.shard_timeout_s >= 1 && exp.shard_timeout_s <= 86400))
        loc.fail(n, "'run.shard_timeout_s' out of range (allowed: 1 to 86400 seconds)");
    }
    if (const toml::node* n = run->as_table()->get("max_renders"))
      exp.max_renders = uint64_t(loc.integer(*n, "run.max_renders", 1, INT64_MAX));
    if (const toml::node* n = run->as_table()->get("max_shards"))
      exp.max_shards = uint64_t(loc.integer(*n, "run.max_shards", 1, int64_t(kMaxShardsCeiling)));
    if (const toml::node* n = run->as_table()->get("records_format")) {
      const auto* name = n->as_string();
      const std::optional<rundir::RecordsFormat> f =
          name ? rundir::parse_records_format(name->get()) : std::nullopt;
      if (!f) loc.fail(n, "'run.records_format' must be \"csv.zst\" or \"csv\"");
      exp.records_format = *f;
    }
  }
  check_plan_size(loc, root, exp);

  if (const toml::node* f = root.get("faults")) {
    if (!f->is_table()) loc.fail(f, "'faults' must be a table");
    exp.faults = parse_fault_plan(loc, *f->as_table());
    bool faulty = false;
    for (const auto& p : exp.platforms) faulty |= (rundir::split_build(p).first == "faulty");
    if (!faulty) loc.fail(f, "[faults] only applies to the 'faulty' test platform, which is not listed");
  }
  return exp;
}

Experiment load_experiment(const std::string& path) {
  return parse_experiment(util::TomlLocator::read_text(path), path);
}

}  // namespace ra::rundir
