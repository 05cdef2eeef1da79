// Tests of the estimation side of the timing study (time_heuristics.h): fits recover known
// coefficients from synthetic timings, the per-object table interpolates, c at 99 % matches an
// analytic quantile, Table 6's error on a hand-computed example.
#include "timing/time_heuristics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "util/errors.h"

namespace ra::timing {
namespace {

// Objects like the scenes': #tris 50..20000, #v and #tv correlated with #tris but not collinear,
// #pix 0..300000 independent of the geometry.
std::vector<ObjectCounts> synthetic_objects(std::size_t n, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> tris(50, 20000), ratio(0.5, 1.2), vr(0.6, 1.4),
      pix(0, 300000);
  std::vector<ObjectCounts> x(n);
  for (ObjectCounts& o : x) {
    o.triangles = std::round(tris(rng));
    o.transformed = std::round(o.triangles * ratio(rng));
    o.vertices = std::round(o.triangles * vr(rng));
    o.pixels = std::round(pix(rng));
  }
  return x;
}

double param(const HeuristicFit& f, const std::string& name) {
  for (std::size_t k = 0; k < f.names.size(); ++k)
    if (f.names[k] == name) return f.coefficients[k];
  ADD_FAILURE() << "no parameter " << name;
  return NAN;
}
double se(const HeuristicFit& f, const std::string& name) {
  for (std::size_t k = 0; k < f.names.size(); ++k)
    if (f.names[k] == name) return f.standard_errors[k];
  return NAN;
}

// Each linear heuristic, without intercept, on data generated from it with Gaussian noise of
// sd 20 us: the estimate lies within 4 standard errors of the truth, the standard error is
// small against the coefficient, and the residual sd matches the noise.
TEST(TimeHeuristics, LinearFitsRecoverKnownCoefficients) {
  std::mt19937_64 rng(11);
  const auto x = synthetic_objects(3000, rng);
  std::normal_distribution<double> noise(0, 20);
  struct Case {
    Heuristic h;
    std::vector<std::pair<std::string, double>> truth;
  };
  const Case cases[] = {{Heuristic::kH1, {{"c", 0.05}}},
                        {Heuristic::kH2, {{"c", 0.08}}},
                        {Heuristic::kH4, {{"c1", 0.06}, {"c2", 0.002}}}};
  for (const Case& c : cases) {
    std::vector<double> y;
    for (const ObjectCounts& o : x) {
      HeuristicFit truth;
      truth.heuristic = c.h;
      for (auto& t : c.truth) truth.coefficients.push_back(t.second);
      y.push_back(truth.predict(o) + noise(rng));
    }
    const HeuristicFit f = fit_heuristic(c.h, x, y, false);
    EXPECT_FALSE(f.intercept);
    for (auto& [name, value] : c.truth) {
      EXPECT_NEAR(param(f, name), value, 4 * se(f, name)) << heuristic_name(c.h) << " " << name;
      EXPECT_LT(se(f, name), 0.02 * value) << heuristic_name(c.h) << " " << name;
    }
    EXPECT_NEAR(f.rmse, 20, 2) << heuristic_name(c.h);
    EXPECT_GT(f.r_squared, 0.9);
    // with an intercept, the true intercept 0 is found within its error
    const HeuristicFit fb = fit_heuristic(c.h, x, y, true);
    EXPECT_EQ(fb.names.front(), "b0");
    EXPECT_NEAR(param(fb, "b0"), 0, 4 * se(fb, "b0"));
  }
}

// An intercept is recovered when the data have one (a per-draw constant of 150 us).
TEST(TimeHeuristics, InterceptRecovered) {
  std::mt19937_64 rng(5);
  const auto x = synthetic_objects(2000, rng);
  std::normal_distribution<double> noise(0, 10);
  std::vector<double> y;
  for (const ObjectCounts& o : x) y.push_back(150 + 0.07 * o.transformed + 0.001 * o.pixels + noise(rng));
  const HeuristicFit f = fit_heuristic(Heuristic::kH4, x, y, true);
  EXPECT_NEAR(param(f, "b0"), 150, 4 * se(f, "b0"));
  EXPECT_NEAR(param(f, "c1"), 0.07, 4 * se(f, "c1"));
  EXPECT_NEAR(param(f, "c2"), 0.001, 4 * se(f, "c2"));
}

// H3 on data generated from the max model: the alternating least-squares fit finds c1, c2, c3
// within 3 % and assigns the samples to the right branches (the generating model's assignment,
// up to the samples within the noise of the switch).
TEST(TimeHeuristics, H3MaxModelRecoversItsCoefficients) {
  std::mt19937_64 rng(3);
  const auto x = synthetic_objects(4000, rng);
  std::normal_distribution<double> noise(0, 3);
  const double c1 = 0.02, c2 = 0.015, c3 = 0.0025;
  std::vector<double> y;
  std::size_t geometry_truth = 0;
  for (const ObjectCounts& o : x) {
    const double g = c1 * o.triangles + c2 * o.vertices, r = c3 * o.pixels;
    geometry_truth += g >= r;
    y.push_back(std::max(g, r) + noise(rng));
  }
  ASSERT_GT(geometry_truth, 800u);  // both branches well represented
  ASSERT_LT(geometry_truth, 3200u);
  const HeuristicFit f = fit_heuristic(Heuristic::kH3, x, y, false);
  EXPECT_EQ(f.names, (std::vector<std::string>{"c1", "c2", "c3"}));
  EXPECT_NEAR(param(f, "c1"), c1, 0.03 * c1);
  EXPECT_NEAR(param(f, "c2"), c2, 0.03 * c2);
  EXPECT_NEAR(param(f, "c3"), c3, 0.03 * c3);
  EXPECT_TRUE(f.converged);
  EXPECT_NEAR(double(f.geometry_limited), double(geometry_truth), 0.02 * x.size());
  EXPECT_NEAR(f.rmse, 3, 0.3);
  // the max model fits better than either branch alone
  EXPECT_LT(f.sse, fit_heuristic(Heuristic::kH4, x, y, false).sse);

  // with intercepts: max(bg + c1 t + c2 v, br + c3 pix)
  std::vector<double> yb;
  for (std::size_t i = 0; i < x.size(); ++i)
    yb.push_back(std::max(40 + c1 * x[i].triangles + c2 * x[i].vertices, 90 + c3 * x[i].pixels) +
                 noise(rng));
  const HeuristicFit fb = fit_h3(x, yb, true);
  EXPECT_NEAR(param(fb, "bg"), 40, 4);
  EXPECT_NEAR(param(fb, "br"), 90, 4);
  EXPECT_NEAR(param(fb, "c3"), c3, 0.03 * c3);
  EXPECT_NEAR(fb.predict({10000, 8000, 5000, 0}), 40 + c1 * 10000 + c2 * 8000, 3);
}

// Purely geometry-limited data: H3 stays a good fit (the all-geometry start).
TEST(TimeHeuristics, H3OnGeometryOnlyData) {
  std::mt19937_64 rng(8);
  auto x = synthetic_objects(500, rng);
  std::normal_distribution<double> noise(0, 1);
  std::vector<double> y;
  for (const ObjectCounts& o : x) y.push_back(0.03 * o.triangles + 0.01 * o.vertices + noise(rng));
  const HeuristicFit f = fit_heuristic(Heuristic::kH3, x, y, false);
  EXPECT_NEAR(f.rmse, 1, 0.2);
  EXPECT_NEAR(param(f, "c1"), 0.03, 0.002);
}

TEST(TimeHeuristics, TooFewSamplesIsAUserError) {
  std::vector<ObjectCounts> x(2, ObjectCounts{10, 10, 10, 10});
  EXPECT_THROW(fit_heuristic(Heuristic::kH4, x, {1, 2}, true), util::UserError);
  EXPECT_THROW(fit_heuristic(Heuristic::kH3, x, {1, 2}, false), util::UserError);
}

// c = q_0.99 - min. On the evenly spaced sample 0, 1, ..., 10000 the HF6 quantile at 0.99 sits
// at position 0.99 * 10002 = 9901.98, i.e. value 9900.98.
TEST(SystemTask, ConstantOnEvenlySpacedSample) {
  std::vector<double> v;
  for (int i = 10000; i >= 0; --i) v.push_back(1000 + i);  // order must not matter
  const SystemTaskStats s = system_task_stats(v, 0.99);
  EXPECT_EQ(s.n, 10001u);
  EXPECT_DOUBLE_EQ(s.min_us, 1000);
  EXPECT_NEAR(s.q99_us, 1000 + 9900.98, 1e-9);
  EXPECT_NEAR(s.c_us, 9900.98, 1e-9);
  EXPECT_DOUBLE_EQ(s.median_us, 6000);
}

// Frame times min + Exponential(rate): the 99 % quantile above the minimum is ln(100) / rate.
// With n = 200,000 the sample quantile's standard error is sqrt(0.99 * 0.01 / n) / (0.01 rate)
// = 0.022 / rate; tolerance 0.1 / rate (4.5 standard errors).
TEST(SystemTask, ConstantMatchesAnalyticQuantile) {
  std::mt19937_64 rng(2003);
  const double rate = 2.0;  // per ms -> mean 0.5 ms above the minimum
  std::exponential_distribution<double> e(rate);
  std::vector<double> v;
  for (int i = 0; i < 200000; ++i) v.push_back(12000 + 1000 * e(rng));  // us
  const SystemTaskStats s = system_task_stats(v);
  EXPECT_NEAR(s.c_us / 1000, std::log(100.0) / rate, 0.1 / rate);
  EXPECT_NEAR(s.min_us, 12000, 1);
}

PosGrid small_grid() {
  PosGrid g;
  g.n_alpha = 4, g.n_gamma = 4, g.n_phi = 3;
  g.alpha_min = 0.1, g.alpha_max = 0.7;
  g.phi_min = -0.2, g.phi_max = 0.8;
  return g;
}

// f = 10 + 50 alpha + 3 phi + 7 k: trilinear interpolation reproduces it exactly between grid
// points in alpha and phi; in gamma it interpolates between neighbouring directions, periodically.
TEST(PosTable, ExactAtGridPointsAndInterpolatesBetween) {
  const PosGrid g = small_grid();
  PosTable t(g, 0.0);
  auto f = [&](int i, int k, int j) { return 10 + 50 * g.alpha_at(i) + 3 * g.phi_at(j) + 7 * k; };
  for (const auto& p : t.points_to_measure()) t.set(p[0], p[1], p[2], f(p[0], p[1], p[2]));
  ASSERT_TRUE(t.complete());
  ASSERT_EQ(t.points_to_measure().size(), g.cells());
  for (int i = 0; i < g.n_alpha; ++i)
    for (int k = 0; k < g.n_gamma; ++k)
      for (int j = 0; j < g.n_phi; ++j) {
        EXPECT_DOUBLE_EQ(t.lookup(g.alpha_at(i), g.gamma_at(k), g.phi_at(j)), f(i, k, j));
        EXPECT_DOUBLE_EQ(t.lookup(g.alpha_at(i), g.gamma_at(k), g.phi_at(j), PosLookup::kNearest),
                         f(i, k, j));
      }
  // between alpha and phi points, on a gamma node: the linear function itself
  EXPECT_NEAR(t.lookup(0.25, g.gamma_at(1), 0.1), 10 + 50 * 0.25 + 3 * 0.1 + 7, 1e-12);
  // half way between gamma nodes 1 and 2
  EXPECT_NEAR(t.lookup(0.3, 0.5 * (g.gamma_at(1) + g.gamma_at(2)), 0.3), 10 + 15 + 0.9 + 10.5,
              1e-12);
  // between the last node (k = 3) and 2 pi (= node 0): periodic
  const double g_mid = 0.5 * (g.gamma_at(3) + 2 * M_PI);
  EXPECT_NEAR(t.lookup(0.1, g_mid, -0.2), 10 + 5 - 0.6 + 0.5 * 21, 1e-12);
  EXPECT_NEAR(t.lookup(0.1, g_mid - 2 * M_PI, -0.2), t.lookup(0.1, g_mid, -0.2), 1e-12);
  // clamped outside the grid: alpha below the smallest = the smallest's value
  EXPECT_DOUBLE_EQ(t.lookup(0.0, 0, -0.2), f(0, 0, 0));
  EXPECT_DOUBLE_EQ(t.lookup(3.0, 0, 5.0), f(3, 0, 2));
  // nearest: the closest node
  EXPECT_DOUBLE_EQ(t.lookup(0.29, g.gamma_at(2) + 0.1, 0.25, PosLookup::kNearest), f(1, 2, 1));
}

// Rows below the prune angle are measured once and hold that value for every direction.
TEST(PosTable, PrunedRowsNeedOneMeasurement) {
  const PosGrid g = small_grid();
  PosTable t(g, 0.35);  // alpha 0.1 and 0.3 pruned, 0.5 and 0.7 not
  EXPECT_TRUE(t.pruned_row(0));
  EXPECT_TRUE(t.pruned_row(1));
  EXPECT_FALSE(t.pruned_row(2));
  const auto pts = t.points_to_measure();
  EXPECT_EQ(pts.size(), 2u + 2u * 4u * 3u);
  for (const auto& p : pts) t.set(p[0], p[1], p[2], p[0] < 2 ? 100.0 + p[0] : 500.0);
  ASSERT_TRUE(t.complete());
  EXPECT_DOUBLE_EQ(t.lookup(0.1, 2.0, 0.5), 100);
  EXPECT_DOUBLE_EQ(t.lookup(0.2, 4.0, 0.1), 100.5);
}

// Table 6 by hand: errors 0.5, -0.5 and 0 ms -> (0.25 + 0.25 + 0) / 3 ms^2.
TEST(Table6, AverageSquaredErrorByHand) {
  EXPECT_DOUBLE_EQ(average_squared_error_ms2({1000, 2500, 3000}, {1500, 2000, 3000}), 0.5 / 3);
  EXPECT_DOUBLE_EQ(average_squared_error_ms2({4000}, {1000}), 9.0);
  EXPECT_THROW(average_squared_error_ms2({}, {}), std::invalid_argument);
  EXPECT_THROW(average_squared_error_ms2({1}, {1, 2}), std::invalid_argument);
}

}  // namespace
}  // namespace ra::timing
