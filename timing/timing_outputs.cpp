// The outputs of `renderaudit timing` (timing_outputs.h).
#include "timing/timing_outputs.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "plots/figure_set.h"
#include "rundir/manifest.h"
#include "rundir/run_folder.h"
#include "rundir/study_dir.h"
#include "stats/descriptive.h"
#include "timing/timing_document.h"
#include "timing/timing_figures.h"
#include "util/atomic_file.h"
#include "util/cell_text.h"
#include "util/errors.h"
#include "util/json_number.h"
#include "util/number_text.h"

namespace ra::timing {
namespace {

// Not-finite values as empty cells.

std::string list(const std::vector<double>& v) {
  std::string s;
  for (std::size_t i = 0; i < v.size(); ++i) s += (i ? ";" : "") + util::full_precision_if_finite(v[i]);
  return s;
}


nlohmann::json fit_json(const HeuristicFit& f) {
  nlohmann::json j = {{"heuristic", heuristic_name(f.heuristic)},
                      {"formula", heuristic_formula(f.heuristic)},
                      {"intercept", f.intercept},
                      {"n", f.n},
                      {"rmse_us", util::finite_or_null(f.rmse)},
                      {"r_squared", util::finite_or_null(f.r_squared)}};
  j["parameters"] = nlohmann::json::array();
  for (std::size_t k = 0; k < f.coefficients.size(); ++k)
    j["parameters"].push_back({{"name", f.names[k]},
                               {"unit", f.units[k]},
                               {"value", util::finite_or_null(f.coefficients[k])},
                               {"standard_error", util::finite_or_null(f.standard_errors[k])}});
  if (f.heuristic == Heuristic::kH3) {
    j["geometry_limited"] = f.geometry_limited;
    j["raster_limited"] = f.raster_limited;
    j["iterations"] = f.iterations;
    j["start"] = f.start;
    j["converged"] = f.converged;
  }
  return j;
}

nlohmann::json comparison_json(const CpuGpuComparison& c) {
  return {{"n", c.n}, {"median_ratio", util::finite_or_null(c.median_ratio)}, {"pearson_r", util::finite_or_null(c.pearson_r)}};
}

// A quantity over the repeated runs; `unit` is appended to the names of the numbers ("_us").
nlohmann::json spread_json(const RunSpread& s, const std::string& unit) {
  nlohmann::json per_run = nlohmann::json::array();
  for (double v : s.values) per_run.push_back(util::finite_or_null(v));
  return {{"per_run" + unit, per_run},       {"n", s.n},
          {"mean" + unit, util::finite_or_null(s.mean)}, {"sd" + unit, util::finite_or_null(s.sd)},
          {"min" + unit, util::finite_or_null(s.min)},   {"max" + unit, util::finite_or_null(s.max)},
          {"ci_low" + unit, util::finite_or_null(s.ci_low)}, {"ci_high" + unit, util::finite_or_null(s.ci_high)}};
}

nlohmann::json repeated_json(const StudyResults& r) {
  nlohmann::json platforms = nlohmann::json::array();
  for (const RepeatedPlatform& p : r.repeated) {
    nlohmann::json t6 = nlohmann::json::object(), ranking = nlohmann::json::object();
    for (const auto& [scene, by_method] : p.table6_ms2)
      for (const auto& [method, spread] : by_method) t6[scene][method] = spread_json(spread, "");
    for (const auto& [scene, rk] : p.ranking)
      ranking[scene] = {{"per_run", rk.per_run},
                        {"wins", rk.wins},
                        {"paper_wins", rk.paper_wins},
                        {"runs_without_winner", rk.runs_without_winner}};
    platforms.push_back({{"name", p.platform},
                         {"runs", p.runs},
                         {"failed", p.failed},
                         {"wall_s", p.wall_s},
                         {"methods", p.methods},
                         {"system_task_c", spread_json(p.c_us, "_us")},
                         {"table6_ms2", t6},
                         {"ranking", ranking}});
  }
  const double confidence = r.repeated.empty() ? 0.95 : r.repeated.front().c_us.confidence;
  return {{"runs", r.settings.study_runs},
          {"primary_run", 1},
          {"confidence", confidence},
          {"what", "each run a complete, independent measurement of every platform (same "
                   "experiment and seed); the rest of this file is the primary run's"},
          {"platforms", platforms}};
}

}  // namespace

nlohmann::json timing_json(const StudyResults& r) {
  const TimingSettings& s = r.settings;
  nlohmann::json j = rundir::document_header("timing", 1);
  j["wall_s"] = r.wall_s;
  nlohmann::json scenes = nlohmann::json::array();
  for (const scenes::SceneSpec& sc : s.scenes)
    scenes.push_back({{"name", sc.name}, {"kind", sc.kind}});
  nlohmann::json work = nlohmann::json::object();
  for (const auto& [p, w] : s.platform_work)
    work[p] = {{"repetitions", w.repetitions},
               {"system_task_renders", w.system_task_renders},
               {"object_samples", w.object_samples},
               {"frame_stride", w.frame_stride},
               {"pos_repetitions", w.pos_repetitions}};
  j["experiment"] = {
      {"file", s.file},
      {"name", s.name},
      {"settings",
       {{"window", {s.camera.width, s.camera.height}},
        {"fov_deg", s.camera.fov_y_deg},
        {"near", s.camera.near},
        {"far", s.camera.far},
        {"cache_size", s.cache_size},
        {"seed", s.seed},
        {"gpu_timer", s.gpu_timer},
        {"alpha_min_deg", s.alpha_min_deg},
        {"phi_deg", {s.phi_min_deg, s.phi_max_deg}},
        {"pos_grid", {s.pos_grid.n_alpha, s.pos_grid.n_gamma, s.pos_grid.n_phi}},
        {"pos_alpha_range_rad", {s.pos_grid.alpha_min, s.pos_grid.alpha_max}},
        {"pos_prune_alpha_deg", s.pos_prune_alpha_deg},
        {"pos_lookup", s.pos_lookup == PosLookup::kNearest ? "nearest" : "interpolate"},
        {"work", work}}},
      {"scenes", scenes}};
  // (a single run writes neither key: its file is that of a single study)
  if (!r.repeated.empty()) {
    j["experiment"]["settings"]["study_runs"] = s.study_runs;
    j["repeated"] = repeated_json(r);
  }
  j["units"] = {{"time", "microseconds (_us), milliseconds (_ms); Table 6 in ms^2"},
                {"measurement", "median of the repetitions, CPU clock around draw + glFinish"},
                {"angles", "radians"}};
  j["platforms"] = nlohmann::json::array();
  for (std::size_t i = 0; i < r.measured.size(); ++i) {
    const PlatformMeasurements& m = r.measured[i];
    nlohmann::json p;
    p["name"] = m.renderer.platform;
    p["renderer"] = {{"renderer", m.renderer.renderer},
                     {"version", m.renderer.version},
                     {"vendor", m.renderer.vendor},
                     {"gallium_driver", m.renderer.gallium_driver},
                     {"backend", m.renderer.backend},
                     {"lp_num_threads", m.renderer.lp_num_threads},
                     {"depth_bits", m.renderer.depth_bits}};
    p["timer_query"] = {{"supported", m.renderer.timer_query},
                        {"extension_listed", m.renderer.timer_query_listed},
                        {"counter_bits", m.renderer.timer_query_bits},
                        {"used", !m.system_gpu_us.empty()}};
    p["wall_s"] = m.seconds;
    p["error"] = m.error.empty() ? nlohmann::json() : nlohmann::json(m.error);
    if (!m.error.empty() || i >= r.analysed.size()) {
      j["platforms"].push_back(std::move(p));
      continue;
    }
    const PlatformAnalysis& a = r.analysed[i];
    p["system_task"] = {{"scene", m.system_scene},
                        {"frame", m.system_frame},
                        {"visible_objects", m.system_visible_objects},
                        {"n", a.system.n},
                        {"confidence", a.system.confidence},
                        {"quantile_definition", "hyndman_fan_6"},
                        {"min_us", a.system.min_us},
                        {"median_us", a.system.median_us},
                        {"mean_us", a.system.mean_us},
                        {"sd_us", a.system.sd_us},
                        {"max_us", a.system.max_us},
                        {"q99_us", a.system.q99_us},
                        {"c_us", a.system.c_us},
                        {"c_ms", a.system.c_us / 1000.0},
                        {"cpu_us", m.system_cpu_us},
                        {"gpu_us", m.system_gpu_us}};
    p["fits"] = nlohmann::json::array();
    for (const HeuristicFit& f : a.fits) p["fits"].push_back(fit_json(f));
    p["scenes"] = nlohmann::json::array();
    for (const SceneMeasurements& sm : m.scenes) {
      int64_t cells = 0;
      for (const MeasuredPosTable& t : sm.pos) cells += int64_t(t.table.points_to_measure().size());
      p["scenes"].push_back(
          {{"name", sm.name},
           {"kind", sm.kind},
           {"objects", sm.objects},
           {"triangles", sm.triangles},
           {"vertices", sm.vertices},
           {"transformed", sm.transformed},
           {"tv_per_triangle", sm.triangles ? double(sm.transformed) / double(sm.triangles) : 0.0},
           {"textures", sm.textures},
           {"state_switches", sm.state_switches},
           {"path_frames", sm.path_frames},
           {"frames_measured", sm.frames.size()},
           {"object_samples", sm.object_samples.size()},
           {"pos_tables", sm.pos.size()},
           {"pos_cells_measured", cells},
           {"frame_base_us", a.frame_base_us.count(sm.name) ? a.frame_base_us.at(sm.name) : NAN},
           {"seconds", sm.seconds}});
    }
    p["table6_ms2"] = a.table6_ms2;
    p["table6_methods"] = a.methods;
    p["cpu_vs_gpu"] = a.gpu_measured
                          ? nlohmann::json{{"objects", comparison_json(a.cpu_gpu_objects)},
                                           {"frames", comparison_json(a.cpu_gpu_frames)},
                                           {"ratio", "gpu median / cpu median per draw"}}
                          : nlohmann::json();
    j["platforms"].push_back(std::move(p));
  }
  return j;
}

std::string object_samples_csv(const StudyResults& r) {
  std::ostringstream o;
  o << "platform,scene,object,alpha,gamma,phi,triangles,vertices,transformed,pixels,"
       "state_changes,repetitions,cpu_median_us,gpu_median_us,cpu_us,gpu_us\n";
  for (const PlatformMeasurements& m : r.measured)
    for (const SceneMeasurements& s : m.scenes)
      for (const ObjectSample& x : s.object_samples)
        o << util::csv_escape(m.renderer.platform) << ',' << util::csv_escape(s.name) << ','
          << x.object << ',' << util::full_precision_if_finite(x.alpha) << ',' << util::full_precision_if_finite(x.gamma) << ',' << util::full_precision_if_finite(x.phi) << ','
          << x.triangles << ',' << x.vertices << ',' << x.transformed << ',' << x.pixels << ','
          << x.state_changes << ',' << x.cpu_us.size() << ',' << util::full_precision_if_finite(stats::median(x.cpu_us)) << ','
          << util::full_precision_if_finite(stats::median_or_nan(x.gpu_us)) << ',' << list(x.cpu_us) << ',' << list(x.gpu_us)
          << '\n';
  return o.str();
}

std::string frames_csv(const StudyResults& r) {
  std::vector<std::string> methods;
  for (const PlatformAnalysis& a : r.analysed)
    if (!a.methods.empty()) {
      methods = a.methods;
      break;
    }
  std::ostringstream o;
  o << "platform,scene,frame,visible_objects,triangles,vertices,transformed,pixels,state_changes,"
       "repetitions,measured_us,measured_gpu_us";
  for (const std::string& m : methods) o << ",pred_" << m << "_us";
  o << ",cpu_us,gpu_us\n";
  for (std::size_t i = 0; i < r.measured.size() && i < r.analysed.size(); ++i) {
    const PlatformMeasurements& m = r.measured[i];
    const PlatformAnalysis& a = r.analysed[i];
    for (const SceneMeasurements& s : m.scenes) {
      if (!a.frames.count(s.name)) continue;
      const std::vector<FramePrediction>& preds = a.frames.at(s.name);
      for (std::size_t f = 0; f < s.frames.size() && f < preds.size(); ++f) {
        const FrameSample& fs = s.frames[f];
        int64_t tris = 0, verts = 0, tv = 0, pix = 0, sw = 0;
        for (const ObjectSample& x : fs.objects)
          tris += x.triangles, verts += x.vertices, tv += x.transformed, pix += x.pixels,
              sw += x.state_changes;
        o << util::csv_escape(m.renderer.platform) << ',' << util::csv_escape(s.name) << ','
          << fs.frame << ',' << fs.objects.size() << ',' << tris << ',' << verts << ',' << tv << ','
          << pix << ',' << sw << ',' << fs.cpu_us.size() << ',' << util::full_precision_if_finite(preds[f].measured_us) << ','
          << util::full_precision_if_finite(preds[f].measured_gpu_us);
        for (const std::string& meth : methods) o << ',' << util::full_precision_if_finite(preds[f].predicted_us.at(meth));
        o << ',' << list(fs.cpu_us) << ',' << list(fs.gpu_us) << '\n';
      }
    }
  }
  return o.str();
}

std::string pos_tables_csv(const StudyResults& r) {
  std::ostringstream o;
  o << "platform,scene,object,alpha_index,gamma_index,phi_index,alpha,gamma,phi,pruned,us\n";
  for (const PlatformMeasurements& m : r.measured)
    for (const SceneMeasurements& s : m.scenes)
      for (const MeasuredPosTable& t : s.pos) {
        const PosGrid& g = t.table.grid();
        for (int i = 0; i < g.n_alpha; ++i)
          for (int k = 0; k < g.n_gamma; ++k)
            for (int j = 0; j < g.n_phi; ++j)
              o << util::csv_escape(m.renderer.platform) << ',' << util::csv_escape(s.name) << ','
                << t.object << ',' << i << ',' << k << ',' << j << ',' << util::full_precision_if_finite(g.alpha_at(i)) << ','
                << util::full_precision_if_finite(g.gamma_at(k)) << ',' << util::full_precision_if_finite(g.phi_at(j)) << ','
                << (t.table.pruned_row(i) ? 1 : 0) << ',' << util::full_precision_if_finite(t.table.at(i, k, j)) << '\n';
      }
  return o.str();
}

std::string table6_repeated_csv(const StudyResults& r) {
  std::ostringstream o;
  o << "platform,scene,method,runs,mean_ms2,sd_ms2,min_ms2,max_ms2,ci_low_ms2,ci_high_ms2,"
       "confidence,wins,paper_wins,rank_per_run,ms2_per_run\n";
  for (const RepeatedPlatform& p : r.repeated)
    for (const auto& [scene, by_method] : p.table6_ms2) {
      const SceneRanking& rk = p.ranking.at(scene);
      for (const std::string& method : p.methods) {
        const RunSpread& s = by_method.at(method);
        std::string ranks;
        for (std::size_t k = 0; k < rk.per_run.size(); ++k) {
          const auto& order = rk.per_run[k];
          const auto at = std::find(order.begin(), order.end(), method);
          ranks += (k ? ";" : "") + std::to_string(at - order.begin() + 1);
        }
        o << util::csv_escape(p.platform) << ',' << util::csv_escape(scene) << ','
          << util::csv_escape(method) << ',' << s.n << ',' << util::full_precision_if_finite(s.mean) << ',' << util::full_precision_if_finite(s.sd) << ','
          << util::full_precision_if_finite(s.min) << ',' << util::full_precision_if_finite(s.max) << ',' << util::full_precision_if_finite(s.ci_low) << ',' << util::full_precision_if_finite(s.ci_high) << ','
          << util::significant(s.confidence, 6) << ',' << rk.wins.at(method) << ','
          << (is_paper_method(method) ? std::to_string(rk.paper_wins.at(method)) : "") << ','
          << ranks << ',' << list(s.values) << '\n';
      }
    }
  return o.str();
}

std::string system_task_c_repeated_csv(const StudyResults& r) {
  std::ostringstream o;
  o << "platform,runs,failed,mean_ms,sd_ms,min_ms,max_ms,ci_low_ms,ci_high_ms,confidence,"
       "c_ms_per_run\n";
  auto ms = [](double us) { return util::full_precision_if_finite(us / 1000.0); };
  for (const RepeatedPlatform& p : r.repeated) {
    const RunSpread& c = p.c_us;
    std::vector<double> per_run;
    for (double v : c.values) per_run.push_back(v / 1000.0);
    o << util::csv_escape(p.platform) << ',' << p.runs << ',' << p.failed << ',' << ms(c.mean)
      << ',' << ms(c.sd) << ',' << ms(c.min) << ',' << ms(c.max) << ',' << ms(c.ci_low) << ','
      << ms(c.ci_high) << ',' << util::significant(c.confidence, 6) << ',' << list(per_run) << '\n';
  }
  return o.str();
}

std::vector<std::string> write_timing_outputs(const StudyResults& r, const std::string& dir,
                                              bool figures) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (!std::filesystem::is_directory(dir))
    throw util::UserError("cannot create the output directory " + dir + ": " + ec.message());
  std::vector<std::string> written;
  auto put = [&](const std::string& name, const std::string& text) {
    util::write_file_atomic(dir + "/" + name, text);
    written.push_back(dir + "/" + name);
  };
  put("object_samples.csv", object_samples_csv(r));
  put("frames.csv", frames_csv(r));
  put("pos_tables.csv", pos_tables_csv(r));
  if (!r.repeated.empty()) {
    put("table6_repeated.csv", table6_repeated_csv(r));
    put("system_task_c_repeated.csv", system_task_c_repeated_csv(r));
  }
  if (figures)
    for (const std::string& p : plots::write_figure_set(timing_figures(r), dir)) written.push_back(p);
  const nlohmann::json doc = timing_json(r);
  put("timing.md", timing_markdown(doc));
  put(rundir::run_folder::kTimingFile, doc.dump(2) + "\n");
  // last: its presence means a complete study folder; the study is analysed as it runs
  rundir::StudyInfo info;
  info.kind = rundir::StudyKind::kTiming;
  info.name = r.settings.name;
  info.title = "renderaudit timing report: " + r.settings.name;
  info.subtitle =
      "How long renderers take to draw a frame, and how well the heuristics of Wimmer & Wonka "
      "(EGSR 2003) predict it, measured on this machine.";
  info.document = "timing.md";
  info.analysed = true;
  rundir::write_study_info(dir, info);
  written.push_back(rundir::run_folder::study(dir));
  return written;
}

}  // namespace ra::timing
