// The regulation study's run (regulation_run.h): random instances against the optimum, the
// scene's levels of detail, the plans along the camera path rendered and timed.
#include "regulation/regulation_run.h"

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
#include "regulation/attention.h"
#include "regulation/lod_chain.h"
#include "regulation/plan_rendering.h"
#include "regulation/policies.h"
#include "regulation/random_instances.h"
#include "regulation/regulation_document.h"
#include "regulation/regulation_experiment.h"
#include "rundir/manifest.h"
#include "rundir/run_folder.h"
#include "stats/descriptive.h"
#include "util/atomic_file.h"
#include "util/cell_text.h"
#include "util/errors.h"
#include "util/json_number.h"
#include "util/number_text.h"

namespace ra::regulation {
namespace {

using nlohmann::json;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

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
  for (double v : ratio) r.push_back(util::finite_or_null(v));
  for (double v : ratio_only) ro.push_back(util::finite_or_null(v));
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
  sum << "regulation study -> " << dir << " (" << util::json_number_text(j["wall_s"], "%.1f") << " s)\n"
      << "random instances: " << instances << ", value(OPT)/value(greedy) max " << util::json_number_text(rq.value("max", json()))
      << ", median " << util::json_number_text(rq.value("q50", json())) << "; ratio-only greedy max "
      << util::json_number_text(j["random"]["value_ratio_ratio_only"].value("max", json())) << "\n";
  for (const json& row : j["sweep"])
    if (row["policy"] == "greedy")
      sum << "budget " << util::json_number_text(row["budget_ms"]) << " ms: greedy expected cost "
          << util::json_number_text(row["mean_expected_cost"]) << ", skips " << row["skips"].get<int>() << "/"
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

}  // namespace ra::regulation
