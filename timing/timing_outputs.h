// What `renderaudit timing` writes (every file atomically, util/atomic_file.h):
//
// DIR/timing.json (schema "renderaudit-timing/1"): provenance (program, commit-free: the binary's
// version, UTC date, host, experiment file and its settings), then "platforms": one object per
// platform measured:
//   name, renderer {renderer, version, vendor, gallium_driver, lp_num_threads, depth_bits},
//   timer_query {supported, extension_listed, counter_bits, used},
//   wall_s, error (null when it succeeded),
//   system_task {scene, frame, visible_objects, n, confidence, quantile_definition, min_us,
//                median_us, mean_us, sd_us, max_us, q99_us, c_us, c_ms, cpu_us [every frame time],
//                gpu_us [every GPU frame time, or empty]},
//   fits [{heuristic, formula, intercept, parameters [{name, unit, value, standard_error}], n,
//          rmse_us, r_squared, (h3:) geometry_limited, raster_limited, iterations, start,
//          converged}] (timer: CPU medians),
//   scenes [{name, kind, objects, triangles, vertices, transformed, tv_per_triangle, textures,
//            state_switches, path_frames, frames_measured, object_samples, pos_tables,
//            pos_cells_measured, frame_base_us, seconds}],
//   table6_ms2 {scene: {method: average squared error, ms^2}} for the methods h1..h4 (the paper's
//              forms), h1+b..h4+b (with a per-object intercept) and pos,
//   cpu_vs_gpu {objects: {n, median_ratio, pearson_r}, frames: {...}} (null without GPU timer).
// With study_runs = N >= 2 (repeated_runs.h) everything above is the first run's, and timing.json
// also has experiment.settings.study_runs and
//   repeated {runs, primary_run (1), confidence (0.95), platforms [{name, runs, failed, wall_s
//             [per run], methods, system_task_c {per_run_us, n, mean_us, sd_us, min_us, max_us,
//             ci_low_us, ci_high_us}, table6_ms2 {scene: {method: {per_run, n, mean, sd, min,
//             max, ci_low, ci_high}}}, ranking {scene: {per_run [[methods, best first]], wins
//             {method: runs}, paper_wins {method: runs}, runs_without_winner}}}]};
//   with N = 1 neither key is written, so the file is that of a single study.
// DIR/table6_repeated.csv (N >= 2 only): one row per platform, scene and method: the spread over
//   the runs, wins, the rank and the value of every run (';'-separated).
// DIR/system_task_c_repeated.csv (N >= 2 only): one row per platform: c over the runs.
// DIR/object_samples.csv: one row per object measurement (every repetition in cpu_us / gpu_us,
//   ';'-separated).
// DIR/frames.csv: one row per measured path frame: counts summed over the visible objects, the
//   measured median and every repetition, and each method's prediction.
// DIR/pos_tables.csv: every cell of every per-object sampling table.
// DIR/figures/: system_task_density_<platform> (the paper's Figure 3) and
//   path_<platform>_<scene>_<method> (predicted vs measured frame time along the path), each as
//   PNG, PDF and CSV (plots/figure_renderer.h).
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "timing/repeated_runs.h"
#include "timing/timing_study.h"

namespace ra::timing {

struct StudyResults {
  TimingSettings settings;
  std::vector<PlatformMeasurements> measured;
  std::vector<PlatformAnalysis> analysed;  // same order; empty analysis where measurement failed
  // study_runs >= 2: per platform (same order) Table 6 and c over every run; measured and
  // analysed above are then the first run's. Empty for a single run.
  std::vector<RepeatedPlatform> repeated;
  double wall_s = 0;
};

nlohmann::json timing_json(const StudyResults& r);
std::string object_samples_csv(const StudyResults& r);
std::string frames_csv(const StudyResults& r);
std::string pos_tables_csv(const StudyResults& r);
std::string table6_repeated_csv(const StudyResults& r);
std::string system_task_c_repeated_csv(const StudyResults& r);

// Writes everything above into `dir` (created when missing), with timing.md (timing_document.h)
// and the figures (timing_figures.h) unless `figures` is false.
// Returns the paths written.
std::vector<std::string> write_timing_outputs(const StudyResults& r, const std::string& dir,
                                              bool figures = true);

}  // namespace ra::timing
