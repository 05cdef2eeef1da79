// The [timing] table of a timing experiment file (timing_experiment.h).
#include "timing/timing_experiment.h"

#include <cmath>
#include <set>
#include <sstream>

#include "rundir/platform_spec.h"
#include "scenes/study_settings.h"
#include "util/errors.h"
#include "util/toml_locator.h"

namespace ra::timing {
namespace {

using Locator = util::TomlLocator;  // file:line:column errors, as every experiment reader

void parse_work(const Locator& loc, const toml::table& t, const std::string& where,
                WorkSettings& w) {
  if (const auto* n = t.get("repetitions"))
    w.repetitions = int(loc.integer(*n, where + "repetitions", 1, 1000));
  if (const auto* n = t.get("system_task_renders"))
    w.system_task_renders = int(loc.integer(*n, where + "system_task_renders", 10, 1000000));
  if (const auto* n = t.get("object_samples"))
    w.object_samples = int(loc.integer(*n, where + "object_samples", 10, 10000000));
  if (const auto* n = t.get("frame_stride"))
    w.frame_stride = int(loc.integer(*n, where + "frame_stride", 1, 100000));
  if (const auto* n = t.get("pos_repetitions"))
    w.pos_repetitions = int(loc.integer(*n, where + "pos_repetitions", 1, 1000));
}

}  // namespace

const WorkSettings& TimingSettings::work_for(const std::string& platform) const {
  auto it = platform_work.find(platform);
  return it == platform_work.end() ? work : it->second;
}

TimingSettings read_timing_experiment(const std::string& path) {
  return parse_timing_experiment(util::TomlLocator::read_text(path), path);
}

TimingSettings parse_timing_experiment(const std::string& text, const std::string& path) {
  Locator loc(path);
  TimingSettings s;
  const scenes::StudyFile file = scenes::read_study_file(loc, text, "timing", {"scene"}, false, &s);
  const toml::table& root = file.root;
  const toml::table& t = file.table();
  loc.reject_unknown_keys(
      t, "timing.",
      {"platforms", "window", "fov_deg", "near", "far", "repetitions", "system_task_renders",
       "object_samples", "system_task_scene", "system_task_frame", "cache_size", "seed", "gpu_timer", "frame_stride", "pos_repetitions",
       "alpha_min_deg",
       "phi_deg", "pos_grid", "pos_prune_alpha_deg", "pos_lookup", "platform", "study_runs"});

  if (const auto* n = t.get("platforms")) {
    const auto& a =
        loc.array(*n, "timing.platforms", 0, SIZE_MAX, "a non-empty array of platform names");
    if (a.empty()) loc.fail(n, "'timing.platforms' must not be empty");
    s.platforms.clear();
    for (const auto& e : a) {
      const auto* str = e.as_string();
      // The study draws aliased frames: a multisample platform would be measured as aliased.
      if (!str || !rundir::is_aliased_gl_platform(str->get()))
        loc.fail(&e,
                 "'timing.platforms' holds an unknown, driverless or multisample platform "
                 "(allowed: " +
                     rundir::aliased_gl_platform_names() + ")");
      for (const auto& p : s.platforms)
        if (p == str->get()) loc.fail(&e, "platform '" + p + "' is listed twice");
      s.platforms.push_back(str->get());
    }
  }
  scenes::read_camera_block(loc, t, "timing", &s.camera);
  parse_work(loc, t, "timing.", s.work);
  if (const auto* n = t.get("study_runs"))
    s.study_runs = int(loc.integer(*n, "timing.study_runs", 1, 100));
  if (const auto* n = t.get("cache_size"))
    s.cache_size = unsigned(loc.integer(*n, "timing.cache_size", 3, 1024));
  if (const auto* n = t.get("seed"))
    s.seed = uint64_t(loc.integer(*n, "timing.seed", 0, INT64_MAX));
  if (const auto* n = t.get("gpu_timer")) {
    const auto* b = n->as_boolean();
    if (!b) loc.fail(n, "'timing.gpu_timer' must be true or false");
    s.gpu_timer = b->get();
  }
  if (const auto* n = t.get("alpha_min_deg"))
    s.alpha_min_deg = loc.number(*n, "timing.alpha_min_deg", "0 < alpha_min_deg < 90",
                                 [](double v) { return v > 0 && v < 90; });
  if (const auto* n = t.get("phi_deg")) {
    const auto& a = loc.array(*n, "timing.phi_deg", 2, 2, "[lowest, highest] elevation in degrees");
    auto in_range = [](double v) { return v >= -90 && v <= 90; };
    s.phi_min_deg = loc.number(*a.get(0), "timing.phi_deg", "-90 to 90", in_range);
    s.phi_max_deg = loc.number(*a.get(1), "timing.phi_deg", "-90 to 90", in_range);
    if (s.phi_max_deg < s.phi_min_deg)
      loc.fail(n, "'timing.phi_deg' must be [lowest, highest] (allowed: lowest <= highest)");
  }
  if (const auto* n = t.get("pos_grid")) {
    const auto& a =
        loc.array(*n, "timing.pos_grid", 3, 3, "[alpha points, gamma points, phi points]");
    s.pos_grid.n_alpha = int(loc.integer(*a.get(0), "timing.pos_grid[0] (alpha)", 2, 64));
    s.pos_grid.n_gamma = int(loc.integer(*a.get(1), "timing.pos_grid[1] (gamma)", 1, 64));
    s.pos_grid.n_phi = int(loc.integer(*a.get(2), "timing.pos_grid[2] (phi)", 1, 64));
  }
  if (const auto* n = t.get("pos_prune_alpha_deg"))
    s.pos_prune_alpha_deg = loc.number(*n, "timing.pos_prune_alpha_deg", "0 <= value < 180",
                                       [](double v) { return v >= 0 && v < 180; });
  if (const auto* n = t.get("pos_lookup")) {
    const auto* str = n->as_string();
    if (!str || (str->get() != "interpolate" && str->get() != "nearest"))
      loc.fail(n, "'timing.pos_lookup' must be a string (allowed: \"interpolate\", \"nearest\")");
    s.pos_lookup = str->get() == "nearest" ? PosLookup::kNearest : PosLookup::kInterpolate;
  }
  const double deg = M_PI / 180.0;
  s.pos_grid.alpha_min = s.alpha_min_deg * deg;
  s.pos_grid.alpha_max = scenes::max_clipped_alpha(s.camera);
  if (s.pos_grid.alpha_max <= s.pos_grid.alpha_min)
    loc.fail(t.get("alpha_min_deg"), "'timing.alpha_min_deg' must be below the largest clipped "
                                     "alpha of the window (" +
                                         std::to_string(s.pos_grid.alpha_max / deg) + " degrees)");
  s.pos_grid.phi_min = s.phi_min_deg * deg;
  s.pos_grid.phi_max = s.phi_max_deg * deg;

  for (const auto& p : s.platforms) s.platform_work[p] = s.work;
  if (const auto* n = t.get("platform")) {
    const auto* pt = n->as_table();
    if (!pt) loc.fail(n, "'timing.platform' must be a table of per-platform tables");
    for (const auto& [key, node] : *pt) {
      const std::string name(key.str());
      if (!s.platform_work.count(name))
        loc.fail_at(key.source().begin, "'timing.platform." + name +
                                            "' names a platform not in timing.platforms");
      const auto* wt = node.as_table();
      if (!wt) loc.fail(&node, "'timing.platform." + name + "' must be a table");
      const std::string where = "timing.platform." + name + ".";
      loc.reject_unknown_keys(*wt, where,
                              {"repetitions", "system_task_renders", "object_samples", "frame_stride",
                               "pos_repetitions"});
      parse_work(loc, *wt, where, s.platform_work[name]);
    }
  }

  s.scenes = scenes::parse_scene_specs(root, path);
  if (s.scenes.empty())
    loc.fail(nullptr, "no [[scene]] table: the study needs at least one scene (kind = \"city\", "
                      "\"terrain\" or \"forest\")");
  const scenes::SceneSpec* system_scene = &s.scenes.front();
  if (const auto* n = t.get("system_task_scene")) {
    const auto* str = n->as_string();
    std::string names;
    system_scene = nullptr;
    for (const scenes::SceneSpec& spec : s.scenes) {
      names += (names.empty() ? "" : ", ") + spec.name;
      if (str && spec.name == str->get()) system_scene = &spec;
    }
    if (!system_scene)
      loc.fail(n, "'timing.system_task_scene' must name a scene of the file (allowed: " + names + ")");
    s.system_task_scene = str->get();
  }
  if (const auto* n = t.get("system_task_frame"))
    // A recorded path's length is known only once it is read: the study checks it then.
    s.system_task_frame =
        int(loc.integer(*n, "timing.system_task_frame", 0,
                        system_scene->path_file.empty() ? system_scene->path.frames - 1 : 999999));
  return s;
}

}  // namespace ra::timing
