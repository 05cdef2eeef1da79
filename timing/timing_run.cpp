// The rendering-time study from an experiment file (timing_run.h).
#include "timing/timing_run.h"

#include <chrono>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "rundir/run_folder.h"
#include "util/errors.h"
#include "timing/timing_outputs.h"
#include "platforms/platform_probe.h"
#include "timing/timing_study.h"
#include "util/errors.h"
#include "util/number_text.h"

namespace ra::timing {
namespace {

std::string summary_of(const StudyResults& r, const std::string& dir) {
  std::string s;
  for (std::size_t i = 0; i < r.measured.size(); ++i) {
    const PlatformMeasurements& m = r.measured[i];
    if (!m.error.empty()) {
      s += m.renderer.platform + ": FAILED: " + m.error + "\n";
      continue;
    }
    const PlatformAnalysis& a = r.analysed[i];
    s += util::format_text("%s (%s): %.0f s; GL_TIME_ELAPSED %s\n", m.renderer.platform.c_str(),
                           m.renderer.renderer.c_str(), m.seconds,
                           m.renderer.timer_query ? "supported" : "not supported");
    s += util::format_text(
        "  system task: %zu renderings, min %.3f ms, median %.3f ms, c (99%%) = %.3f ms\n",
        a.system.n, a.system.min_us / 1000, a.system.median_us / 1000, a.system.c_us / 1000);
    if (a.gpu_measured)
      s += util::format_text(
          "  GPU/CPU timer: median ratio %.3f (objects), %.3f (frames); r = %.3f, %.3f\n",
          a.cpu_gpu_objects.median_ratio, a.cpu_gpu_frames.median_ratio,
          a.cpu_gpu_objects.pearson_r, a.cpu_gpu_frames.pearson_r);
    s += util::format_text("  Table 6 (average squared error, ms^2):\n    %-10s", "scene");
    for (const std::string& meth : a.methods) s += util::format_text(" %9s", meth.c_str());
    s += "\n";
    for (const auto& [scene, row] : a.table6_ms2) {
      s += util::format_text("    %-10s", scene.c_str());
      for (const std::string& meth : a.methods) s += util::format_text(" %9.4g", row.at(meth));
      s += "\n";
    }
  }
  for (const RepeatedPlatform& p : r.repeated) {
    s += util::format_text("%s over %d runs (%d failed; the files above are run 1's):\n",
                           p.platform.c_str(), p.runs, p.failed);
    const RunSpread& c = p.c_us;
    s += util::format_text(
        "  c (99%%) = %.3f ms, SD %.3f, min-max %.3f-%.3f, %.0f%% t interval of the mean "
        "%.3f-%.3f ms\n",
        c.mean / 1000, c.sd / 1000, c.min / 1000, c.max / 1000, 100 * c.confidence, c.ci_low / 1000,
        c.ci_high / 1000);
    s += "  best method (runs won):";
    const char* sep = " ";
    for (const auto& [scene, rk] : p.ranking) {
      s += sep + scene + ":";
      for (const std::string& m : p.methods)
        if (rk.wins.at(m)) s += util::format_text(" %s %d", m.c_str(), rk.wins.at(m));
      sep = "; ";
    }
    s += "\n";
  }
  s += "wrote " + rundir::run_folder::timing(dir) +
       " (and object_samples.csv, frames.csv, pos_tables.csv, " +
       (r.repeated.empty() ? "" : "table6_repeated.csv, system_task_c_repeated.csv, ") +
       "figures/)\n";
  return s;
}

}  // namespace

rundir::StudyRunResult run_timing_study(const rundir::StudyRunOptions& options, bool figures) {
  const auto t0 = std::chrono::steady_clock::now();
  StudyResults r;
  r.settings = read_timing_experiment(options.experiment);
  std::vector<std::string> platforms = r.settings.platforms;
  if (!options.platforms.empty()) {
    std::string allowed;
    for (const std::string& e : r.settings.platforms) allowed += (allowed.empty() ? "" : ", ") + e;
    for (const std::string& p : options.platforms) {
      bool listed = false;
      for (const std::string& e : r.settings.platforms) listed = listed || e == p;
      if (!listed)
        throw util::UserError("--platform " + p + ": not a platform of " + options.experiment +
                              " (allowed: " + allowed + ")");
    }
    platforms = options.platforms;
  }
  const std::string dir = options.out_dir.empty() ? "outputs/" + r.settings.name : options.out_dir;
  platforms::require_platforms_draw(platforms, options.experiment);  // before anything is written
  const Progress progress = options.progress ? Progress([](const std::string& line) {
    std::fprintf(stderr, "timing: %s\n", line.c_str());
  })
                                             : Progress();

  // Scenes and paths are built once, before any GL (the children inherit them).
  std::vector<scenes::Scene> scenes;
  std::vector<std::vector<scenes::Viewpoint>> paths;
  for (const scenes::SceneSpec& spec : r.settings.scenes) {
    if (progress) progress("building scene " + spec.name + " (" + spec.kind + ")");
    scenes.push_back(scenes::build_scene(spec));
    paths.push_back(scenes::build_camera_path(spec, scenes.back()));
  }
  for (std::size_t i = 0; i < scenes.size(); ++i) {
    const bool system_scene = r.settings.system_task_scene.empty()
                                  ? i == 0
                                  : r.settings.scenes[i].name == r.settings.system_task_scene;
    if (system_scene && r.settings.system_task_frame >= int(paths[i].size()))
      throw util::UserError(
          options.experiment +
          ": timing.system_task_frame = " + std::to_string(r.settings.system_task_frame) +
          " is out of range (allowed: 0 to " + std::to_string(int(paths[i].size()) - 1) +
          ", the frames of scene " + r.settings.scenes[i].name + ")");
  }
  std::filesystem::create_directories(dir);
  rundir::StudyRunResult result;
  result.dir = dir;
  // study_runs independent runs, one after the other, every platform measured afresh in each (a
  // new child process: frame base, object measurements, path, pos tables, system task). The
  // first run's measurements are the study's files; the others keep their Table 6 and c.
  const int runs = r.settings.study_runs;
  std::vector<std::vector<RunOutcome>> outcomes(platforms.size());
  std::vector<std::string> methods;
  for (int run = 0; run < runs; ++run) {
    const std::string tag = runs > 1 ? util::format_text("run %d/%d: ", run + 1, runs) : "";
    const Progress run_progress =
        progress && runs > 1 ? Progress([&](const std::string& line) { progress(tag + line); })
                             : progress;
    for (std::size_t i = 0; i < platforms.size(); ++i) {
      const std::string& p = platforms[i];
      PlatformMeasurements m =
          measure_platform_in_child(r.settings, p, scenes, paths, dir, run_progress);
      RunOutcome outcome;
      outcome.wall_s = m.seconds;
      PlatformAnalysis a;
      if (!m.error.empty()) {
        std::fprintf(stderr, "renderaudit timing: %s%s failed: %s\n", tag.c_str(), p.c_str(),
                     m.error.c_str());
        result.findings = true;
      } else {
        a = analyse_platform(r.settings, m);
        outcome.ok = true;
        outcome.table6_ms2 = a.table6_ms2;
        outcome.c_us = a.system.n ? a.system.c_us : NAN;
        if (methods.empty()) methods = a.methods;
      }
      outcomes[i].push_back(std::move(outcome));
      if (run == 0) {
        r.measured.push_back(std::move(m));
        r.analysed.push_back(std::move(a));
      }
    }
  }
  if (runs > 1)
    for (std::size_t i = 0; i < platforms.size(); ++i)
      r.repeated.push_back(aggregate_runs(platforms[i], methods, outcomes[i]));
  r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (progress) progress("writing outputs to " + dir);
  write_timing_outputs(r, dir, figures);
  result.summary = summary_of(r, dir);
  return result;
}

}  // namespace ra::timing
