// Rendering-time estimation (Wimmer & Wonka 2003, "Rendering Time Estimation for Real-Time
// Rendering", sections 4.2, 5.2, 5.3 and 7.2): the heuristics H1-H4 fitted by least squares on
// object measurements, the per-object sampling table (pos), the system-task constant c, frame
// predictions and the average squared error of Table 6.
//
// Units: times are microseconds (us) unless a name says ms; counts are per draw of one object;
// angles are radians. Coefficients are us per unit of their predictor (us per triangle, ...).
//
// Heuristics (paper section 5.3), ET(x) for one object x:
//   H1 = c * #tris                                   (triangle count)
//   H2 = c * #tv                                     (vertices transformed, FIFO vertex cache)
//   H3 = max(c1 * #tris + c2 * #v, c3 * #pix)        (Funkhouser & Sequin 1993)
//   H4 = c1 * #tv + c2 * #pix                        (the paper's new heuristic)
// The paper's forms have no intercept. Every draw of an object also pays a constant (the draw
// calls, the state set-up, the synchronisation the measurement needs): fit_heuristic() can add a
// per-object intercept b0 (for H3 one per branch: max(bg + c1 #tris + c2 #v, br + c3 #pix)); the
// study fits and reports both forms.
//
// Fitting H3 (the max of two linear models is not linear): alternating least squares on the
// partition of the samples, the algorithm of Magnani & Boyd ("Convex piecewise-linear fitting",
// Optim. Eng. 10, 2009) for max-affine models with two pieces:
//   1. start from coefficients (see the starts below);
//   2. assign each sample to the geometry branch when c1 #tris + c2 #v (+ bg) >= c3 #pix (+ br)
//      under the current coefficients, else to the raster branch;
//   3. refit each branch by least squares (stats/linear_regression.h) on its own samples only;
//   4. repeat 2-3 until the assignment no longer changes (or 100 iterations);
//   5. the result is the iterate with the smallest SSE of the max model, sum (y - H3(x))^2, over
//      all iterations of all starts.
// Starts: (a) the two separate fits, each branch fitted to all samples (the brief's start);
// (b) splits of the samples by the ratio #pix / #tris at its 25 %, 50 % and 75 % quantiles (the
// larger ratios raster-limited); (c) everything geometry-limited (raster branch c3 = 0, br = 0:
// the max model then is the plain geometry fit, so H3 is never worse than that). A branch left
// with fewer samples than its parameters + 1 keeps its previous coefficients. Standard errors of
// H3 are those of each branch's final least-squares fit on its assigned samples (conditional on
// the assignment).
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "timing/timing_samples.h"

namespace ra::timing {

enum class Heuristic { kH1, kH2, kH3, kH4 };
constexpr Heuristic kAllHeuristics[] = {Heuristic::kH1, Heuristic::kH2, Heuristic::kH3,
                                        Heuristic::kH4};

const char* heuristic_name(Heuristic h);     // "h1" .. "h4"
const char* heuristic_formula(Heuristic h);  // e.g. "c1*tv + c2*pix"

// The counts a heuristic reads from one object draw.
struct ObjectCounts {
  double triangles = 0;    // #tris
  double vertices = 0;     // #v
  double transformed = 0;  // #tv
  double pixels = 0;       // #pix
};
ObjectCounts counts_of(const ObjectSample& s);

// A fitted heuristic. Parameters in `names` order; for H3 the geometry branch first:
// ["bg", "c1", "c2", "br", "c3"] with intercepts, ["c1", "c2", "c3"] without.
struct HeuristicFit {
  Heuristic heuristic = Heuristic::kH1;
  bool intercept = false;                 // a per-object constant (per branch for H3)
  std::vector<std::string> names;         // parameter names
  std::vector<std::string> units;         // "us/triangle", "us/vertex", "us/pixel", "us"
  std::vector<double> coefficients;       // in `units`
  std::vector<double> standard_errors;    // same units
  std::size_t n = 0;                      // samples fitted
  double sse = 0;                         // sum of squared residuals, us^2
  double rmse = 0;                        // sqrt(sse / n), us
  double r_squared = 0;                   // 1 - sse / centred total sum of squares
  // H3 only: the final partition and how it was found.
  std::size_t geometry_limited = 0, raster_limited = 0;
  int iterations = 0;                     // of the start that gave the result
  std::string start;                      // which start gave the result (see above)
  bool converged = true;                  // the assignment became stable

