// What drawing an object at a level of detail costs (time) and leaves (perceptual cost), seen from
// one viewpoint.
//
// Time: the rendering-time study's heuristic H4 (Wimmer & Wonka 2003, section 5.3; our timing
// study, timing/time_heuristics.h): ET = b0 + c1 * #tv + c2 * #pix, microseconds, with #tv the
// level's transformed vertices (FIFO cache, scenes/vertex_cache.h) and #pix the pixels it covers.
// #pix is what the timing study fitted H4 with: GL_SAMPLES_PASSED of the object drawn alone with
// the depth test off (timing/scene_renderer.h, SceneRenderer::pixels_alone), i.e. every fragment
// its triangles generate inside the window (about twice the silhouette for a closed object).
// Two sources (`pixels`, experiment key regulation.cost_model.pixels):
// - measured (default): that query, per frame, per visible object and per level, in the rendering
//   process before the frame is planned (plan_rendering.h); a simplified level keeps roughly its
//   silhouette, but its own count is used. Only possible when the plans are rendered: with
//   render = false the estimate below is used.
// - estimated: the projected bounding sphere's disc (radius f * r / sqrt(d^2 - r^2) pixels, f the
//   focal length in pixels) as pi/4 of its bounding square clipped to the window (the whole window
//   when the eye is inside the sphere), the same for every level of an object. It overestimates
//   badly for objects near the eye or large and flat (the forest's ground: the whole window).
// `pixel_factor` multiplies #pix of either source.
//
// Perceptual cost (Horvitz & Lengyel 1997, section 7.2: "the product of the screen area occupied
// by a sprite multiplied by ... our fiducial measure of geometric distortion"; section 5.1: the
// fiducial of the Talisman studies is a sum of squared distances of reference points):
//   CP = (screen area / window area) * (e_px / 1 pixel)^exponent,
// e_px = e_m * f / d the simplifier's geometric error (metres) projected at the object's distance
// d, in pixels; exponent 2 by default (squared distance, as the paper's fiducial). 0 at full
// detail (e_m = 0). Dimensionless.
#pragma once

#include <cstdint>
#include <string>

#include "geometry/vector_math.h"
#include "scenes/scene.h"
#include "scenes/camera.h"

namespace ra::regulation {

struct CostModel {
  double c1_us_per_tv = 0.13;     // us per transformed vertex
  double c2_us_per_pixel = 0.086; // us per pixel
  double intercept_us = 0;        // b0: us per object drawn (the H4+b form); 0: the paper's form
  double pixel_factor = 1.0;      // multiplies #pix (measured or estimated)
  bool measured_pixels = true;    // #pix from the pixel query (when rendered), else the estimate
  double cost_unit_us = 1.0;      // integer cost unit of the knapsack (costs rounded up to it)
  std::string source = "explicit";  // where the coefficients came from
};

// H4 for one object: b0 + c1 * tv + c2 * pixels, microseconds.
double predict_us(const CostModel& m, double transformed_vertices, double pixels);
// ceil(us / unit): conservative integer cost units for the knapsack (>= 0).
int64_t cost_units(const CostModel& m, double us);

// The H4 fit of `platform` in a timing study's timing.json (timing/timing_outputs.cpp layout:
// platforms[].name, platforms[].fits[] with heuristic "h4", intercept, parameters b0/c1/c2).
// `intercept`: the h4+b fit. Keeps pixel_factor, measured_pixels and cost_unit_us of `base`. Throws UserError
// naming the file when it is unreadable or holds no such fit.
CostModel cost_model_from_timing_json(const std::string& path, const std::string& platform,
                                      bool intercept, const CostModel& base);

// An object's bounding sphere seen from a viewpoint.
struct Footprint {
  bool visible = false;     // the sphere intersects the view frustum
  double distance_m = 0;    // eye to centre, metres
  double focal_px = 0;      // (height / 2) / tan(half fov y), pixels per unit at distance 1
  double pixels = 0;        // estimated covered pixels (see above; without pixel_factor)
  double area_fraction = 0; // pixels / (width * height), [0, 1]; the perceptual cost's screen
                            //   area (estimated in both #pix modes, so that the modes differ in
                            //   time only)
};
Footprint footprint_of(const scenes::BoundingSphere& s, const geometry::Mat4& view,
                       const scenes::Frustum& frustum, const scenes::CameraSettings& cam);

// The perceptual cost above for one object at one level.
double perceptual_cost(double area_fraction, double error_m, double distance_m, double focal_px,
                       double exponent);

}  // namespace ra::regulation
