// The regulation study: run, analyze, plot (regulation_study.h).
#include "regulation/regulation_study.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "platforms/platform_probe.h"
#include "plots/figure.h"
#include "plots/figure_set.h"
#include "regulation/attention.h"
#include "regulation/lod_chain.h"
#include "regulation/plan_rendering.h"
#include "regulation/policies.h"
#include "regulation/random_instances.h"
#include "regulation/regulation_experiment.h"
#include "rundir/manifest.h"
#include "rundir/run_folder.h"
#include "stats/descriptive.h"
#include "stats/table_writer.h"
#include "util/atomic_file.h"
#include "util/cell_text.h"
#include "util/errors.h"
#include "util/number_text.h"

namespace ra::regulation {
namespace {

using nlohmann::json;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

json nullable(double v) { return std::isfinite(v) ? json(v) : json(); }

// A number of a JSON document through a printf format, "n/a" where it is null (not finite).
std::string fmt(const json& v, const char* f = "%.4g") {
  return v.is_number() ? util::format_double(f, v.get<double>()) : "n/a";
}

// Quantiles of the finite values (HF6); nulls when there are none.
json quantiles(std::vector<double> v) {
  v.erase(std::remove_if(v.begin(), v.end(), [](double x) { return !std::isfinite(x); }), v.end());
  if (v.empty()) return {{"n", 0}};
  std::sort(v.begin(), v.end());
  return {{"n", v.size()},
          {"min", v.front()},
          {"q50", stats::quantile_sorted(v, 0.5)},
          {"q90", stats::quantile_sorted(v, 0.9)},
          {"q99", stats::quantile_sorted(v, 0.99)},
          {"max", v.back()},
          {"mean", stats::mean(v)}};
}

const char* kTitle = "Decision-theoretic regulation of levels of detail";

}  // namespace

namespace {

// Random instances: greedy against the exact optimum (and brute force on small ones); writes
// instances.csv, fills j["random"], returns the number of instances.
std::size_t random_instances_stage(const RegulationSettings& s, const std::string& dir, json& j,
                                   std::vector<std::string>& findings) {
  const auto t = Clock::now();
  const std::vector<InstanceComparison> inst = run_random_instances(s.random);
  util::write_file_atomic(dir + "/instances.csv", instances_csv(inst));
  std::vector<double> ratio, ratio_only, loss_ratio;
  int over2 = 0, over2_only = 0, brute = 0, mismatch = 0, over_budget = 0, adversarial = 0, no_opt = 0;
  for (const InstanceComparison& c : inst) {
    ratio.push_back(c.value_ratio);
    ratio_only.push_back(c.value_ratio_ratio_only);
    loss_ratio.push_back(c.loss_ratio);
    over2 += c.value_ratio > 2 + 1e-9;
    over2_only += c.value_ratio_ratio_only > 2 + 1e-9;
    brute += c.brute_forced;
    mismatch += !c.dp_matches_brute_force;
    over_budget += !c.within_budget;
    adversarial += c.adversarial;
    no_opt += !c.optimum_computed;
  }
  j["random"] = {{"instances", inst.size()},
                 {"adversarial", adversarial},
                 {"objects", {s.random.objects_min, s.random.objects_max}},
                 {"levels", {s.random.levels_min, s.random.levels_max}},
                 {"max_cost", s.random.max_cost},
                 {"brute_forced", brute},
                 {"dp_mismatches", mismatch},
                 {"over_budget", over_budget},
                 {"optimum_not_computed", no_opt},
                 {"value_ratio", quantiles(ratio)},
                 {"value_ratio_above_2", over2},
                 {"value_ratio_ratio_only", quantiles(ratio_only)},
                 {"value_ratio_ratio_only_above_2", over2_only},
                 {"loss_ratio", quantiles(loss_ratio)},
                 {"seconds", seconds_since(t)}};
  std::vector<json> r, ro;
  for (double v : ratio) r.push_back(nullable(v));
  for (double v : ratio_only) ro.push_back(nullable(v));
  j["random"]["ratios"] = r;
  j["random"]["ratios_ratio_only"] = ro;
  if (over2) findings.push_back(std::to_string(over2) + " random instances with value(OPT) / value(greedy) > 2");
  if (mismatch) findings.push_back(std::to_string(mismatch) + " random instances where the DP differs from brute force");
  if (over_budget) findings.push_back(std::to_string(over_budget) + " random instances with a plan over budget");
  return inst.size();
}

// The scene, its LOD chains (lod_levels.csv) and attention tags; fills j["lod"], j["scene"],
// j["cost_model"] and j["attention"].
struct StudyScene {
  scenes::Scene scene;
  std::vector<scenes::Viewpoint> path;
  std::vector<LodChain> chains;
  std::vector<double> weights;  // attention weight of each object
};

StudyScene scene_stage(const RegulationSettings& s, const std::string& dir, json& j) {
  const auto t = Clock::now();
  StudyScene out;
  out.scene = scenes::build_scene(s.scene);
  out.path = scenes::build_camera_path(s.scene, out.scene);
  std::vector<LodChain>& chains = out.chains;
  const scenes::Scene& scene = out.scene;
  const std::vector<scenes::Viewpoint>& path = out.path;
  std::vector<std::string> names;
  for (const scenes::SceneObject& o : scene.objects) {
    chains.push_back(build_lod_chain(o, s.lod_ratios, s.cache_size));
    names.push_back(o.name);
  }
  const std::vector<Category> tags = tag_objects(names, s.attention, s.seed);
  std::vector<double>& weights = out.weights;
  std::map<std::string, int> tag_count;
  for (Category c : tags) {
    weights.push_back(attention_weight(s.attention, c));
    ++tag_count[category_name(c)];
  }
  {
    std::ostringstream o;
    o << "object,name,category,attention_weight,level,target_ratio,triangles,vertices,transformed,"
         "error_m,simplifier_error_m\n";
    for (std::size_t i = 0; i < chains.size(); ++i)
      for (std::size_t k = 0; k < chains[i].levels.size(); ++k) {
        const LodLevel& l = chains[i].levels[k];
        o << i << ',' << util::csv_escape(chains[i].name) << ',' << category_name(tags[i]) << ','
          << util::full_precision(weights[i]) << ',' << k << ','
          << util::full_precision(l.target_ratio) << ',' << l.triangles << ',' << l.vertices << ','
          << l.transformed << ',' << util::full_precision(l.error_m) << ','
          << util::full_precision(l.simplifier_error_m) << '\n';
      }
    util::write_file_atomic(dir + "/lod_levels.csv", o.str());
    json lod = json::array();
    for (std::size_t k = 0; k < s.lod_ratios.size(); ++k) {
      int64_t objects = 0, tris = 0, tv = 0;
      std::vector<double> err;
      for (const LodChain& c : chains) {
        // objects whose chain stopped early are counted at their last level
        const LodLevel& l = c.levels[std::min(k, c.levels.size() - 1)];
        objects += k < c.levels.size();
        tris += l.triangles;
        tv += l.transformed;
        err.push_back(l.error_m);
      }
      const json q = quantiles(err);
      lod.push_back({{"level", k}, {"target_ratio", s.lod_ratios[k]}, {"objects_with_level", objects},
                     {"triangles", tris}, {"transformed", tv}, {"error_median_m", q.value("q50", json())},
                     {"error_max_m", q.value("max", json())}});
    }
    j["lod"] = lod;
  }
  j["scene"] = {{"name", s.scene.name}, {"kind", scene.kind}, {"objects", scene.objects.size()},
                {"path_frames", path.size()}, {"frame_stride", s.frame_stride},
                {"lod_seconds", seconds_since(t)}};
  j["cost_model"] = {{"form", "b0 + c1 * tv + c2 * pixel_factor * pix"},
                     {"c1_us_per_tv", s.cost.c1_us_per_tv}, {"c2_us_per_pixel", s.cost.c2_us_per_pixel},
                     {"intercept_us", s.cost.intercept_us}, {"pixel_factor", s.cost.pixel_factor},
                     {"cost_unit_us", s.cost.cost_unit_us}, {"source", s.cost.source},
                     {"pixels_requested", s.cost.measured_pixels ? "measured" : "estimated"}};
  json probs = json::object();
  for (int c = 0; c < kCategories; ++c)
    probs[category_name(Category(c))] = {{"probability", s.attention.probability[c]},
                                         {"share", s.attention.share[c]},
                                         {"weight", attention_weight(s.attention, Category(c))},
                                         {"objects", tag_count[category_name(Category(c))]}};
  j["attention"] = {{"alpha", s.attention.alpha}, {"element_given_object", s.attention.element_given_object},
                    {"categories", probs}, {"declared_tags", s.attention.tags.size()},
                    {"error_exponent", s.error_exponent}};
  return out;
}

// budget_sweep.csv, frames.csv and (when measured) pixels.csv from the rendered plans.
void write_plan_tables(const RenderOutcome& ro, const std::vector<LodChain>& chains,
                       const std::string& dir, json& j) {
  std::ostringstream sw, fr;
  sw << "frame,budget_ms,policy,visible,budget_units,plan_units,fits,expected_cost,value,"
        "value_ratio_opt_over_policy,predicted_us,triangles,pixels,predicted_estimated_us,transformed\n";
  fr << "frame,budget_ms,policy,predicted_us,measured_median_us,skipped,repetitions,measured_us,"
        "predicted_estimated_us\n";
  for (const FrameRecord& r : ro.records) {
    sw << r.frame << ',' << util::full_precision(r.budget_ms) << ',' << r.policy << ',' << r.visible
       << ',' << r.budget_units << ',' << r.plan_units << ',' << int(r.fits) << ','
       << util::full_precision(r.expected_cost) << ',' << util::full_precision(r.value) << ','
       << util::full_precision(r.value_ratio_to_optimal) << ','
       << util::full_precision(r.predicted_us) << ',' << r.triangles << ','
       << util::full_precision(r.pixels) << ',' << util::full_precision(r.predicted_estimated_us)
       << ',' << r.transformed << '\n';
    std::string reps;
    for (double v : r.measured_us) reps += (reps.empty() ? "" : ";") + util::full_precision(v);
    fr << r.frame << ',' << util::full_precision(r.budget_ms) << ',' << r.policy << ','
       << util::full_precision(r.predicted_us) << ',' << util::full_precision(r.measured_median_us)
       << ',' << int(r.skipped) << ',' << r.measured_us.size() << ',' << reps << ','
       << util::full_precision(r.predicted_estimated_us) << '\n';
  }
  util::write_file_atomic(dir + "/budget_sweep.csv", sw.str());
  util::write_file_atomic(dir + "/frames.csv", fr.str());
  if (ro.pixels_measured) {
    std::ostringstream px;
    px << "frame,object,name,distance_m,radius_m,estimated_pixels,level,measured_pixels\n";
    std::vector<double> ratio;  // measured level 0 / estimated, objects seen whole and far
    for (const PixelSample& p : ro.pixels) {
      for (std::size_t k = 0; k < p.measured.size(); ++k)
        px << p.frame << ',' << p.object << ',' << util::csv_escape(chains[p.object].name) << ','
           << util::full_precision(p.distance_m) << ',' << util::full_precision(p.radius_m) << ','
           << util::full_precision(p.estimated) << ',' << k << ','
           << util::full_precision(p.measured[k]) << '\n';
      if (p.estimated > 0 && !p.measured.empty()) ratio.push_back(p.measured[0] / p.estimated);
    }
    util::write_file_atomic(dir + "/pixels.csv", px.str());
    j["cost_model"]["measured_over_estimated_pixels"] = quantiles(ratio);
  }
}

// Per policy and budget: costs, predictions against measurements, value against the optimum;
// fills j["sweep"] and the render's error summaries.
void sweep_stage(const RegulationSettings& s, const RenderOutcome& ro, json& j,
                 std::vector<std::string>& findings) {
  json sweep = json::array(), points = json::array();
  int scene_over2 = 0, greedy_over = 0, scene_no_opt = 0;
  std::vector<double> all_abs_rel, all_abs_rel_est;
  for (Policy p : kAllPolicies)
    for (double b : s.budgets_ms) {
      std::vector<double> cost, pred, meas, rel, ratio, abs_rel, abs_rel_est;
      int frames = 0, fits = 0, skips = 0, rendered = 0, feasible = 0;
      for (const FrameRecord& r : ro.records) {
        if (r.policy != policy_name(p) || r.budget_ms != b) continue;
        ++frames;
        fits += r.fits;
        feasible += r.feasible;
        cost.push_back(r.expected_cost);
        pred.push_back(r.predicted_us / 1000.0);
        ratio.push_back(r.value_ratio_to_optimal);
        if (p == Policy::kGreedy && r.value_ratio_to_optimal > 2 + 1e-9) ++scene_over2;
        if (p == Policy::kGreedy && r.feasible && !r.fits) ++greedy_over;
        if (p == Policy::kGreedy && std::isnan(r.value_ratio_to_optimal)) ++scene_no_opt;
        if (!r.measured_us.empty()) {
          ++rendered;
          skips += r.skipped;
          meas.push_back(r.measured_median_us / 1000.0);
          rel.push_back((r.measured_median_us - r.predicted_us) / r.predicted_us);
          abs_rel.push_back(std::abs(r.predicted_us - r.measured_median_us) / r.measured_median_us);
          abs_rel_est.push_back(std::abs(r.predicted_estimated_us - r.measured_median_us) /
                                r.measured_median_us);
          all_abs_rel.push_back(abs_rel.back());
          all_abs_rel_est.push_back(abs_rel_est.back());
          points.push_back({{"policy", r.policy}, {"budget_ms", b}, {"frame", r.frame},
                            {"predicted_ms", r.predicted_us / 1000.0},
                            {"measured_ms", r.measured_median_us / 1000.0}});
        }
      }
      if (!frames) continue;
      const json qc = quantiles(cost), qp = quantiles(pred), qm = quantiles(meas), qr = quantiles(rel),
                 qv = quantiles(ratio);
      sweep.push_back({{"policy", policy_name(p)}, {"budget_ms", b}, {"frames", frames},
                       {"fits", fits}, {"feasible", feasible}, {"mean_expected_cost", qc.value("mean", json())},
                       {"median_expected_cost", qc.value("q50", json())},
                       {"mean_predicted_ms", qp.value("mean", json())},
                       {"max_value_ratio_to_optimal", qv.value("max", json())},
                       {"rendered", rendered}, {"skips", skips},
                       {"skip_fraction", rendered ? json(double(skips) / rendered) : json()},
                       {"median_measured_ms", qm.value("q50", json())},
                       {"median_relative_error", qr.value("q50", json())},
                       {"median_abs_relative_error", quantiles(abs_rel).value("q50", json())},
                       {"median_abs_relative_error_estimated_pixels",
                        quantiles(abs_rel_est).value("q50", json())}});
    }
  j["sweep"] = sweep;
  j["render"]["points"] = points;
  // |predicted - measured| / measured over every rendered plan: the prediction used, and the
  // same plans predicted with the estimated #pix
  j["render"]["abs_relative_error"] = quantiles(all_abs_rel);
  j["render"]["abs_relative_error_estimated_pixels"] = quantiles(all_abs_rel_est);
  j["scene_value_ratio_above_2"] = scene_over2;
  // frame x budget instances whose exact DP would exceed dp_max_cells (no optimal row for them)
  j["scene_optimum_not_computed"] = scene_no_opt;
  if (scene_over2) findings.push_back(std::to_string(scene_over2) + " scene frames with value(OPT) / value(greedy) > 2");
  if (greedy_over) findings.push_back(std::to_string(greedy_over) + " scene frames where greedy's plan exceeds a feasible budget");
}

// The lines `renderaudit run` prints when the study is done.
std::string summary_text(const json& j, const std::string& dir, std::size_t instances,
                         const std::vector<std::string>& findings) {
  std::ostringstream sum;
  const json& rq = j["random"]["value_ratio"];
  sum << "regulation study -> " << dir << " (" << fmt(j["wall_s"], "%.1f") << " s)\n"
      << "random instances: " << instances << ", value(OPT)/value(greedy) max " << fmt(rq.value("max", json()))
      << ", median " << fmt(rq.value("q50", json())) << "; ratio-only greedy max "
      << fmt(j["random"]["value_ratio_ratio_only"].value("max", json())) << "\n";
  for (const json& row : j["sweep"])
    if (row["policy"] == "greedy")
      sum << "budget " << fmt(row["budget_ms"]) << " ms: greedy expected cost "
          << fmt(row["mean_expected_cost"]) << ", skips " << row["skips"].get<int>() << "/"
          << row["rendered"].get<int>() << "\n";
  for (const std::string& f : findings) sum << "FINDING: " << f << "\n";
  return sum.str();
}
}  // namespace

rundir::StudyRunResult run_regulation_study(const rundir::StudyRunOptions& options) {
  const auto t_start = Clock::now();
  RegulationSettings s = read_regulation_experiment(options.experiment);
  if (!options.platforms.empty()) {
    if (options.platforms.size() != 1)
      throw util::UserError(
          "the regulation study renders on one platform: give at most one --platform");
    try {
      validate_platform(options.platforms.front());  // names the allowed platforms
    } catch (const util::UserError& e) {
      throw util::UserError(std::string("--platform: ") + e.what());
    }
    s.platform = options.platforms.front();
  }
  const std::string dir = options.out_dir.empty() ? "outputs/" + s.name : options.out_dir;
  if (s.render)
    platforms::require_platforms_draw({s.platform}, options.experiment);  // before any write
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (!std::filesystem::is_directory(dir))
    throw util::UserError("cannot create the output directory " + dir + ": " + ec.message());
  // a folder is complete only when it is rewritten
  std::filesystem::remove(rundir::run_folder::study(dir));
  // derived outputs of an earlier run (analyze, plot) would describe the old numbers
  std::filesystem::remove(dir + "/regulation.md", ec);
  std::filesystem::remove_all(rundir::run_folder::figures(dir), ec);
  auto say = [&](const std::string& line) {
    if (options.progress) std::fprintf(stderr, "regulation: %s\n", line.c_str());
  };

  json j = rundir::document_header("regulation", 1);
  j["experiment"] = {{"file", s.file}, {"name", s.name}};
  std::vector<std::string> findings;

  say("random instances: " + std::to_string(s.random.instances));
  const std::size_t instances = random_instances_stage(s, dir, j, findings);
  say("scene " + s.scene.name + " and LOD chains");
  const StudyScene st = scene_stage(s, dir, j);

  // ---- plans along the path, rendered ----
  say(std::string(s.render ? "planning and rendering on " + s.platform : "planning (no rendering)"));
  const RenderOutcome ro = plan_and_render(st.scene, st.chains, st.weights, st.path, s, dir, options.progress);
  j["platform"] = s.platform;
  j["render"] = {{"enabled", s.render}, {"renderer", ro.renderer}, {"version", ro.version},
                 {"base_us", ro.base_us}, {"base_reps_us", ro.base_reps_us},
                 {"repetitions", s.repetitions}, {"seconds", ro.seconds},
                 {"error", ro.error.empty() ? json() : json(ro.error)}};
  if (!ro.error.empty()) findings.push_back("rendering failed: " + ro.error);
  j["cost_model"]["pixels"] =
      ro.pixels_measured
          ? "measured: GL_SAMPLES_PASSED of each level of each visible object drawn alone, depth test off, per frame"
          : "estimated: projected bounding-sphere disc clipped to the window";
  j["cost_model"]["pixels_measured"] = ro.pixels_measured;
  write_plan_tables(ro, st.chains, dir, j);
  sweep_stage(s, ro, j, findings);
  j["findings"] = findings;
  j["wall_s"] = seconds_since(t_start);
  util::write_file_atomic(dir + "/regulation.json", j.dump(1) + "\n");

  rundir::StudyInfo info;
  info.kind = rundir::StudyKind::kRegulation;
  info.name = s.name;
  info.title = kTitle;
  info.subtitle = "Horvitz & Lengyel (UAI 1997) on " + s.scene.name + ": greedy marginal-value "
                  "regulation against the exact optimum and baselines, and the chosen plans rendered on " +
                  s.platform + ".";
  rundir::write_study_info(dir, info);  // last: the folder is complete

  rundir::StudyRunResult res;
  res.dir = dir;
  res.findings = !findings.empty();
  res.summary = summary_text(j, dir, instances, findings);
  return res;
}

namespace {

json load_complete(const std::string& dir) {
  const auto info = rundir::read_study_info(dir);
  if (!info || info->kind != rundir::StudyKind::kRegulation)
    throw util::UserError(dir +
                          " is not a complete regulation study (no study.json of kind regulation: "
                          "run `renderaudit run` on a regulation experiment first)");
  try {
    return json::parse(util::read_file(dir + "/regulation.json"));
  } catch (const std::exception& e) {
    throw util::UserError(dir + "/regulation.json cannot be read: " + e.what());
  }
}

std::string regulation_markdown(const json& j) {
  std::ostringstream md;
  const json& sc = j["scene"];
  const json& cm = j["cost_model"];
  const json& rnd = j["random"];
  const json& rq = rnd["value_ratio"];
  md << "# Decision-theoretic regulation\n\n"
     << "Horvitz & Lengyel, Perception, Attention, and Resources: A Decision-Theoretic Approach to "
        "Graphics Rendering (UAI 1997), sections 5-7, with levels of detail in place of Talisman's "
        "sprites: experiment `" << j["experiment"].value("file", "") << "`, scene `"
     << sc.value("name", "") << "` (" << sc.value("kind", "") << ", " << sc.value("objects", 0)
     << " objects, " << sc.value("path_frames", 0) << " path frames, planned every "
     << sc.value("frame_stride", 1) << " frames), computed " << j.value("created_utc", "") << ".\n\n";
  md << "### Method\n\n"
     << "- **Levels of detail**: meshoptimizer's `meshopt_simplify` per texture group at the target "
        "triangle ratios below, restripified; the error of a level is the simplifier's, in metres.\n"
     << "- **Time** (the timing study's H4): " << fmt(cm["intercept_us"]) << " us + "
     << fmt(cm["c1_us_per_tv"]) << " us x #tv + " << fmt(cm["c2_us_per_pixel"]) << " us x #pix ("
     << cm.value("source", "") << "); #pix " << cm.value("pixels", "") << "; knapsack costs rounded up to "
     << fmt(cm["cost_unit_us"]) << " us.\n"
     << "- **Perceptual cost** (section 7.2): screen-area fraction x (projected geometric error in "
        "pixels)^" << fmt(j["attention"]["error_exponent"]) << ", 0 at full detail.\n"
     << "- **Attention** (equations 4 and 6, alpha = " << fmt(j["attention"]["alpha"])
     << "): each object is weighted by q + (1 - q) alpha, q = p(A_S | A_O) p(A_O).\n"
     << "- **Policies**: `greedy` = increments of each object's convex-hull upgrade chain in "
        "decreasing Phi = gain / cost, compared with the best single-object upgrade (the better "
        "of the two); `greedy_ratio_only` = without that check; `optimal` = dynamic programme over "
        "the integer budget; `uniform` = the finest single level for all objects that fits; "
        "`distance` = levels by distance bands scaled until the plan fits.\n\n";

  md << "### Attention categories\n\n"
     << stats::markdown_header({"Category", "p(attend)", "Seeded share", "Weight", "Objects"}, 1);
  for (const auto& [name, c] : j["attention"]["categories"].items())
    md << stats::markdown_row({name, fmt(c["probability"], "%.2f"), fmt(c["share"], "%.2f"), fmt(c["weight"], "%.3f"),
               std::to_string(c.value("objects", 0))});
  md << "\n### Levels of detail (all objects)\n\n"
     << stats::markdown_header({"Level", "Target ratio", "Objects with it", "Triangles", "#tv", "Median error m", "Max error m"}, 1);
  for (const json& l : j["lod"])
    md << stats::markdown_row({std::to_string(l.value("level", 0)), fmt(l["target_ratio"], "%.4g"),
               std::to_string(l.value("objects_with_level", 0)), std::to_string(l.value("triangles", 0)),
               std::to_string(l.value("transformed", 0)), fmt(l["error_median_m"], "%.3g"),
               fmt(l["error_max_m"], "%.3g")});
  md << "\nAn object whose simplifier could not reduce further keeps fewer levels (counted at its last "
        "level in the sums).\n\n";

  md << "### Greedy against the optimum on random instances\n\n"
     << "The factor-two guarantee holds for the **value**, the expected perceptual cost saved over "
        "the all-coarsest plan: value(OPT) <= 2 value(greedy). The ratio of the expected costs "
        "themselves has no bound.\n\n"
     << stats::markdown_header({"Quantity", "n", "Median", "q90", "q99", "Max", "Above 2"}, 1);
  auto qrow = [&](const std::string& name, const json& q, const json& above) {
    md << stats::markdown_row({name, std::to_string(q.value("n", 0)), fmt(q.value("q50", json())), fmt(q.value("q90", json())),
               fmt(q.value("q99", json())), fmt(q.value("max", json())),
               above.is_number() ? std::to_string(above.get<int>()) : "-"});
  };
  qrow("value(OPT) / value(greedy)", rq, rnd["value_ratio_above_2"]);
  qrow("value(OPT) / value(greedy, ratio only)", rnd["value_ratio_ratio_only"], rnd["value_ratio_ratio_only_above_2"]);
  qrow("cost(greedy) / cost(OPT), expected perceptual cost", rnd["loss_ratio"], json());
  md << "\n" << rnd.value("instances", 0) << " instances (" << rnd.value("adversarial", 0)
     << " adversarial: the trap of the single-item check and its tight case), "
     << rnd["objects"][0].get<int>() << "-" << rnd["objects"][1].get<int>() << " objects of "
     << rnd["levels"][0].get<int>() << "-" << rnd["levels"][1].get<int>() << " levels; the DP was checked "
        "against brute force on " << rnd.value("brute_forced", 0) << " of them ("
     << rnd.value("dp_mismatches", 0) << " differences); plans over budget: " << rnd.value("over_budget", 0)
     << ".\n\n";

  const json& render = j["render"];
  md << "### Expected perceptual cost against the frame budget (camera path)\n\n"
     << "Mean over the planned frames; the objects may spend the budget minus the empty frame ("
     << fmt(json(render.value("base_us", 0.0) / 1000.0), "%.3f") << " ms measured).\n\n";
  std::vector<std::string> budgets;
  std::vector<std::string> policies;
  for (const json& r : j["sweep"]) {
    const std::string b = fmt(r["budget_ms"], "%g");
    if (std::find(budgets.begin(), budgets.end(), b) == budgets.end()) budgets.push_back(b);
    const std::string p = r.value("policy", "");
    if (std::find(policies.begin(), policies.end(), p) == policies.end()) policies.push_back(p);
  }
  std::vector<std::string> cols = {"Policy"};
  for (const auto& b : budgets) cols.push_back(b + " ms");
  md << stats::markdown_header(cols, 1);
  for (const auto& p : policies) {
    std::vector<std::string> cells = {p};
    for (const auto& b : budgets) {
      std::string c = "-";
      for (const json& r : j["sweep"])
        if (r.value("policy", "") == p && fmt(r["budget_ms"], "%g") == b) c = fmt(r["mean_expected_cost"]);
      cells.push_back(c);
    }
    md << stats::markdown_row(cells);
  }
  if (render.value("enabled", false) && render["error"].is_null()) {
    md << "\n### Rendered plans: frame skips on " << j.value("platform", "") << "\n\n"
       << render.value("renderer", "") << ", " << render.value("repetitions", 0)
       << " timed repetitions per plan (clear + chosen levels + glFinish); a frame is skipped when "
          "its median measured time exceeds the budget. Relative error = (measured - predicted) / "
          "predicted, median over frames; |error| = |predicted - measured| / measured, median over "
          "frames, with the #pix used and (last column) with the estimated #pix for the same plans.\n\n"
       << stats::markdown_header({"Policy", "Budget ms", "Frames", "Skips", "Skip rate", "Mean predicted ms",
                  "Median measured ms", "Median relative error", "Median abs error",
                  "Median abs error, estimated #pix"}, 1);
    for (const json& r : j["sweep"])
      md << stats::markdown_row({r.value("policy", ""), fmt(r["budget_ms"], "%g"), std::to_string(r.value("rendered", 0)),
                 std::to_string(r.value("skips", 0)), fmt(r["skip_fraction"], "%.2f"),
                 fmt(r["mean_predicted_ms"], "%.2f"), fmt(r["median_measured_ms"], "%.2f"),
                 fmt(r["median_relative_error"], "%+.2f"), fmt(r["median_abs_relative_error"], "%.2f"),
                 fmt(r["median_abs_relative_error_estimated_pixels"], "%.2f")});
    const json& ae = render["abs_relative_error"];
    const json& ee = render["abs_relative_error_estimated_pixels"];
    md << "\nOver all " << ae.value("n", 0) << " rendered plans, median |predicted - measured| / measured: "
       << fmt(ae.value("q50", json()), "%.3f") << " (q90 " << fmt(ae.value("q90", json()), "%.3f")
       << "); with the estimated #pix for the same plans " << fmt(ee.value("q50", json()), "%.3f")
       << " (q90 " << fmt(ee.value("q90", json()), "%.3f") << ").\n";
    if (cm.contains("measured_over_estimated_pixels")) {
      const json& q = cm["measured_over_estimated_pixels"];
      md << "Measured #pix of the finest level / estimated #pix per (frame, visible object): median "
         << fmt(q.value("q50", json()), "%.3f") << ", min " << fmt(q.value("min", json()), "%.3g")
         << ", max " << fmt(q.value("max", json()), "%.3g") << " (n = " << q.value("n", 0) << "; pixels.csv).\n";
    }
  } else if (!render["error"].is_null()) {
    md << "\nRendering failed: " << render["error"].get<std::string>() << "\n";
  }
  md << "\n### Findings\n\n";
  md << "- value(OPT) / value(greedy) on " << rnd.value("instances", 0) << " random instances: max "
     << fmt(rq.value("max", json())) << ", median " << fmt(rq.value("q50", json()))
     << " (never above 2: " << (rnd.value("value_ratio_above_2", 1) == 0 ? "yes" : "NO") << "); "
     << "without the single-item check the max is " << fmt(rnd["value_ratio_ratio_only"].value("max", json()))
     << ".\n";
  for (const json& f : j["findings"]) md << "- **Check failed**: " << f.get<std::string>() << "\n";
  md << "\n";
  return md.str();
}

}  // namespace

void analyze_regulation_study(const std::string& dir) {
  const json j = load_complete(dir);
  util::write_file_atomic(dir + "/regulation.md", regulation_markdown(j));
  rundir::StudyInfo info = *rundir::read_study_info(dir);
  info.document = "regulation.md";
  info.analysed = true;
  rundir::write_study_info(dir, info);
}

void plot_regulation_study(const std::string& dir) {
  const json j = load_complete(dir);
  if (!rundir::read_study_info(dir)->analysed)
    throw util::UserError(dir + " has not been analysed: run `renderaudit analyze " + dir +
                          "` first");
  plots::StudyFigures figs("regulation");
  // 1. distribution of value(OPT) / value(greedy)
  {
    std::vector<double> r;
    for (const json& v : j["random"]["ratios"]) if (v.is_number()) r.push_back(v.get<double>());
    plots::HistogramSeries hs;
    hs.name = "greedy with the single-item check";
    const int bins = 40;
    for (int i = 0; i <= bins; ++i) hs.edges.push_back(1.0 + double(i) / bins);
    hs.counts.assign(bins, 0);
    for (double v : r) hs.counts[std::min(bins - 1, std::max(0, int((v - 1.0) * bins)))] += 1;
    for (auto c : hs.counts) hs.heights.push_back(double(c));
    hs.n = r.size();
    plots::HistogramContent hc;
    hc.density = false;
    hc.series.push_back(hs);
    figs.add("regulation_ratio_histogram", "value(OPT) / value(greedy) on random instances",
             "value(OPT) / value(greedy)", "instances",
             "Distribution of the ratio of the optimal to the greedy value (perceptual cost saved "
             "over the all-coarsest plan) on " +
                 std::to_string(r.size()) +
                 " random knapsack instances; the theorem bounds it by 2.",
             hc);
  }
  // y against x of `rows` on log axes, one series per policy in the order they first appear; a
  // row without a number for y is left out (its policy keeps its place).
  auto by_policy = [](const json& rows, const char* x, const char* y) {
    plots::SeriesInOrder by;
    for (const json& r : rows) {
      plots::ScatterSeries& s = by[r.value("policy", "")];
      if (!r[y].is_number()) continue;
      s.x.push_back(r[x].get<double>());
      s.y.push_back(r[y].get<double>());
    }
    plots::ScatterContent sc;
    sc.series = by.series();
    sc.x_log10 = sc.y_log10 = true;
    return sc;
  };
  // 2. expected perceptual cost against budget, one series per policy
  {
    const plots::ScatterContent sc = by_policy(j["sweep"], "budget_ms", "mean_expected_cost");
    figs.add("regulation_cost_vs_budget", "Expected perceptual cost against frame budget",
             "frame budget (ms)", "mean expected perceptual cost",
             "Mean expected perceptual cost of the plans along the camera path, per policy and "
             "budget.",
             sc)
        .note = plots::scatter_omitted_note(sc);
  }
  // 3. skip rate per budget and policy; 4. measured against predicted
  if (j["render"].value("enabled", false) && j["render"]["error"].is_null()) {
    plots::BarChartContent bc;
    std::map<std::string, std::size_t> series_index;
    for (const json& r : j["sweep"]) {
      const std::string b = fmt(r["budget_ms"], "%g") + " ms";
      if (std::find(bc.categories.begin(), bc.categories.end(), b) == bc.categories.end())
        bc.categories.push_back(b);
    }
    for (const json& r : j["sweep"]) {
      const std::string p = r.value("policy", "");
      if (!series_index.count(p)) {
        series_index[p] = bc.series.size();
        bc.series.push_back({p, std::vector<double>(bc.categories.size(), 0.0), {}});
      }
      const std::string b = fmt(r["budget_ms"], "%g") + " ms";
      const auto at = std::find(bc.categories.begin(), bc.categories.end(), b) - bc.categories.begin();
      bc.series[series_index[p]].values[std::size_t(at)] =
          100.0 * (r["skip_fraction"].is_number() ? r["skip_fraction"].get<double>() : 0.0);
    }
    bc.y_max = 100;
    figs.add("regulation_frame_skips", "Frame skips per budget and policy", "frame budget",
             "frames over budget (%)",
             "Share of the planned frames whose median measured time exceeded the budget.", bc);

    const plots::ScatterContent sc = by_policy(j["render"]["points"], "predicted_ms", "measured_ms");
    figs.add("regulation_measured_vs_predicted", "Measured against predicted frame time",
             "predicted frame time (ms)", "measured median frame time (ms)",
             "Each rendered plan: the H4 prediction plus the empty frame against the median "
             "measured time.",
             sc)
        .note = plots::scatter_omitted_note(sc);
  }
  figs.write(dir);
}

}  // namespace ra::regulation