  // ET(x) in us for one object.
  double predict(const ObjectCounts& x) const;
};

// Fits `h` to y_us[i] (a time in us, e.g. the median of the repetitions) of objects x[i] by least
// squares. Throws ra::util::UserError when there are too few samples (fewer than parameters + 2) or the
// design is degenerate (e.g. all #pix zero for H4).
HeuristicFit fit_heuristic(Heuristic h, const std::vector<ObjectCounts>& x,
                           const std::vector<double>& y_us, bool intercept);

// The alternating least-squares fit of H3 with explicit controls, for tests.
HeuristicFit fit_h3(const std::vector<ObjectCounts>& x, const std::vector<double>& y_us,
                    bool intercept, int max_iterations = 100);

// ---- System tasks (section 4.2) ----

// The paper: "we estimate the time of the system tasks as a constant c representing the maximum
// deviation of the minimum rendering time for a given confidence interval ... The constant c is
// determined by calculating the width of the given confidence interval with respect to the
// empirical probability distribution function of a test measurement." We read this as the
// one-sided interval that starts at the smallest observed frame time and holds the given share
// of the renderings: c = q_p - min, where q_p is the empirical p-quantile (p = 0.99 for the
// paper's "99 %"), Hyndman-Fan definition 6 (the project's default, stats/descriptive.h).
// A frame budget of min + c then is met by 99 % of the renderings of that viewpoint.
struct SystemTaskStats {
  std::size_t n = 0;
  double min_us = 0, median_us = 0, mean_us = 0, max_us = 0, sd_us = 0;
  double q99_us = 0;  // q_{confidence}
  double c_us = 0;    // q99_us - min_us
  double confidence = 0.99;
};
SystemTaskStats system_task_stats(const std::vector<double>& frame_us, double confidence = 0.99);

// ---- Per-object sampling (section 5.2) ----

// A regular grid over (alpha, gamma, phi). alpha: the angle of the bounding sphere's supporting
// lines seen from the eye, clipped to the view frustum (see clipped_alpha in scenes/camera.h),
// n_alpha points from alpha_min to alpha_max; gamma: azimuth of the eye around the centre,
// n_gamma points 2 pi k / n_gamma (periodic); phi: elevation, n_phi points from phi_min to
// phi_max (one point: phi_min).
struct PosGrid {
  int n_alpha = 6, n_gamma = 8, n_phi = 3;
  double alpha_min = 0.02, alpha_max = 1.0;
  double phi_min = -0.5, phi_max = 1.2;
  double alpha_at(int i) const;
  double gamma_at(int k) const;
  double phi_at(int j) const;
  std::size_t cells() const { return std::size_t(n_alpha) * n_gamma * n_phi; }
};

enum class PosLookup { kNearest, kInterpolate };

// One object's table: the rendering time measured at every grid point. Rows with alpha below the
// prune angle are geometry-limited (the paper: "As the angle alpha becomes smaller, the rendering
// time will be geometry limited and not depend on the viewing parameters any more. We use this
// observation to prune unnecessary test measurements."): they hold one measurement, taken from
// the (gamma_0, phi_0) direction, for every direction.
class PosTable {
 public:
  PosTable() = default;
  PosTable(const PosGrid& grid, double prune_alpha);
  const PosGrid& grid() const { return grid_; }
  double prune_alpha() const { return prune_alpha_; }
  bool pruned_row(int alpha_index) const { return grid_.alpha_at(alpha_index) < prune_alpha_; }
  // The grid points that need a measurement: every (i, k, j) of unpruned rows, (i, 0, 0) of
  // pruned ones.
  std::vector<std::array<int, 3>> points_to_measure() const;
  void set(int i, int k, int j, double us);  // a pruned row's (i, 0, 0) fills the whole row
  double at(int i, int k, int j) const;
  bool complete() const;                     // every cell set
  // ET(x) in us. alpha is clamped to [alpha_min, alpha_max] (below alpha_min the object is
  // geometry-limited: the smallest measured size stands for it), phi to [phi_min, phi_max],
  // gamma wraps. kInterpolate: trilinear (periodic in gamma); kNearest: the closest grid point.
  double lookup(double alpha, double gamma, double phi, PosLookup how = PosLookup::kInterpolate) const;
  const std::vector<double>& values() const { return values_; }

 private:
  std::size_t index(int i, int k, int j) const;
  PosGrid grid_;
  double prune_alpha_ = 0;
  std::vector<double> values_;  // NaN: not set
};

// ---- Frame prediction and Table 6 ----

// Average squared error of per-frame predictions (the paper's Table 6), ms^2: the mean over
// frames of (predicted - measured)^2 with both converted from us to ms. Throws
// std::invalid_argument on empty input or different lengths.
double average_squared_error_ms2(const std::vector<double>& predicted_us,
                                 const std::vector<double>& measured_us);

}  // namespace ra::timing
