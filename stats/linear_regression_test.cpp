// Tests of the least-squares fit: the certified values of every NIST StRD linear regression set
// (Norris, Pontius, NoInt1, NoInt2, Filip, Longley, Wampler1-5) and the exact least-squares
// solutions of their double data (tests/data/strd/lls_exact.json, Python fractions), known
// coefficients recovered from synthetic frame timings with noise, a no-intercept fit against exact
// rational arithmetic, and the refusals of bad input.
#include "stats/linear_regression.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
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
  std::vector<double> y, x;        // x: the first predictor column
  std::vector<std::vector<double>> columns;  // every predictor column (Longley: 6)
  std::vector<double> estimate, sd;  // B0, B1, ...
  double residual_sd = 0;
  double r_squared = 0;
};

// The certified block has lines "  B0  estimate  sd" (B1 first without an intercept),
// "  Standard Deviation   s" (after
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
    // B0 first, or B1 first in the no-intercept sets (NoInt1, NoInt2)
    const std::size_t next = s.estimate.size();
    if (first == "B" + std::to_string(next) || (next == 0 && first == "B1")) {
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
    s.columns.resize(row.size() - 1);
    for (std::size_t j = 1; j < row.size(); ++j) s.columns[j - 1].push_back(row[j]);
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

// The exact least-squares solution of a set's double data (tests/data/strd/lls_exact.json, made
// by lls_exact.py in Python fractions): what the data as doubles determine. design: "columns",
// "exact_powers" (x^k of the double x, exact) or "rounded_powers" (each power rounded to double).
struct ExactSolution {
  std::vector<double> coefficients, sd;
  double residual_sd = 0, r_squared = 0;
};

ExactSolution exact_solution(const std::string& set, const std::string& design) {
  static const nlohmann::json all = [] {
    std::ifstream in(testing::strd_path("lls_exact.json"));
    return nlohmann::json::parse(in);
  }();
  const nlohmann::json& e = all.at("sets").at(set).at(design);
  const auto number = [](const nlohmann::json& v) {
    return std::strtod(v.get<std::string>().c_str(), nullptr);
  };
  ExactSolution x;
  for (const auto& v : e.at("coefficients")) x.coefficients.push_back(number(v));
  for (const auto& v : e.at("sd")) x.sd.push_back(number(v));
  x.residual_sd = number(e.at("residual_sd"));
  x.r_squared = number(e.at("r_squared"));
  return x;
}

// Every certified value (coefficients, their SDs, residual SD, R^2) to LRE >= 13, or, where the
// double data determine fewer digits, to within 0.5 of the LRE of their exact least-squares
// solution. With `against_exact`, also every value to LRE >= 13 against that exact solution
// (values the certificate gives as 0 excepted: their relative error is meaningless).
// Prints the LREs (docs/regression.md); returns the smallest.
double expect_representable_limit(const std::string& label, const LinearFit& fit,
                                  const StrdRegression& c, const ExactSolution& exact,
                                  bool against_exact = false) {
  EXPECT_EQ(fit.coefficients.size(), c.estimate.size()) << label;
  if (fit.coefficients.size() != c.estimate.size()) return 0;
  double worst = std::numeric_limits<double>::infinity();
  std::ostringstream report;
  const auto check = [&](const std::string& what, double computed, double certified,
                         double exact_value) {
    const double limit = std::min(13.0, testing::lre(exact_value, certified) - 0.5);
    const double lre = testing::lre(computed, certified);
    EXPECT_GE(lre, limit) << label << " " << what << ": " << computed << " vs certified "
                          << certified << " (exact solution of the doubles " << exact_value
                          << ")";
    if (against_exact && certified != 0) {
      EXPECT_GE(testing::lre(computed, exact_value), 13)
          << label << " " << what << ": " << computed << " vs exact " << exact_value;
    }
    report << " " << what << "=" << std::min(lre, 99.0);
    worst = std::min(worst, lre);
  };
  for (std::size_t j = 0; j < c.estimate.size(); ++j) {
    check("b" + std::to_string(j), fit.coefficients[j], c.estimate[j], exact.coefficients[j]);
    check("sd" + std::to_string(j), fit.standard_deviations[j], c.sd[j], exact.sd[j]);
  }
  check("residual_sd", fit.residual_sd, c.residual_sd, exact.residual_sd);
  EXPECT_TRUE(fit.r_squared.has_value()) << label;
  check("r_squared", fit.r_squared.value_or(0), c.r_squared, exact.r_squared);
  std::cout << "[ LRE      ] " << label << ": min " << std::min(worst, 99.0) << " ("
            << fit_method_name(fit.method) << ", condition " << fit.condition_number << ");"
            << report.str() << "\n";
  return worst;
}

struct PolynomialSet {
  const char* file;
  const char* name;
  int degree;
};
const PolynomialSet kPolynomialSets[] = {
    {"Pontius.dat", "Pontius", 2},   {"Filip.dat", "Filip", 10},
    {"Wampler1.dat", "Wampler1", 5}, {"Wampler2.dat", "Wampler2", 5},
    {"Wampler3.dat", "Wampler3", 5}, {"Wampler4.dat", "Wampler4", 5},
    {"Wampler5.dat", "Wampler5", 5}};

// The polynomial sets given as x and a degree: powers formed in binary128. Filip (degree 10,
// condition number 5e9) was refused as rank deficient by a double QR with lm's tolerance.
TEST(LinearRegression, StrdPolynomialSetsFromXAndDegree) {
  for (const auto& set : kPolynomialSets) {
    const auto c = read_strd_regression(set.file);
    const LinearFit fit = fit_polynomial(c.x, c.y, set.degree, true, "x");
    EXPECT_EQ(fit.method, FitMethod::kBinary128Qr) << set.name;
    EXPECT_EQ(fit.rank, static_cast<std::size_t>(set.degree + 1)) << set.name;
    expect_representable_limit(std::string(set.name) + " (x, degree)", fit, c,
                               exact_solution(set.name, "exact_powers"));
  }
  const auto filip = read_strd_regression("Filip.dat");
  const LinearFit fit = fit_polynomial(filip.x, filip.y, 10, true, "x");
  EXPECT_EQ(fit.names.back(), "x^10");
  EXPECT_EQ(fit.df, 71u);  // certified ANOVA table
  // NumPy's SVD of the scaled design in double: 5.21e9 (well inside double's reach for sigma_min)
  EXPECT_NEAR(std::log10(fit.condition_number), std::log10(5.21e9), 0.01);
}

// The same sets with the powers given as double columns (what a CSV holds). Their powers are
// exact in double except Filip's, whose rounded powers determine only 7.6 digits of the
// certified values: the fit must still reach the exact solution of those doubles.
TEST(LinearRegression, StrdPolynomialSetsFromColumnsOfPowers) {
  for (const auto& set : kPolynomialSets) {
    const auto c = read_strd_regression(set.file);
    // x^k rounded once to double, as lls_exact.py rounds them (binary128 products: 1e-33)
    std::vector<std::vector<double>> powers(static_cast<std::size_t>(set.degree));
    for (double x : c.x) {
      __float128 v = 1;
      for (auto& column : powers) column.push_back(static_cast<double>(v *= x));
    }
    const LinearFit fit = fit_least_squares(powers, c.y, true);
    expect_representable_limit(std::string(set.name) + " (columns of powers)", fit, c,
                               exact_solution(set.name, "rounded_powers"), true);
  }
}

// The sets with data columns: Norris (a line), NoInt1 and NoInt2 (through the origin), Longley
// (six economic series, condition number 4e4 scaled).
TEST(LinearRegression, StrdColumnSets) {
  const auto norris = read_strd_regression("Norris.dat");
  const LinearFit n = fit_least_squares(norris.columns, norris.y, true);
  EXPECT_EQ(n.method, FitMethod::kDoubleQr);
  EXPECT_NEAR(n.condition_number, 2.8, 0.05);  // NumPy: 2.8
  expect_representable_limit("Norris", n, norris, exact_solution("Norris", "columns"), true);
  for (const char* name : {"NoInt1", "NoInt2"}) {
    const auto c = read_strd_regression(std::string(name) + ".dat");
    const LinearFit fit = fit_least_squares(c.columns, c.y, false);
    EXPECT_FALSE(fit.r_squared_centred);
    expect_representable_limit(name, fit, c, exact_solution(name, "columns"), true);
  }
  const auto longley = read_strd_regression("Longley.dat");
  ASSERT_EQ(longley.columns.size(), 6u);
  const LinearFit l = fit_least_squares(longley.columns, longley.y, true);
  EXPECT_EQ(l.method, FitMethod::kBinary128NormalEquations);
  EXPECT_NEAR(std::log10(l.condition_number), std::log10(4.33e4), 0.01);  // NumPy: 4.33e4
  expect_representable_limit("Longley", l, longley, exact_solution("Longley", "columns"), true);
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
  } catch (const util::UserError& e) {
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
  const bool names_one =
      proportional.find("'polys' is a linear combination") != std::string::npos ||
      proportional.find("'verts' is a linear combination") != std::string::npos;
  EXPECT_TRUE(names_one) << proportional;
  // a constant predictor duplicates the intercept
  const std::string constant = user_error({polys, {2, 2, 2, 2, 2}}, t, true, {"polys", "fov"});
  EXPECT_NE(constant.find("rank 2 for 3 parameters"), std::string::npos) << constant;
  EXPECT_NE(constant.find("'(intercept)'"), std::string::npos) << constant;
  // a column of zeros
  const std::string zero = user_error({polys, {0, 0, 0, 0, 0}}, t, false, {"polys", "lights"});
  EXPECT_NE(zero.find("'lights' is 0 in every observation"), std::string::npos) << zero;
}

// Nearly dependent columns that the data still determine are fitted, not dropped: #vertices =
// 3 #polygons + 1 in one row, with #polygons near 1e9 (a relative perturbation of 1e-10,
// condition number ~1e10). y = 1 + 2 #polys + 3 #verts exactly (integers below 2^53), so the exact
// least-squares solution is (1, 2, 3) with zero residual; a double QR with lm's tolerance (1e-7)
// refused this design as rank 2.
TEST(LinearRegression, NearlyDependentColumnsTheDataDetermineAreFitted) {
  const std::vector<double> polys{1e9, 2.5e9, 4e9, 5.2e9, 7e9};
  std::vector<double> verts, y;
  for (std::size_t i = 0; i < polys.size(); ++i) {
    verts.push_back(3 * polys[i] + (i == 2 ? 1 : 0));
    y.push_back(1 + 2 * polys[i] + 3 * verts.back());
  }
  const LinearFit fit = fit_least_squares({polys, verts}, y, true, {"polys", "verts"});
  EXPECT_EQ(fit.rank, 3u);
  EXPECT_EQ(fit.method, FitMethod::kBinary128Qr);
  EXPECT_GT(fit.condition_number, 1e9);
  EXPECT_LT(fit.condition_number, 1e12);
  EXPECT_GE(testing::lre(fit.coefficients[0], 1), 13) << fit.coefficients[0];
  EXPECT_GE(testing::lre(fit.coefficients[1], 2), 13) << fit.coefficients[1];
  EXPECT_GE(testing::lre(fit.coefficients[2], 3), 13) << fit.coefficients[2];
  EXPECT_LT(fit.residual_sd, 1e-6);  // y ~ 5e10: zero to 17 digits of y
  // the same design, exactly dependent, is refused naming a column
  std::vector<double> y_exact;
  for (double p : polys) y_exact.push_back(1 + 11 * p);
  std::vector<double> triple;
  for (double p : polys) triple.push_back(3 * p);
  const std::string refused = user_error({polys, triple}, y_exact, true, {"polys", "verts"});
  EXPECT_NE(refused.find("rank 2 for 3 parameters"), std::string::npos) << refused;
  EXPECT_NE(refused.find("above 2^52"), std::string::npos) << refused;
}

TEST(LinearRegression, PolynomialInputIsChecked) {
  const std::vector<double> x{1, 2, 2, 3, 3, 3}, y{1, 2, 3, 4, 5, 6};
  const auto message = [&](const std::vector<double>& xs, int degree, bool intercept) {
    try {
      fit_polynomial(xs, y, degree, intercept, "tris");
    } catch (const util::UserError& e) {
      return std::string(e.what());
    }
    return std::string("(no UserError)");
  };
  // three distinct values determine a quadratic, not a cubic
  EXPECT_EQ(fit_polynomial(x, y, 2, true, "tris").names,
            (std::vector<std::string>{"(intercept)", "tris", "tris^2"}));
  const std::string cubic = message(x, 3, true);
  EXPECT_NE(cubic.find("degree 3 in 'tris' with an intercept needs 4 distinct values of 'tris', "
                       "the data have 3"),
            std::string::npos)
      << cubic;
  // without an intercept a zero x adds nothing
  const std::string origin = message({0, 0, 0, 1, 1, 2}, 3, false);
  EXPECT_NE(origin.find("needs 3 distinct nonzero values of 'tris', the data have 2"),
            std::string::npos)
      << origin;
  EXPECT_NE(message(x, 0, true).find("polynomial degree 0 of 'tris'; it must be 1 or more"),
            std::string::npos);
  EXPECT_NE(message({1, 2, 3}, 1, true).find("has 3 values but y has 6"), std::string::npos);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(message({1, 2, nan, 4, 5, 6}, 1, true).find("predictor 'tris', observation 3 of 6"),
            std::string::npos);
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


// Coefficients beyond the double range: x near 1e300 makes the x^2 coefficient about 1e-601, x
// near 1e-300 makes it about 1e+600. Each is refused with the reason; an inexact fit is never
// reported with standard deviations of 0 ("exact").
TEST(LinearRegression, CoefficientsOutsideTheDoubleRangeAreRefused) {
  const std::vector<double> noise{0.31, -0.42, 0.05, 0.38, -0.27, -0.11, 0.46, -0.35, 0.02, -0.07};
  for (const double magnitude : {1e300, 1e-300}) {
    std::vector<double> x, y;
    for (std::size_t i = 0; i < noise.size(); ++i) {
      x.push_back(magnitude * (1 + 0.1 * double(i)));
      y.push_back(1 + double(i) + noise[i]);
    }
    std::string message = "(no UserError)";
    try {
      const LinearFit fit = fit_polynomial(x, y, 2, true, "x");
      for (double sd : fit.standard_deviations) EXPECT_GT(sd, 0) << magnitude;
    } catch (const util::UserError& e) {
      message = e.what();
    }
    EXPECT_NE(message.find("lies outside the range of double precision"), std::string::npos)
        << magnitude << ": " << message;
    EXPECT_NE(message.find("rescale the predictor"), std::string::npos) << message;
  }
}

// Inside the range, the binary128 path scales its results back exactly: x near 1e150 (x^2 near
// 1e300, its coefficient near 1e-300) gives the fit of x / 1e150 with each coefficient divided by
// 1e150 per power, to binary128's accuracy rounded to doubles.
TEST(LinearRegression, APolynomialInHugeXScalesLikeTheRescaledFit) {
  const std::vector<double> noise{0.31, -0.42, 0.05, 0.38, -0.27, -0.11, 0.46, -0.35, 0.02, -0.07};
  std::vector<double> x, y;
  for (std::size_t i = 0; i < noise.size(); ++i) {
    x.push_back((1 + 0.1 * double(i)) * 1e150);
    y.push_back(1 + double(i) + noise[i]);
  }
  const LinearFit huge = fit_polynomial(x, y, 2, true, "x");
  std::vector<double> back;
  for (double v : x) back.push_back(v / 1e150);
  const LinearFit unit = fit_polynomial(back, y, 2, true, "x");
  ASSERT_EQ(huge.coefficients.size(), 3u);
  EXPECT_NEAR(huge.coefficients[0], unit.coefficients[0], 1e-9 * std::fabs(unit.coefficients[0]));
  EXPECT_NEAR(huge.coefficients[1] * 1e150, unit.coefficients[1],
              1e-9 * std::fabs(unit.coefficients[1]));
  EXPECT_NEAR(huge.coefficients[2] * 1e150 * 1e150, unit.coefficients[2],
              1e-9 * std::fabs(unit.coefficients[2]));
  EXPECT_GT(std::fabs(huge.coefficients[2]), 1e-310);  // a normal double, not rounded to 0
  EXPECT_LT(std::fabs(huge.coefficients[2]), 1e-290);
  EXPECT_NEAR(huge.residual_sd, unit.residual_sd, 1e-12 * unit.residual_sd);
  EXPECT_NEAR(huge.standard_deviations[2] * 1e300, unit.standard_deviations[2],
              1e-9 * unit.standard_deviations[2]);
}

}  // namespace
}  // namespace ra::stats
