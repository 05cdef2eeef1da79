// The [regulation] table of a regulation experiment file (regulation_experiment.h).
#include "regulation/regulation_experiment.h"

#include <cmath>
#include <filesystem>
#include <sstream>

#include "util/errors.h"
#include "rundir/platform_spec.h"
#include "scenes/study_settings.h"
#include "util/number_text.h"
#include "util/toml_locator.h"

namespace ra::regulation {
namespace {

using Locator = util::TomlLocator;

const toml::table& table_of(const Locator& loc, const toml::table& parent, const std::string& key,
                            const std::string& where, const toml::table& empty) {
  const toml::node* n = parent.get(key);
  if (!n) return empty;
  if (!n->is_table()) loc.fail(n, "'" + where + "' must be a table");
  return *n->as_table();
}

// [lo, hi] integer pair
void int_pair(const Locator& loc, const toml::node& node, const std::string& key, int64_t lo,
              int64_t hi, int* a, int* b) {
  const auto& arr = loc.array(node, key, 2, 2, "[smallest, largest]");
  *a = int(loc.integer(*arr.get(0), key, lo, hi));
  *b = int(loc.integer(*arr.get(1), key, lo, hi));
  if (*b < *a) loc.fail(&node, "'" + key + "' must be [smallest, largest] (allowed: smallest <= largest)");
}

void parse_categories(const Locator& loc, const toml::table& t, const std::string& where,
                      std::array<double, kCategories>* out) {
  std::set<std::string> names;
  for (int i = 0; i < kCategories; ++i) names.insert(category_name(Category(i)));
  loc.reject_unknown_keys(t, where + ".", names);
  for (int i = 0; i < kCategories; ++i) {
    const std::string name = category_name(Category(i));
    if (const auto* n = t.get(name))
      (*out)[i] = loc.number(*n, where + "." + name, "0 to 1", [](double v) { return v >= 0 && v <= 1; });
  }
}

// Every random instance's exact DP must fit dp_max_cells (random_instance_dp_cells): the error
// names the largest max_cost and objects that would fit, or the dp_max_cells that would.
[[noreturn]] void fail_dp_too_large(const Locator& loc, const toml::table& t, const toml::table& rt,
                                    const RegulationSettings& s) {
  RandomInstanceSettings r = s.random;
  int64_t cost_max = 0;  // the largest max_cost that fits, 0: none
  for (int64_t lo = 1, hi = 100000; lo <= hi;) {
    r.max_cost = lo + (hi - lo) / 2;
    if (random_instance_dp_cells(r) <= s.dp_max_cells) cost_max = r.max_cost, lo = r.max_cost + 1;
    else hi = r.max_cost - 1;
  }
  r.max_cost = s.random.max_cost;
  int objects_max = 0;  // the largest objects_max that fits with this max_cost, 0: none
  for (int n = 1; n <= 64; ++n) {
    r.objects_max = n;
    if (random_instance_dp_cells(r) <= s.dp_max_cells) objects_max = n;
  }
  std::string allowed;
  if (cost_max > 0) allowed += "regulation.random.max_cost <= " + std::to_string(cost_max) + " with these objects";
  if (objects_max >= s.random.objects_min)
    allowed += std::string(allowed.empty() ? "" : ", or ") + "regulation.random.objects up to " +
               std::to_string(objects_max) + " with this max_cost";
  allowed += std::string(allowed.empty() ? "" : ", or ") + "regulation.dp_max_cells >= " +
             std::to_string(random_instance_dp_cells(s.random));
  const toml::node* at = rt.get("max_cost");
  if (!at) at = rt.get("objects");
  if (!at) at = t.get("dp_max_cells");
  if (!at) at = t.get("random");
  loc.fail(at, "'regulation.random.max_cost' = " + std::to_string(s.random.max_cost) +
                   " with 'regulation.random.objects' = [" + std::to_string(s.random.objects_min) + ", " +
                   std::to_string(s.random.objects_max) + "] needs an exact DP of up to " +
                   std::to_string(random_instance_dp_cells(s.random)) + " cells, more than " +
                   "'regulation.dp_max_cells' = " + std::to_string(s.dp_max_cells) + " (allowed: " +
                   allowed + ")");
}

// [regulation.cost_model]: explicit coefficients or a timing study's JSON.
void parse_cost_model(const Locator& loc, const toml::table& t, const std::string& path,
                      RegulationSettings& s) {
  const toml::table empty;
  const toml::table& cm = table_of(loc, t, "cost_model", "regulation.cost_model", empty);
  loc.reject_unknown_keys(cm, "regulation.cost_model.",
                          {"c1_us_per_tv", "c2_us_per_pixel", "intercept_us", "pixel_factor",
                           "cost_unit_us", "timing_json", "timing_platform", "timing_intercept", "pixels"});
  auto nonneg = [](double v) { return v >= 0; };
  if (const auto* n = cm.get("c1_us_per_tv")) s.cost.c1_us_per_tv = loc.number(*n, "regulation.cost_model.c1_us_per_tv", ">= 0", nonneg);
  if (const auto* n = cm.get("c2_us_per_pixel")) s.cost.c2_us_per_pixel = loc.number(*n, "regulation.cost_model.c2_us_per_pixel", ">= 0", nonneg);
  if (const auto* n = cm.get("intercept_us")) s.cost.intercept_us = loc.number(*n, "regulation.cost_model.intercept_us", "a finite number", [](double) { return true; });
  if (const auto* n = cm.get("pixel_factor")) s.cost.pixel_factor = loc.number(*n, "regulation.cost_model.pixel_factor", "0 < factor <= 100", [](double v) { return v > 0 && v <= 100; });
  if (const auto* n = cm.get("cost_unit_us")) s.cost.cost_unit_us = loc.number(*n, "regulation.cost_model.cost_unit_us", "0 < unit <= 1000000", [](double v) { return v > 0 && v <= 1e6; });
  if (const auto* n = cm.get("pixels")) {
    const auto* str = n->as_string();
    if (!str || (str->get() != "measured" && str->get() != "estimated"))
      loc.fail(n, "'regulation.cost_model.pixels' must be a string (allowed: \"measured\", \"estimated\")");
    s.cost.measured_pixels = str->get() == "measured";
  }
  s.cost.source = "explicit coefficients in " + path;
  s.timing_platform = s.platform;
  if (const auto* n = cm.get("timing_platform")) {
    const auto* str = n->as_string();
    if (!str || str->get().empty()) loc.fail(n, "'regulation.cost_model.timing_platform' must be a platform name");
    s.timing_platform = str->get();
  }
  if (const auto* n = cm.get("timing_intercept")) s.timing_intercept = loc.boolean(*n, "regulation.cost_model.timing_intercept");
  if (const auto* n = cm.get("timing_json")) {
    const auto* str = n->as_string();
    if (!str || str->get().empty()) loc.fail(n, "'regulation.cost_model.timing_json' must be a path");
    std::filesystem::path p(str->get());
    if (p.is_relative()) p = std::filesystem::path(path).parent_path() / p;
    s.timing_json = p.lexically_normal().string();
    if (!std::filesystem::exists(s.timing_json))
      loc.fail(n, "'regulation.cost_model.timing_json' = " + s.timing_json + " does not exist");
    for (const char* k : {"c1_us_per_tv", "c2_us_per_pixel", "intercept_us"})
      if (cm.get(k)) loc.fail(cm.get(k), std::string("'regulation.cost_model.") + k + "' and timing_json exclude each other");
    try {
      s.cost = cost_model_from_timing_json(s.timing_json, s.timing_platform, s.timing_intercept, s.cost);
    } catch (const util::UserError& e) {
      loc.fail(n, e.what());
    }
  }
}

// [regulation.attention]: the attention model's probabilities, shares and tags.
void parse_attention(const Locator& loc, const toml::table& t, RegulationSettings& s) {
  const toml::table empty;
  const toml::table& at = table_of(loc, t, "attention", "regulation.attention", empty);
  loc.reject_unknown_keys(at, "regulation.attention.", {"alpha", "element_given_object", "probability", "share", "tags"});
  auto unit = [](double v) { return v >= 0 && v <= 1; };
  if (const auto* n = at.get("alpha")) s.attention.alpha = loc.number(*n, "regulation.attention.alpha", "0 to 1", unit);
  if (const auto* n = at.get("element_given_object"))
    s.attention.element_given_object = loc.number(*n, "regulation.attention.element_given_object", "0 to 1", unit);
  parse_categories(loc, table_of(loc, at, "probability", "regulation.attention.probability", empty),
                   "regulation.attention.probability", &s.attention.probability);
  if (const auto* n = at.get("share")) {
    parse_categories(loc, table_of(loc, at, "share", "regulation.attention.share", empty),
                     "regulation.attention.share", &s.attention.share);
    double sum = 0;
    for (double v : s.attention.share) sum += v;
    if (std::abs(sum - 1) > 1e-9)
      loc.fail(n, "'regulation.attention.share' sums to " + util::significant(sum, 6) + " (allowed: the shares sum to 1)");
  }
  const toml::table& tags = table_of(loc, at, "tags", "regulation.attention.tags", empty);
  for (const auto& [key, node] : tags) {
    const auto* str = node.as_string();
    Category c;
    if (!str || !parse_category(str->get(), &c))
      loc.fail(&node, "'regulation.attention.tags.\"" + std::string(key.str()) +
                          "\"' must be a category (allowed: primary_actor, secondary_actor, "
                          "critical_environment, background)");
    s.attention.tags[std::string(key.str())] = c;
  }
}

// [regulation.random]: the random knapsack instances, each small enough for the exact DP.
void parse_random(const Locator& loc, const toml::table& t, RegulationSettings& s) {
  const toml::table empty;
  const toml::table& rt = table_of(loc, t, "random", "regulation.random", empty);
  loc.reject_unknown_keys(rt, "regulation.random.",
                          {"instances", "objects", "levels", "max_cost", "adversarial_every", "brute_force_max_plans"});
  s.random.seed = s.seed;
  if (const auto* n = rt.get("instances")) s.random.instances = int(loc.integer(*n, "regulation.random.instances", 0, 1000000));
  if (const auto* n = rt.get("objects")) int_pair(loc, *n, "regulation.random.objects", 1, 64, &s.random.objects_min, &s.random.objects_max);
  if (const auto* n = rt.get("levels")) int_pair(loc, *n, "regulation.random.levels", 1, 16, &s.random.levels_min, &s.random.levels_max);
  if (const auto* n = rt.get("max_cost")) s.random.max_cost = loc.integer(*n, "regulation.random.max_cost", 1, 100000);
  if (const auto* n = rt.get("adversarial_every")) s.random.adversarial_every = int(loc.integer(*n, "regulation.random.adversarial_every", 0, 1000000));
  if (const auto* n = rt.get("brute_force_max_plans")) s.random.brute_force_max_plans = loc.integer(*n, "regulation.random.brute_force_max_plans", 0, 10000000);
  s.random.dp_max_cells = s.dp_max_cells;
  if (s.random.instances > 0 && random_instance_dp_cells(s.random) > s.dp_max_cells)
    fail_dp_too_large(loc, t, rt, s);
}

}  // namespace

void validate_platform(const std::string& name) {
  if (!rundir::is_aliased_gl_platform(name))
    throw util::UserError("'regulation.platform' = \"" + name + "\" is out of range (allowed: " +
                          rundir::aliased_gl_platform_names() + ")");
}

RegulationSettings read_regulation_experiment(const std::string& path) {
  return parse_regulation_experiment(util::TomlLocator::read_text(path), path);
}

RegulationSettings parse_regulation_experiment(const std::string& text, const std::string& path) {
  Locator loc(path);
  RegulationSettings s;
  const scenes::StudyFile file =
      scenes::read_study_file(loc, text, "regulation", {"scene"}, true, &s);
  const toml::table& root = file.root;
  const toml::table& t = file.table();
  loc.reject_unknown_keys(t, "regulation.",
                          {"platform", "window", "fov_deg", "near", "far", "lod_ratios", "cache_size",
                           "seed", "budgets_ms", "frame_stride", "repetitions", "render",
                           "error_exponent", "dp_max_cells", "cost_model", "attention", "random"});
  if (const auto* n = t.get("platform"))
    s.platform = scenes::read_study_platform(loc, *n, "regulation.platform");
  scenes::read_camera_block(loc, t, "regulation", &s.camera);
  if (const auto* n = t.get("lod_ratios")) {
    const auto& a = loc.array(*n, "regulation.lod_ratios", 2, 16, "an array of 2 to 16 ratios");
    s.lod_ratios.clear();
    for (std::size_t i = 0; i < a.size(); ++i) {
      const double prev = i ? s.lod_ratios.back() : 2.0;
      const std::string allowed = i == 0 ? "the first ratio is 1" : "below the previous ratio, above 0";
      s.lod_ratios.push_back(loc.number(*a.get(i), "regulation.lod_ratios", allowed, [&](double v) {
        return i == 0 ? v == 1.0 : (v > 0 && v < prev);
      }));
    }
  }
  if (const auto* n = t.get("cache_size")) s.cache_size = unsigned(loc.integer(*n, "regulation.cache_size", 3, 1024));
  if (const auto* n = t.get("seed")) s.seed = uint64_t(loc.integer(*n, "regulation.seed", 0, INT64_MAX));
  if (const auto* n = t.get("budgets_ms")) {
    const auto& a = loc.array(*n, "regulation.budgets_ms", 1, 64, "an array of 1 to 64 budgets in ms");
    s.budgets_ms.clear();
    for (std::size_t i = 0; i < a.size(); ++i) {
      const double prev = i ? s.budgets_ms.back() : 0.0;
      s.budgets_ms.push_back(loc.number(*a.get(i), "regulation.budgets_ms",
                                    "increasing, each in (0, 10000]",
                                    [&](double v) { return v > prev && v <= 10000; }));
    }
  }
  if (const auto* n = t.get("frame_stride")) s.frame_stride = int(loc.integer(*n, "regulation.frame_stride", 1, 100000));
  if (const auto* n = t.get("repetitions")) s.repetitions = int(loc.integer(*n, "regulation.repetitions", 1, 1000));
  if (const auto* n = t.get("render")) s.render = loc.boolean(*n, "regulation.render");
  if (const auto* n = t.get("error_exponent"))
    s.error_exponent = loc.number(*n, "regulation.error_exponent", "0 < exponent <= 8",
                              [](double v) { return v > 0 && v <= 8; });
  if (const auto* n = t.get("dp_max_cells"))
    s.dp_max_cells = loc.integer(*n, "regulation.dp_max_cells", 1000, 4'000'000'000);

  parse_cost_model(loc, t, path, s);
  parse_attention(loc, t, s);
  parse_random(loc, t, s);

  std::vector<scenes::SceneSpec> scenes = scenes::parse_scene_specs(root, path);
  if (scenes.size() != 1) {
    const toml::node* n = root.get("scene");
    loc.fail(n, "the regulation study needs exactly one [[scene]] (found " + std::to_string(scenes.size()) + ")");
  }
  s.scene = scenes.front();
  return s;
}

}  // namespace ra::regulation
