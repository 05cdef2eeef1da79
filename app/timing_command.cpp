// `renderaudit timing EXPERIMENT.toml [--out DIR] [--platform P ...] [--quiet] [--no-figures]`:
// the rendering-time study of Wimmer & Wonka 2003 (timing/timing_study.h) on OSMesa platforms:
// system-task constant c, heuristics H1-H4 fitted on object measurements, per-object sampling,
// and Table 6 along each scene's camera path. Outputs: timing/timing_report.h.
#include <chrono>
#include <filesystem>
#include <cstdio>
#include <string>
#include <vector>

#include "app/commands.h"
#include "runner/errors.h"
#include "timing/timing_report.h"
#include "timing/timing_study.h"

namespace ra::app {
namespace {

struct TimingRequest {
  std::string experiment;
  std::string out_dir;
  std::vector<std::string> platforms;
  bool quiet = false;
  bool no_figures = false;
};

void print_summary(const timing::StudyResults& r, const std::string& dir) {
  for (std::size_t i = 0; i < r.measured.size(); ++i) {
    const timing::PlatformMeasurements& m = r.measured[i];
    if (!m.error.empty()) {
      std::printf("%s: FAILED: %s\n", m.renderer.platform.c_str(), m.error.c_str());
      continue;
    }
    const timing::PlatformAnalysis& a = r.analysed[i];
    std::printf("%s (%s): %.0f s; GL_TIME_ELAPSED %s\n", m.renderer.platform.c_str(),
                m.renderer.renderer.c_str(), m.seconds,
                m.renderer.timer_query ? "supported" : "not supported");
    std::printf("  system task: %zu renderings, min %.3f ms, median %.3f ms, c (99%%) = %.3f ms\n",
                a.system.n, a.system.min_us / 1000, a.system.median_us / 1000,
                a.system.c_us / 1000);
    if (a.gpu_measured)
      std::printf("  GPU/CPU timer: median ratio %.3f (objects), %.3f (frames); r = %.3f, %.3f\n",
                  a.cpu_gpu_objects.median_ratio, a.cpu_gpu_frames.median_ratio,
                  a.cpu_gpu_objects.pearson_r, a.cpu_gpu_frames.pearson_r);
    std::printf("  Table 6 (average squared error, ms^2):\n    %-10s", "scene");
    for (const std::string& meth : a.methods) std::printf(" %9s", meth.c_str());
    std::printf("\n");
    for (const auto& [scene, row] : a.table6_ms2) {
      std::printf("    %-10s", scene.c_str());
      for (const std::string& meth : a.methods) std::printf(" %9.4g", row.at(meth));
      std::printf("\n");
    }
  }
  std::printf("wrote %s/timing.json (and object_samples.csv, frames.csv, pos_tables.csv, figures/)\n",
              dir.c_str());
}

}  // namespace

void register_timing_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand(
      "timing",
      "The rendering-time study (Wimmer & Wonka 2003) on OSMesa platforms: each scene drawn as\n"
      "indexed triangle strips, the system-task constant c (99 %), heuristics H1-H4 fitted on\n"
      "object measurements, per-object sampling, and Table 6 (average squared error of frame\n"
      "time predictions along each camera path). Each platform is measured in its own process;\n"
      "run it on an otherwise idle machine.");
  static TimingRequest q;
  cmd->add_option("experiment", q.experiment, "experiment file ([timing] and [[scene]] tables)")
      ->required();
  cmd->add_option("--out,-o", q.out_dir, "output directory (default: outputs/<name>)");
  cmd->add_option("--platform,-p", q.platforms,
                  "measure only these platforms of the experiment (repeatable)");
  cmd->add_flag("--quiet,-q", q.quiet, "no progress lines on stderr");
  cmd->add_flag("--no-figures", q.no_figures, "write the JSON and CSV files only");
  cmd->callback([&exit_code] {
    const auto t0 = std::chrono::steady_clock::now();
    timing::StudyResults r;
    r.settings = timing::read_timing_experiment(q.experiment);
    std::vector<std::string> platforms = r.settings.platforms;
    if (!q.platforms.empty()) {
      for (const std::string& p : q.platforms) {
        bool listed = false;
        for (const std::string& e : r.settings.platforms) listed = listed || e == p;
        if (!listed) {
          std::string allowed;
          for (const std::string& e : r.settings.platforms) allowed += (allowed.empty() ? "" : ", ") + e;
          throw UserError("--platform " + p + ": not a platform of " + q.experiment +
                          " (allowed: " + allowed + ")");
        }
      }
      platforms = q.platforms;
    }
    const std::string dir = q.out_dir.empty() ? "outputs/" + r.settings.name : q.out_dir;
    const timing::Progress progress =
        q.quiet ? timing::Progress() : [](const std::string& line) {
          std::fprintf(stderr, "timing: %s\n", line.c_str());
        };

    // Scenes and paths are built once, before any GL (the children inherit them).
    std::vector<Scene> scenes;
    std::vector<std::vector<Viewpoint>> paths;
    for (const SceneSpec& spec : r.settings.scenes) {
      if (progress) progress("building scene " + spec.name + " (" + spec.kind + ")");
      scenes.push_back(build_scene(spec));
      paths.push_back(build_camera_path(spec, scenes.back()));
    }
    std::filesystem::create_directories(dir);
    bool failed = false;
    for (const std::string& p : platforms) {
      r.measured.push_back(
          timing::measure_platform_in_child(r.settings, p, scenes, paths, dir, progress));
      const timing::PlatformMeasurements& m = r.measured.back();
      if (!m.error.empty()) {
        std::fprintf(stderr, "renderaudit timing: %s failed: %s\n", p.c_str(), m.error.c_str());
        failed = true;
        r.analysed.emplace_back();
        continue;
      }
      r.analysed.push_back(timing::analyse_platform(r.settings, m));
    }
    r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (progress) progress("writing outputs to " + dir);
    timing::write_timing_outputs(r, dir, !q.no_figures);
    print_summary(r, dir);
    exit_code = failed ? kExitFindings : kExitOk;
  });
}

}  // namespace ra::app
