// The rendering-time study of Wimmer & Wonka 2003 (sections 4.2, 5.2, 5.3, 7.2) on one or more
// OSMesa platforms: measurement (GL, one child process per platform) and estimation (no GL).
//
// Per platform, in a child process forked before any GL call (Mesa picks its driver once per
// process), for every scene of the experiment:
// 1. Frame base: an empty frame (colour + depth clear, glFinish) timed `repetitions` x 10 times.
// 2. Object measurements (section 7.2, "10,000 test measurements of different objects"): the
//    platform's object_samples split evenly over the scenes; each picks an object uniformly at
//    random and a viewpoint looking at its bounding sphere's centre from a random direction (gamma
//    uniform in [0, 2 pi), phi uniform in the phi_deg range) at the distance where its clipped
//    alpha is a random value, log-uniform in [alpha_min, largest clipped alpha] (small objects are
//    the common case of a walkthrough, yet every size is covered). One untimed draw counts the
//    pixels (GL_SAMPLES_PASSED, object alone); then `repetitions` timed draws (object alone, clear
//    not timed). The measurement is the median of the repetitions.
// 3. Camera path: every frame_stride-th viewpoint; view-frustum culling at object level
//    (bounding spheres); the frame (clear + visible objects in scene order) timed `repetitions`
//    times; per visible object its counts (#pix drawn alone, texture binds issued in the frame,
//    clipped alpha, gamma, phi).
// 4. Per-object sampling tables (section 5.2) for every object visible in some measured frame (the
//    others are never looked up): the PosGrid's points, each the median of `repetitions` draws of
//    the object alone (pos_repetitions draws); rows below pos_prune_alpha_deg measured once.
// The system task (section 4.2, Figure 3) renders the middle viewpoint of the first scene's path
// system_task_renders times, keeping every frame time.
//
// Then in the parent (no GL): the heuristics fitted on all object measurements of the platform
// (every scene pooled: the coefficients are rates of the renderer, not of a scene), with and
// without intercept; frame predictions; Table 6; the CPU vs GPU timer comparison.
//
// Frame prediction, every method: frame base (measured empty frame) + sum over the visible
// objects of ET(object). The system constant c is not added: it is a safety margin for a frame
// budget, and would only shift every prediction by the same amount.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "timing/scene_renderer.h"
#include "timing/time_heuristics.h"
#include "timing/timing_experiment.h"
#include "timing/timing_samples.h"

namespace ra::timing {

// A per-object sampling table as measured.
struct MeasuredPosTable {
  int object = 0;
  PosTable table;
};

struct SceneMeasurements {
  std::string name, kind;
  int64_t objects = 0, triangles = 0, vertices = 0, transformed = 0, textures = 0;
  int64_t state_switches = 0;          // texture binds drawing every object in order (Table 5)
  int path_frames = 0;                 // viewpoints of the camera path
  std::vector<double> frame_base_us;   // every repetition of the empty frame
  std::vector<ObjectSample> object_samples;
  std::vector<FrameSample> frames;
  std::vector<MeasuredPosTable> pos;
  double seconds = 0;                  // wall time of this scene's measurements
};

struct PlatformMeasurements {
  RendererInfo renderer;
  std::string system_scene;            // scene of the system-task viewpoint
  int system_frame = 0;                // its frame number on the path
  int system_visible_objects = 0;
  std::vector<double> system_cpu_us;   // every rendering
  std::vector<double> system_gpu_us;   // empty when the timer query is not used
  std::vector<SceneMeasurements> scenes;
  double seconds = 0;                  // wall time of the whole platform (child process)
  std::string error;                   // non-empty: the measurement failed (what happened)
};

using Progress = std::function<void(const std::string& line)>;

// Measures one platform in this process (makes its GL context: must be the process's first).
// `scenes` and `paths` are built from settings.scenes, in order.
PlatformMeasurements measure_platform(const TimingSettings& settings, const std::string& platform,
                                      const std::vector<scenes::Scene>& scenes,
                                      const std::vector<std::vector<scenes::Viewpoint>>& paths,
                                      const Progress& progress);

// Measures `platform` in a forked child process and returns what it measured; a child that fails
// or dies is reported in PlatformMeasurements::error. `scratch_dir` holds the child's result file.
PlatformMeasurements measure_platform_in_child(
    const TimingSettings& settings, const std::string& platform,
    const std::vector<scenes::Scene>& scenes,
    const std::vector<std::vector<scenes::Viewpoint>>& paths, const std::string& scratch_dir,
    const Progress& progress);

nlohmann::json to_json(const PlatformMeasurements& m);
PlatformMeasurements platform_measurements_from_json(const nlohmann::json& j);

// ---- estimation ----

// Prediction methods of Table 6: h1..h4 as the paper writes them (no intercept), the same with a
// per-object intercept ("h1+b" ...), and pos.
struct FramePrediction {
  int frame = 0;
  int visible = 0;
  double measured_us = 0;                    // median of the frame's CPU repetitions
  double measured_gpu_us = 0;                // median of its GPU repetitions; NaN if none
  std::map<std::string, double> predicted_us;  // method -> frame base + sum of ET
};

struct CpuGpuComparison {
  std::size_t n = 0;
  double median_ratio = 0;  // median over draws of gpu median / cpu median
  double pearson_r = 0;     // correlation of the two medians over draws
};

struct PlatformAnalysis {
  std::string platform;
  SystemTaskStats system;
  std::vector<HeuristicFit> fits;            // h1..h4 without, then with intercept
  std::vector<std::string> methods;          // "h1".."h4", "h1+b".."h4+b", "pos"
  std::map<std::string, std::vector<FramePrediction>> frames;  // per scene
  std::map<std::string, std::map<std::string, double>> table6_ms2;  // scene -> method -> error
  std::map<std::string, double> frame_base_us;                      // per scene (median)
  bool gpu_measured = false;
  CpuGpuComparison cpu_gpu_objects, cpu_gpu_frames;
};

PlatformAnalysis analyse_platform(const TimingSettings& settings, const PlatformMeasurements& m);

// Pearson correlation of x and y (NaN when n < 2 or a variance is 0).
double pearson(const std::vector<double>& x, const std::vector<double>& y);

}  // namespace ra::timing
