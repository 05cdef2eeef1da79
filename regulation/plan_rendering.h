// Plans along a camera path and their rendering (Horvitz & Lengyel 1997, section 7.2: rendering
// the chosen plans and checking the frame-time budget, the paper's "frame skips").
//
// Per frame of the path (every frame_stride-th), the objects whose bounding spheres meet the view
// frustum become the items of a knapsack instance (policies.h): option k = LOD level k, its cost
// the H4 prediction of the level (cost_model.h) in whole cost units (rounded up), its loss the
// attention-weighted perceptual cost (attention.h x cost_model.h). Objects outside the frustum are
// culled (not drawn, not in the instance). Per frame budget B (ms), the objects may spend
// B - base, base the median measured time of an empty frame (clear + glFinish) on the platform
// (0 when nothing is rendered). Each policy's plan is then drawn as a whole frame (clear + the
// chosen levels + glFinish, timed `repetitions` times, every repetition kept) in a child process
// (Mesa picks its driver once per process), and a frame is *skipped* when the median measured time
// exceeds B.
//
// #pix of H4 (cost_model.h): with cost.measured_pixels and rendering, the child process first
// measures, per planned frame, every level of every visible object with the timing study's pixel
// query (SceneRenderer::pixels_alone: GL_SAMPLES_PASSED, depth test off, untimed), and the frame's
// instance uses those counts; otherwise (estimated pixels, or render = false) the bounding-sphere
// estimate. The perceptual cost's screen area is the estimate in both modes.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "regulation/attention.h"
#include "regulation/cost_model.h"
#include "regulation/lod_chain.h"
#include "regulation/policies.h"
#include "regulation/regulation_experiment.h"
#include "scenes/scene.h"

namespace ra::regulation {

// One visible object of a frame.
struct FrameObject {
  int object = 0;                 // scene object (and chain) index
  Footprint footprint;
  double weight = 1;              // attention weight (equation 6)
  std::vector<double> pixels;        // per level, #pix used in H4 (before pixel_factor)
  bool pixels_measured = false;      // `pixels` from the pixel query (else the estimate)
  std::vector<double> predicted_us;  // per level, H4
  std::vector<double> predicted_estimated_us;  // per level, H4 with the estimated #pix
  std::vector<double> perceptual;    // per level, CP before attention
};

// Measured #pix of one frame: per chain index, per level (empty for an object not measured, e.g.
// outside the frustum: the estimate is used for it).
using FramePixels = std::vector<std::vector<double>>;

// The chains whose bounding spheres meet the view frustum of `vp` (the items of its instance).
std::vector<int> visible_chains(const std::vector<LodChain>& chains, const scenes::Viewpoint& vp,
                                const scenes::CameraSettings& cam);

// The knapsack instance of viewpoint `vp`; `objects` receives the visible objects (the items, in
// order). `budget_us` is what the objects may spend. `measured` (optional): #pix of this frame
// (FramePixels), used for the objects it holds.
Instance frame_instance(const std::vector<LodChain>& chains, const std::vector<double>& weights,
                        const scenes::Viewpoint& vp, const RegulationSettings& s, double budget_us,
                        std::vector<FrameObject>* objects, const FramePixels* measured = nullptr);

// One planned (and possibly rendered) frame.
struct FrameRecord {
  int frame = 0;
  double budget_ms = 0;
  std::string policy;
  int visible = 0;              // objects in the instance
  int64_t budget_units = 0;     // what the objects may spend, cost units
  int64_t plan_units = 0;       // what the plan spends, cost units
  double predicted_us = 0;      // base + sum of the chosen levels' H4 (unrounded)
  double predicted_estimated_us = 0;  // the same plan with the estimated #pix (= predicted_us
                                      //   when the estimate is what was used)
  double pixels = 0;            // sum of the chosen levels' #pix used in H4
  int64_t transformed = 0;      // sum of the chosen levels' #tv
  double expected_cost = 0;     // the plan's expected perceptual cost
  double value = 0;             // saved over the all-coarsest plan
  double value_ratio_to_optimal = 1;  // value(OPT) / value(plan); 1 when both 0
  bool fits = true;             // the plan's cost units fit the budget
  bool feasible = true;         // the all-coarsest plan fits (else no policy can)
  int64_t triangles = 0;        // drawn
  std::vector<double> measured_us;  // every repetition (empty when not rendered)
  double measured_median_us = 0;    // NaN when not rendered
  bool skipped = false;             // measured median > budget
  std::vector<int> draw;            // objects of the LOD scene drawn (internal)
};

// One object's #pix at one planned frame: every level measured, and the estimate.
struct PixelSample {
  int frame = 0, object = 0;
  double distance_m = 0, radius_m = 0;
  double estimated = 0;           // bounding-sphere disc (cost_model.h)
  std::vector<double> measured;   // per level, GL_SAMPLES_PASSED with the depth test off
};

struct RenderOutcome {
  std::string renderer, version;   // GL strings ("" when not rendered)
  bool pixels_measured = false;    // the plans used measured #pix
  std::vector<PixelSample> pixels; // every measured (frame, visible object); empty otherwise
  double base_us = 0;              // median empty frame
  std::vector<double> base_reps_us;
  std::vector<FrameRecord> records;
  std::string error;               // a failure of the measuring process
  double seconds = 0;
};

// Plans every frame x budget x policy (policies.h, kAllPolicies); renders them when s.render
// (in a child process; the planning then happens there too, after the empty frame is measured).
RenderOutcome plan_and_render(const scenes::Scene& scene, const std::vector<LodChain>& chains,
                              const std::vector<double>& weights,
                              const std::vector<scenes::Viewpoint>& path,
                              const RegulationSettings& s, const std::string& scratch_dir,
                              bool progress);

}  // namespace ra::regulation
