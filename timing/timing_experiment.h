// The experiment file of `renderaudit timing`: a [timing] table with the study's settings and
// [[scene]] tables (scenes/scene_spec.h). Every key is checked before anything renders; an unknown
// key, a wrong type or a value out of range is a UserError "FILE:LINE:COLUMN: what (allowed: ...)".
//
//   name = "timing"                 # optional: default the file's stem
//   [timing]
//   platforms = ["osmesa-llvmpipe", "osmesa-softpipe"]   # OSMesa platforms; default llvmpipe
//   window = [640, 480]             # pixels, 16..4096 each
//   fov_deg = 60                    # vertical field of view, (0, 180)
//   near = 0.5                      # metres, > 0
//   far = 20000                     # metres, > near
//   repetitions = 5                 # timed repetitions per measurement, 1..1000
//   system_task_renders = 10000     # renderings of the system-task viewpoint, 10..1000000
//   system_task_scene = "city"      # whose path holds that viewpoint (default: the first scene)
//   system_task_frame = 10          # which frame of that path, 0..frames-1 (default: the middle)
//   object_samples = 10000          # random object measurements per platform, 10..10000000
//   cache_size = 16                 # FIFO vertex-cache entries for #tv, 3..1024
//   seed = 1                        # viewpoints of the object measurements, 0..2^63-1
//   gpu_timer = true                # also time with GL_TIME_ELAPSED where supported
//   frame_stride = 1                # measure every k-th frame of each camera path, 1..100000
//   pos_repetitions = 3             # timed draws per pos table point, 1..1000
//   alpha_min_deg = 0.5             # smallest clipped alpha of object measurements, (0, 90)
//   phi_deg = [-20, 80]             # elevation range of object measurements, within [-90, 90]
//   pos_grid = [6, 8, 3]            # per-object table points in alpha, gamma, phi: 2..64, 1..64, 1..64
//   pos_prune_alpha_deg = 3         # table rows below this alpha: one measurement, [0, 180)
//   pos_lookup = "interpolate"      # or "nearest"
//   study_runs = 1                  # independent runs of the whole measurement, 1..100 (Table 6
//                                   # and c then also as mean and spread over the runs)
//   [timing.platform."osmesa-softpipe"]   # optional per-platform overrides of:
//   repetitions = 3                 #   repetitions, system_task_renders, object_samples,
//   frame_stride = 2                #   frame_stride, pos_repetitions
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "scenes/scene_spec.h"
#include "timing/time_heuristics.h"
#include "scenes/study_settings.h"

namespace ra::timing {

// The knobs that cost time, per platform.
struct WorkSettings {
  int repetitions = 5;
  int system_task_renders = 10000;
  int object_samples = 10000;
  int frame_stride = 1;
  int pos_repetitions = 3;  // timed draws per per-object sampling table point (median)
};

struct TimingSettings : scenes::StudySettings {  // file, name, camera
  std::vector<std::string> platforms{"osmesa-llvmpipe"};
  WorkSettings work;
  std::map<std::string, WorkSettings> platform_work;  // resolved per platform (defaults filled in)
  unsigned cache_size = 16;
  uint64_t seed = 1;
  bool gpu_timer = true;
  double alpha_min_deg = 0.5;
  double phi_min_deg = -20, phi_max_deg = 80;
  PosGrid pos_grid;  // alpha range filled from alpha_min_deg and the camera
  double pos_prune_alpha_deg = 3;
  PosLookup pos_lookup = PosLookup::kInterpolate;
  std::vector<scenes::SceneSpec> scenes;
  std::string system_task_scene;  // a scene's name; empty: the first scene
  int system_task_frame = -1;     // a frame of that scene's camera path; -1: the middle one
  // Independent runs of the whole measurement (every platform measured afresh each time), to see
  // how far Table 6 and c move between runs; not `repetitions`, which counts the timed draws of
  // one measurement. 1: a single study.
  int study_runs = 1;

  const WorkSettings& work_for(const std::string& platform) const;
};

// Reads and validates `path`. Throws UserError (file:line:column) for bad input, also when there
// is no [[scene]] or a platform has no Mesa driver.
TimingSettings read_timing_experiment(const std::string& path);
TimingSettings parse_timing_experiment(const std::string& text, const std::string& path);

}  // namespace ra::timing
