// The point audit against theory, at a size CI can afford (the full-size figures are in the
// issue notes): on llvmpipe, PE should follow the distance from a uniform point of the unit pixel
// square to its centre, and the true-visible fraction should be the frustum's solid angle.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>

#include "stats/descriptive.h"
#include "metrics/records.h"
#include "rundir/records_reader.h"
#include "tests/cli_harness.h"

using namespace ra::testing_cli;

namespace {

// PE for per-axis errors uniform on [-0.5, 0.5]: for r <= 0.5 the CDF is pi r^2 and the density
// 2 pi r, so the quartiles are sqrt(p / pi) (all three are below 0.5).
double pe_quantile(double p) { return std::sqrt(p / M_PI); }
double pe_density(double r) { return 2 * M_PI * r; }

// Fraction of a uniform ball inside a square frustum of full angle `fov_deg` (solid angle
// 4 asin(sin^2(a/2)) over 4 pi), less the pyramid nearer than the near plane.
double visible_fraction(double fov_deg, double near) {
  const double half = fov_deg * M_PI / 360.0;
  const double cone = 4 * std::asin(std::sin(half) * std::sin(half)) / (4 * M_PI);
  const double side = 2 * near * std::tan(half);
  const double near_pyramid = side * side * near / 3.0;
  return cone - near_pyramid / (4.0 * M_PI / 3.0);
}

TEST(PointStatistics, SolidAngleFormulaMatchesThePaperNumbers) {
  EXPECT_NEAR(visible_fraction(30, 0), 0.02134, 5e-6);
  EXPECT_NEAR(visible_fraction(150, 0), 0.3828, 5e-5);
}

TEST(PointStatistics, LlvmpipeMatchesUniformErrorAndSolidAngle) {
  const int n = 40000;
  const std::string dir = fresh_dir("point_stats");
  write_text(dir + "/e.toml",
             "seed = 2008\nplatforms = [\"osmesa-llvmpipe\"]\n[views]\norientations = 2\n"
             "fov_deg = [30, 150]\nwindows = [128]\nnear = 0.01\nfar = 10.0\n[primitives]\n"
             "points = " + std::to_string(n) + "\n[run]\nshard_size = 20000\n");
  const Outcome o = run_renderaudit("run " + dir + "/e.toml --out " + dir + "/run --quiet");
  ASSERT_EQ(o.exit_code, 0) << o.output;

  std::vector<double> pe;
  std::map<double, std::pair<int, int>> visible;  // fov -> (true-visible, total)
  for (const auto& e : std::filesystem::directory_iterator(dir + "/run/records")) {
    ra::rundir::read_records(e.path().string(), [&](const ra::metrics::Record& r) {
      auto& v = visible[r.fov_deg];
      ++v.second;
      if (r.visibility == ra::metrics::Visibility::kTrueVisible) {
        ++v.first;
        pe.push_back(r.pe);
      }
    });
  }
  for (const auto& [fov, counts] : visible) {
    const double p = visible_fraction(fov, 0.01), m = counts.second;
    const double se = std::sqrt(p * (1 - p) / m);
    EXPECT_NEAR(counts.first / m, p, 4 * se) << "FOV " << fov;
  }

  // Asymptotic standard errors of sample quantiles: var(q_p) = p(1-p) / (n f(q_p)^2), and
  // cov(q_a, q_b) = a(1-b) / (n f_a f_b) for a < b.
  const double m = pe.size();
  const ra::stats::Description d = ra::stats::describe(pe);
  const double med = pe_quantile(0.5), q1 = pe_quantile(0.25), q3 = pe_quantile(0.75);
  const double f1 = pe_density(q1), f3 = pe_density(q3);
  const double se_median = std::sqrt(0.25 / m) / pe_density(med);
  const double se_iqr =
      std::sqrt((0.1875 / (f1 * f1) + 0.1875 / (f3 * f3) - 2 * 0.0625 / (f1 * f3)) / m);
  EXPECT_NEAR(med, 0.3990, 1e-4);
  EXPECT_NEAR(q3 - q1, 0.2065, 1e-4);
  EXPECT_NEAR(d.median, med, 3 * se_median) << "n = " << m;
  EXPECT_NEAR(d.iqr, q3 - q1, 3 * se_iqr) << "n = " << m;
}

}  // namespace
