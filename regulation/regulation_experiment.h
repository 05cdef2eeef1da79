// The experiment file of the regulation study: a top-level [regulation] table (rundir/study_dir.h)
// with the study's settings and one [[scene]] table (scenes/scene_spec.h) with its camera path.
// Every key is checked before anything is computed; an unknown key, a wrong type or a value out of
// range is a UserError "FILE:LINE:COLUMN: 'regulation.key' = V is out of range (allowed: ...)".
//
//   name = "regulation"            # optional: default the file's stem
//   [regulation]
//   platform = "osmesa-llvmpipe"   # OSMesa platform the plans are rendered on (or osmesa-softpipe)
//   window = [640, 480]            # pixels, 16..4096 each
//   fov_deg = 60                   # vertical field of view, (0, 180)
//   near = 0.5                     # metres, > 0
//   far = 20000                    # metres, > near
//   lod_ratios = [1, 0.5, 0.25, 0.125, 0.0625]  # triangle ratios of the levels: 1 first, then
//                                  #   decreasing in (0, 1); 2..16 levels
//   cache_size = 16                # FIFO vertex-cache entries for #tv, 3..1024
//   seed = 1                       # attention tags and random instances, 0..2^63-1
//   budgets_ms = [4, 8, 16]        # frame-time budgets, ms, increasing, each in (0, 10000]; 1..64
//   frame_stride = 1               # plan every k-th frame of the camera path, 1..100000
//   repetitions = 5                # timed draws of every rendered plan, 1..1000 (median kept too)
//   render = true                  # render the plans (false: predictions only)
//   error_exponent = 2             # fiducial = (projected error in pixels)^exponent, (0, 8]
//   dp_max_cells = 400000000       # largest items x budget units the exact DP may use, 1000..4e9
//   [regulation.cost_model]        # H4 = intercept + c1 #tv + c2 #pix, microseconds
//   c1_us_per_tv = 0.13            # >= 0
//   c2_us_per_pixel = 0.086        # >= 0
//   intercept_us = 0               # per object drawn, any finite value
//   pixels = "measured"            # #pix of H4: "measured" (the timing study's pixel query, per
//                                  #   frame, object and level, in the rendering process) or
//                                  #   "estimated" (bounding-sphere disc); render = false always
//                                  #   estimates (there is no GL context to measure in)
//   pixel_factor = 1               # multiplies #pix, (0, 100]
//   cost_unit_us = 1               # knapsack cost unit (costs rounded up), (0, 1e6]
//   timing_json = "../outputs/timing/timing.json"  # optional: read c1, c2 (b0) from a timing
//                                  #   study's output instead (path relative to this file)
//   timing_platform = "osmesa-llvmpipe"  # whose fit (default: platform)
//   timing_intercept = false       # the h4+b fit instead of the paper's h4
//   [regulation.attention]         # Horvitz & Lengyel, equations 4-7
//   alpha = 0.2                    # attenuation for unattended objects, [0, 1]
//   element_given_object = 1       # p(A_S | A_O), [0, 1]
//   probability = { primary_actor = 0.9, secondary_actor = 0.5, critical_environment = 0.25,
//                   background = 0.05 }   # p(A_O | E) per category, each [0, 1]
//   share = { primary_actor = 0.05, secondary_actor = 0.15, critical_environment = 0.3,
//             background = 0.5 }   # seeded tagging shares, each [0, 1], summing to 1
//   tags = { "tree 3" = "primary_actor" }  # declared categories by object name
//   [regulation.random]            # random knapsack instances: greedy against the optimum
//   instances = 1000               # 0..1000000
//   objects = [2, 10]              # items per instance, 1..64
//   levels = [2, 5]                # options per item, 1..16
//   max_cost = 300                 # cost units of an item's finest level, 1..100000
//   adversarial_every = 10         # every k-th instance a trap / tight case, 0 (none)..1000000
//   brute_force_max_plans = 20000  # brute-force check of the DP on instances this small, 0..10^7
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "regulation/attention.h"
#include "regulation/cost_model.h"
#include "regulation/random_instances.h"
#include "scenes/scene_spec.h"
#include "scenes/study_settings.h"

namespace ra::regulation {

struct RegulationSettings : scenes::StudySettings {  // file, name, camera
  std::string platform = "osmesa-llvmpipe";
  std::vector<double> lod_ratios{1, 0.5, 0.25, 0.125, 0.0625};
  unsigned cache_size = 16;
  uint64_t seed = 1;
  std::vector<double> budgets_ms{4, 8, 16};
  int frame_stride = 1;
  int repetitions = 5;
  bool render = true;
  double error_exponent = 2;
  int64_t dp_max_cells = 400'000'000;
  CostModel cost;
  std::string timing_json;  // resolved against the experiment file's folder; empty: explicit
  std::string timing_platform;
  bool timing_intercept = false;
  AttentionModel attention;
  RandomInstanceSettings random;
  scenes::SceneSpec scene;
};

// Throws UserError "'regulation.platform' = "NAME" is out of range (allowed: ...)"
// unless `name` is one the study can render on (rundir/platform_spec.h).
void validate_platform(const std::string& name);

RegulationSettings read_regulation_experiment(const std::string& path);
RegulationSettings parse_regulation_experiment(const std::string& text, const std::string& path);

}  // namespace ra::regulation
