// Tests of the least-squares fit: NIST StRD certified values (Norris: straight line; Pontius:
// quadratic with x^2 up to 9e12), known coefficients recovered from synthetic frame timings with
// noise, a no-intercept fit against exact rational arithmetic, and the refusals of bad input.
#include "stats/linear_regression.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "stats/descriptive.h"
#include "stats/stats_testing.h"
#include "util/errors.h"

namespace ra::stats {
namespace {

// NIST StRD linear regression data set: y and x columns, certified estimates of B0, B1, ... with
// their standard deviations, the residual standard deviation and R-squared.
struct StrdRegression {
  std::vector<double> y, x;
  std::vector<double> estimate, sd;  // B0, B1, ...
  double residual_sd = 0;
  double r_squared = 0;
};

// The certified block has lines "  B0  estimate  sd", "  Standard Deviation   s" (after
// "Residual") and "  R-Squared   r2"; the data follow the "Data:  y  x" line (both files).
StrdRegression read_strd_regression(const std::string& file) {
  const auto lines = testing::read_lines(testing::strd_path(file));
  StrdRegression s;
  bool have_sd = false, have_r2 = false;
  for (const auto& line : lines) {
    std::istringstream in(line);
    std::string first, second;
    in >> first >> second;
    std::string rest;
    std::getline(in, rest);
    const std::string expected_name = "B" + std::to_string(s.estimate.size());
    if (first == expected_name) {
      const auto v = testing::numbers_of(second + rest);
      if (v.size() != 2) throw std::runtime_error(file + ": bad line '" + line + "'");
      s.estimate.push_back(v[0]);
      s.sd.push_back(v[1]);
    } else if (first == "Standard" && second == "Deviation") {
      const auto v = testing::numbers_of(rest);
      if (v.size() == 1) s.residual_sd = v[0], have_sd = true;
    } else if (first == "R-Squared") {
      const auto v = testing::numbers_of(second + rest);
      if (v.size() == 1) s.r_squared = v[0], have_r2 = true;
    }
  }
  for (const auto& row : testing::strd_data_rows(lines)) {
    s.y.push_back(row.at(0));
    s.x.push_back(row.at(1));
  }
  if (s.estimate.empty() || !have_sd || !have_r2 || s.y.empty()) {
    throw std::runtime_error(file + ": certified values or data not found");
  }
  return s;
}

// Every certified value to at least `min_lre` correct digits; prints the LREs for docs/stats.md.
void expect_certified(const std::string& file, const LinearFit& fit, const StrdRegression& c,
                      double min_lre) {
  ASSERT_EQ(fit.coefficients.size(), c.estimate.size()) << file;
  double worst = std::numeric_limits<double>::infinity();
  std::ostringstream report;
  const auto check = [&](const std::string& what, double computed, double certified) {
    const double lre = testing::lre(computed, certified);
    EXPECT_GE(lre, min_lre) << file << " " << what << ": " << computed << " vs certified "
                            << certified;
    report << " " << what << "=" << lre;
    worst = std::min(worst, lre);
  };
  for (std::size_t j = 0; j < c.estimate.size(); ++j) {
    check("B" + std::to_string(j), fit.coefficients[j], c.estimate[j]);
    check("sd(B" + std::to_string(j) + ")", fit.standard_deviations[j], c.sd[j]);
  }
  check("residual_sd", fit.residual_sd, c.residual_sd);
  ASSERT_TRUE(fit.r_squared.has_value());
  check("r_squared", *fit.r_squared, c.r_squared);
  std::cout << "[ LRE      ] " << file << report.str() << " (min " << worst << ")\n";
}

// Norris: lower difficulty, y = B0 + B1 x, 36 observations.
TEST(LinearRegression, StrdNorris) {
  const auto c = read_strd_regression("Norris.dat");
  ASSERT_EQ(c.y.size(), 36u);
  const LinearFit fit = fit_least_squares({c.x}, c.y, true, {"x"});
  EXPECT_EQ(fit.n, 36u);
  EXPECT_EQ(fit.df, 34u);  // certified ANOVA table: residual df 34
  EXPECT_EQ(fit.rank, 2u);
  EXPECT_TRUE(fit.r_squared_centred);
  EXPECT_EQ(fit.names, (std::vector<std::string>{"(intercept)", "x"}));
  expect_certified("Norris.dat", fit, c, 9);
  // certified residual sum of squares (ANOVA table, line 46)
  EXPECT_GE(testing::lre(fit.rss, 26.6173985294224), 9);
}

// Pontius: average difficulty, y = B0 + B1 x + B2 x^2 with x up to 3e6: the columns differ by 13
// orders of magnitude and x, x^2 are nearly collinear (the normal equations keep ~11 digits).
TEST(LinearRegression, StrdPontius) {
  const auto c = read_strd_regression("Pontius.dat");
  ASSERT_EQ(c.y.size(), 40u);
  std::vector<double> x2;
  for (double v : c.x) x2.push_back(v * v);  // exact: x is an integer below 2^26
  const LinearFit fit = fit_least_squares({c.x, x2}, c.y, true, {"x", "x^2"});
  EXPECT_EQ(fit.df, 37u);
  expect_certified("Pontius.dat", fit, c, 9);
  EXPECT_GE(testing::lre(fit.rss, 0.155761768796992E-05), 9);
}

// A frame-time model as in Wimmer and Wonka's H2: t = c0 + c1 #polys + c2 #pixels + noise. The
// estimates must fall within a few standard deviations of the truth, and the reported standard
// deviations must match the actual spread of the estimates over many noise draws.
TEST(LinearRegression, RecoversKnownCoefficientsFromNoisyTimings) {
  const double c0 = 0.8, c1 = 2.0e-3, c2 = 1.5e-5;  // ms, ms per polygon, ms per pixel
  const double noise_sd = 0.25;                     // ms
  const std::size_t n = 400;
  testing::Generator design(7);
  std::vector<double> polys(n), pixels(n), clean(n);
  for (std::size_t i = 0; i < n; ++i) {
    polys[i] = std::round(1000 + 49000 * design.uniform());
    pixels[i] = std::round(1e4 + 1e6 * design.uniform());
    clean[i] = c0 + c1 * polys[i] + c2 * pixels[i];
  }
  const std::vector<double> truth{c0, c1, c2};

  // one draw: each estimate within 4 of its standard deviations (a 1-in-16000 event per value)
  {
    const auto noise = testing::normal_sample(n, 0, noise_sd, 11);
    std::vector<double> t(n);
    for (std::size_t i = 0; i < n; ++i) t[i] = clean[i] + noise[i];
    const LinearFit fit = fit_least_squares({polys, pixels}, t, true, {"polys", "pixels"});
    for (std::size_t j = 0; j < 3; ++j) {
      EXPECT_LT(std::fabs(fit.coefficients[j] - truth[j]), 4 * fit.standard_deviations[j])
          << fit.names[j] << " = " << fit.coefficients[j];
    }
    // s estimates the noise SD; its own SD is about noise_sd / sqrt(2 df) = 3.5%
    EXPECT_NEAR(fit.residual_sd, noise_sd, 0.12 * noise_sd);
    ASSERT_TRUE(fit.r_squared.has_value());
    EXPECT_GT(*fit.r_squared, 0.99);
  }

  // many draws: the empirical SD of each estimate vs the mean reported SD. With 300 draws the
  // empirical SD is itself uncertain by about 1 / sqrt(600) = 4%; 15% is over 3 of those.
  const int draws = 300;
  std::vector<std::vector<double>> estimates(3);
  std::vector<double> reported_sd(3, 0);
  for (int d = 0; d < draws; ++d) {
    const auto noise = testing::normal_sample(n, 0, noise_sd, 1000 + d);
    std::vector<double> t(n);
    for (std::size_t i = 0; i < n; ++i) t[i] = clean[i] + noise[i];
    const LinearFit fit = fit_least_squares({polys, pixels}, t, true);
    for (std::size_t j = 0; j < 3; ++j) {
      estimates[j].push_back(fit.coefficients[j]);
      reported_sd[j] += fit.standard_deviations[j] / draws;
    }
  }
  for (std::size_t j = 0; j < 3; ++j) {
    const MeanVariance mv = mean_and_variance(estimates[j]);
    const double empirical_sd = std::sqrt(mv.variance);
    EXPECT_NEAR(empirical_sd / reported_sd[j], 1.0, 0.15) << "parameter " << j;
    // unbiased: the mean estimate within 4 standard errors of the mean of the truth
    EXPECT_LT(std::fabs(mv.mean - truth[j]), 4 * empirical_sd / std::sqrt(draws))
        << "parameter " << j;
  }
}

// No intercept (time proportional to work): coefficients, their SDs, s, RSS, uncentred R-squared,
// t and p against an independent computation: exact rational normal equations (Python fractions,
// of the very doubles below; rounded to double only at the end) and SciPy's t distribution:
//   /usr/bin/python3 - <<'EOF'
//   from fractions import Fraction as F
//   import scipy.stats as st
//   polys = [1000, 2500, 4000, 5200, 7000, 8800, 10000, 12500, 15000, 20000]
//   pixels = [50000, 120000, 30000, 200000, 90000, 160000, 60000, 250000, 110000, 180000]
//   ms = [2.531, 6.174, 8.362, 12.385, 14.853, 19.247, 20.588, 27.561, 31.046, 41.829]
//   X = [[F(a), F(b)] for a, b in zip(polys, pixels)]; y = [F(v) for v in ms]
//   a = [[sum(r[i] * r[j] for r in X) for j in range(2)] for i in range(2)]
//   c = [sum(r[i] * v for r, v in zip(X, y)) for i in range(2)]
//   det = a[0][0] * a[1][1] - a[0][1] * a[1][0]
//   inv = [[a[1][1] / det, -a[0][1] / det], [-a[1][0] / det, a[0][0] / det]]
//   b = [inv[i][0] * c[0] + inv[i][1] * c[1] for i in range(2)]
//   rss = sum((v - r[0] * b[0] - r[1] * b[1]) ** 2 for r, v in zip(X, y)); s2 = rss / 8
//   se = [float(s2 * inv[i][i]) ** 0.5 for i in range(2)]
//   t = [float(b[i]) / se[i] for i in range(2)]
//   print([repr(float(v)) for v in b], [repr(v) for v in se], repr(float(s2) ** 0.5),
//         repr(float(rss)), repr(float(1 - rss / sum(v * v for v in y))), [repr(v) for v in t],
//         [repr(2 * st.t.sf(abs(v), 8)) for v in t])
//   EOF
// (numpy.linalg.lstsq gives the same coefficients to the 9 digits it prints.)
TEST(LinearRegression, NoInterceptAgainstExactArithmetic) {
  const std::vector<double> polys{1000, 2500, 4000, 5200, 7000, 8800, 10000, 12500, 15000, 20000};
  const std::vector<double> pixels{50000,  120000, 30000,  200000, 90000,
                                   160000, 60000,  250000, 110000, 180000};
  const std::vector<double> ms{2.531,  6.174,  8.362,  12.385, 14.853,
                               19.247, 20.588, 27.561, 31.046, 41.829};
  const LinearFit fit = fit_least_squares({polys, pixels}, ms, false, {"polys", "pixels"});
  EXPECT_FALSE(fit.intercept);
  EXPECT_FALSE(fit.r_squared_centred);
  EXPECT_EQ(fit.names, (std::vector<std::string>{"polys", "pixels"}));
  EXPECT_EQ(fit.df, 8u);
  const auto expect_digits = [](double computed, double reference, const char* what) {
    EXPECT_GE(testing::lre(computed, reference), 12) << what << ": " << computed;
  };
  expect_digits(fit.coefficients[0], 0.0019990830949952842, "b polys");
  expect_digits(fit.coefficients[1], 1.012801781976276e-05, "b pixels");
  expect_digits(fit.standard_deviations[0], 2.7031230086860667e-06, "sd polys");
  expect_digits(fit.standard_deviations[1], 1.955786217903196e-07, "sd pixels");
  expect_digits(fit.residual_sd, 0.045393165967053124, "residual sd");
  expect_digits(fit.rss, 0.016484316132099438, "rss");
  ASSERT_TRUE(fit.r_squared.has_value());
  expect_digits(*fit.r_squared, 0.9999965339141041, "uncentred r squared");
  const CoefficientTest t0 = coefficient_t_test(fit, 0);
  const CoefficientTest t1 = coefficient_t_test(fit, 1);
  expect_digits(t0.t, 739.5457360140625, "t polys");
  expect_digits(t1.t, 51.78489206566267, "t pixels");
  // p from Boost vs SciPy (both accurate in the far tail; compared to 10 digits)
  EXPECT_GE(testing::lre(t0.p_value, 1.2516268025006684e-20), 10) << t0.p_value;
  EXPECT_GE(testing::lre(t1.p_value, 2.1425754141254986e-11), 10) << t1.p_value;
}

// Intercept only: the fit is the mean, its SD the standard error of the mean, R-squared 0.
TEST(LinearRegression, InterceptOnlyIsTheMean) {
  const std::vector<double> y{3, 5, 4, 8, 10};
  const LinearFit fit = fit_least_squares({}, y, true);
  EXPECT_DOUBLE_EQ(fit.coefficients[0], 6.0);
  // s^2 = (9 + 1 + 4 + 4 + 16) / 4 = 8.5, sd of the mean = sqrt(8.5 / 5)
  EXPECT_DOUBLE_EQ(fit.residual_sd, std::sqrt(8.5));
  EXPECT_DOUBLE_EQ(fit.standard_deviations[0], std::sqrt(8.5 / 5));
  ASSERT_TRUE(fit.r_squared.has_value());
  EXPECT_NEAR(*fit.r_squared, 0.0, 1e-15);
}

// An exact fit: residual SD 0, coefficient SDs 0, t undefined (std::invalid_argument, which the
// command prints as null with the reason).
TEST(LinearRegression, ExactFitHasZeroDeviationsAndNoT) {
  const std::vector<double> x{1, 2, 3, 4};
  const std::vector<double> y{3, 5, 7, 9};  // 1 + 2x
  const LinearFit fit = fit_least_squares({x}, y, true);
  EXPECT_NEAR(fit.coefficients[0], 1.0, 1e-14);
  EXPECT_NEAR(fit.coefficients[1], 2.0, 1e-14);
  EXPECT_NEAR(fit.residual_sd, 0.0, 1e-14);
  LinearFit exact = fit;
  exact.standard_deviations = {0, 0};  // as when the residuals cancel to the last bit
  EXPECT_THROW(coefficient_t_test(exact, 0), std::invalid_argument);
  EXPECT_THROW(coefficient_t_test(fit, 2), std::out_of_range);
}

// R-squared is undefined when y has no variation to explain.
TEST(LinearRegression, ConstantResponseHasNoRSquared) {
  const LinearFit fit = fit_least_squares({{1, 2, 3, 4}}, {5, 5, 5, 5}, true);
  EXPECT_FALSE(fit.r_squared.has_value());
  EXPECT_NEAR(fit.coefficients[1], 0.0, 1e-15);
}

std::string user_error(const std::vector<std::vector<double>>& predictors,
                       const std::vector<double>& y, bool intercept,
                       const std::vector<std::string>& names = {}) {
  try {
    fit_least_squares(predictors, y, intercept, names);
  } catch (const UserError& e) {
    return e.what();
  }
  return "(no UserError)";
}

TEST(LinearRegression, RankDeficientDesignIsRefusedNamingTheColumn) {
  const std::vector<double> polys{100, 250, 400, 520, 700};
  std::vector<double> vertices;  // a triangle soup: exactly 3 vertices per polygon
  for (double p : polys) vertices.push_back(3 * p);
  const std::vector<double> t{1.1, 2.4, 3.9, 5.3, 6.8};
  const std::string proportional = user_error({polys, vertices}, t, true, {"polys", "verts"});
  EXPECT_NE(proportional.find("rank 2 for 3 parameters"), std::string::npos) << proportional;
  // scaled, the two columns are equal: rounding decides which one pivoting names as dependent
  const bool names_one = proportional.find("'polys' is (to within") != std::string::npos ||
                         proportional.find("'verts' is (to within") != std::string::npos;
  EXPECT_TRUE(names_one) << proportional;
  // a constant predictor duplicates the intercept
  const std::string constant = user_error({polys, {2, 2, 2, 2, 2}}, t, true, {"polys", "fov"});
  EXPECT_NE(constant.find("rank 2 for 3 parameters"), std::string::npos) << constant;
  EXPECT_NE(constant.find("'(intercept)'"), std::string::npos) << constant;
  // a column of zeros
  const std::string zero = user_error({polys, {0, 0, 0, 0, 0}}, t, false, {"polys", "lights"});
  EXPECT_NE(zero.find("'lights' is 0 in every observation"), std::string::npos) << zero;
  // nearly dependent beyond the tolerance: 1e-9 relative perturbation is still refused
  std::vector<double> almost = vertices;
  almost[2] *= 1 + 1e-9;
  EXPECT_NE(user_error({polys, almost}, t, true).find("rank 2"), std::string::npos);
}

TEST(LinearRegression, TooFewObservationsAreRefused) {
  // two points, two parameters: a line through them leaves no degree of freedom for s
  const std::string two = user_error({{1, 2}}, {3, 4}, true, {"x"});
  EXPECT_NE(two.find("2 observation(s) for 2 parameter(s) ('(intercept)', 'x'); at least 3"),
            std::string::npos)
      << two;
  EXPECT_NE(user_error({}, {1}, true).find("1 observation(s) for 1 parameter(s)"),
            std::string::npos);
  EXPECT_NE(user_error({}, {1, 2, 3}, false).find("no parameters"), std::string::npos);
  const std::string lengths = user_error({{1, 2, 3}}, {1, 2, 3, 4}, true, {"x"});
  EXPECT_NE(lengths.find("predictor 'x' has 3 values but y has 4"), std::string::npos) << lengths;
}

TEST(LinearRegression, NonFiniteInputIsRefused) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const std::string in_x = user_error({{1, 2, nan, 4}}, {1, 2, 3, 4}, true, {"pixels"});
  EXPECT_NE(in_x.find("predictor 'pixels', observation 3 of 4, is nan"), std::string::npos) << in_x;
  const std::string in_y = user_error({{1, 2, 3, 4}}, {1, 2, 3, -inf}, true);
  EXPECT_NE(in_y.find("the response y, observation 4 of 4, is -inf"), std::string::npos) << in_y;
}

}  // namespace
}  // namespace ra::stats
