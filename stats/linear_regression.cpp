// Least squares by column-scaled Householder QR in double or binary128; see linear_regression.h.
// Golub and Van Loan, Matrix Computations (4th ed.), 5.4.2 (QR with column pivoting) and 5.3
// (least-squares sensitivity); checked against every NIST StRD linear regression set.
// Eigen's triangular matrix-vector kernel trips GCC's -Wmaybe-uninitialized on a temporary it
// assigns before use.
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include "stats/linear_regression.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cfloat>
#include <boost/math/distributions/students_t.hpp>
#include <cmath>
#include <cstdio>
#include <set>
#include <stdexcept>

#include "stats/binary128_least_squares.h"
#include "stats/descriptive.h"
#include "util/errors.h"
#include "util/number_text.h"

namespace ra::stats {
namespace {

const char* const kInterceptName = "(intercept)";

std::string quoted_list(const std::vector<std::string>& names) {
  std::string s;
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (i > 0) s += ", ";
    s += "'" + names[i] + "'";
  }
  return s;
}

// y - X b, accumulated in long double: the residuals of a good fit are much smaller than y, and
// their sum of squares is what the residual SD and R-squared are made of.
Eigen::VectorXd residuals(const Eigen::MatrixXd& x, const Eigen::VectorXd& y,
                          const Eigen::VectorXd& b) {
  Eigen::VectorXd r(y.size());
  for (Eigen::Index i = 0; i < x.rows(); ++i) {
    long double s = y(i);
    for (Eigen::Index j = 0; j < x.cols(); ++j) {
      s -= static_cast<long double>(x(i, j)) * b(j);
    }
    r(i) = static_cast<double>(s);
  }
  return r;
}

long double sum_of_squares(const Eigen::VectorXd& v) {
  long double s = 0;
  for (Eigen::Index i = 0; i < v.size(); ++i) s += static_cast<long double>(v(i)) * v(i);
  return s;
}

}  // namespace

namespace {
LinearFit fit_least_squares_of_scaled_y(const std::vector<std::vector<double>>& predictors,
                                        const std::vector<double>& y, bool intercept,
                                        const std::vector<std::string>& names, int y_exponent);
LinearFit fit_polynomial_of_scaled_y(const std::vector<double>& x, const std::vector<double>& y,
                                     int degree, bool intercept, const std::string& x_name,
                                     int y_exponent);

// Every coefficient and standard deviation a double can hold, or a refusal naming the first that
// it cannot: past about 1.8e308 a double is infinite, below 2.2e-308 it loses digits and then
// becomes 0 (a standard deviation of 0 would call an inexact fit exact).
void require_double_range(const LinearFit& fit) {
  for (std::size_t j = 0; j < fit.coefficients.size(); ++j) {
    const double b = fit.coefficients[j], sd = fit.standard_deviations[j];
    const bool sd_lost = !std::isfinite(sd) || (sd < DBL_MIN && fit.rss > 0);
    if (std::isfinite(b) && !sd_lost) continue;
    throw util::UserError("least squares: the coefficient of '" + fit.names[j] + "' or its "
                          "standard deviation lies outside the range of double precision "
                          "(2.2e-308 to 1.8e308 in magnitude), so it cannot be reported; rescale "
                          "the predictor (divide it by a power of ten near its magnitude) and fit "
                          "again");
  }
}

// y is scaled by a power of two first (exact): the residual sum of squares of y near 1e200 would
// be near 1e400; t, p and R^2 are scale-free, coefficients and their standard deviations scale
// with y and are scaled back: in binary128 by the binary128 paths (finish_binary128), here for the
// double one. (The predictors' columns are scaled to unit norm below.)
template <typename Fit>
LinearFit with_scaled_y(const std::vector<double>& y, Fit fit_scaled) {
  const int e = scale_exponent(y);
  LinearFit fit = fit_scaled(scaled(y, e), e);
  if (fit.method == FitMethod::kDoubleQr) {
    for (double& b : fit.coefficients) b = std::ldexp(b, e);
    for (double& sd : fit.standard_deviations) sd = std::ldexp(sd, e);
    fit.residual_sd = std::ldexp(fit.residual_sd, e);
    fit.rss = std::ldexp(fit.rss, 2 * e);  // inf when it leaves the double range
  }
  require_double_range(fit);
  return fit;
}
}  // namespace

LinearFit fit_least_squares(const std::vector<std::vector<double>>& predictors,
                            const std::vector<double>& y, bool intercept,
                            const std::vector<std::string>& names) {
  return with_scaled_y(y, [&](const std::vector<double>& ys, int e) {
    return fit_least_squares_of_scaled_y(predictors, ys, intercept, names, e);
  });
}

LinearFit fit_polynomial(const std::vector<double>& x, const std::vector<double>& y, int degree,
                         bool intercept, const std::string& x_name) {
  return with_scaled_y(y, [&](const std::vector<double>& ys, int e) {
    return fit_polynomial_of_scaled_y(x, ys, degree, intercept, x_name, e);
  });
}

namespace {

// The parameters' names and the checks every fit makes before any arithmetic, so that every
// message names what is wrong. `columns` are the predictors' names, in order.
LinearFit checked_start(const std::vector<std::string>& columns, const std::vector<double>& y,
                        bool intercept) {
  LinearFit fit;
  fit.intercept = intercept;
  fit.r_squared_centred = intercept;
  if (intercept) fit.names.push_back(kInterceptName);
  fit.names.insert(fit.names.end(), columns.begin(), columns.end());
  const std::size_t p = fit.names.size();
  const std::size_t n = y.size();
  if (p == 0) {
    throw util::UserError("least squares: no parameters to fit (no predictors and no intercept)");
  }
  if (n <= p) {
    throw util::UserError("least squares: " + std::to_string(n) + " observation(s) for " +
                          std::to_string(p) + " parameter(s) (" + quoted_list(fit.names) +
                          "); at least " + std::to_string(p + 1) +
                          " are needed, so that the residual standard deviation is defined");
  }
  fit.n = n;
  fit.df = n - p;
  fit.rank = p;
  return fit;
}

void require_finite_column(const std::vector<double>& v, const std::string& what) {
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (!std::isfinite(v[i])) {
      throw util::UserError("least squares: " + what + ", observation " + std::to_string(i + 1) +
                            " of " + std::to_string(v.size()) + ", is " + std::to_string(v[i]) +
                            "; only finite numbers can be fitted");
    }
  }
}

std::string condition_text(double kappa) {
  if (std::isinf(kappa)) return "infinite (a zero pivot)";
  return util::significant(kappa, 3);
}

// The refusal of a design whose coefficients the data do not determine. `dependent` are the
// columns last in the pivoted order (those pivoting found nearly dependent on the others).
[[noreturn]] void refuse_undetermined(const LinearFit& fit,
                                      const std::vector<std::string>& dependent,
                                      const std::vector<std::string>& others, double kappa) {
  const std::size_t p = fit.names.size();
  throw util::UserError(
      "least squares: the design has rank " + std::to_string(p - dependent.size()) + " for " +
      std::to_string(p) + " parameters: " + quoted_list(dependent) +
      (dependent.size() == 1 ? " is" : " are") + " a linear combination of " + quoted_list(others) +
      " to within the data's own rounding (condition number of the "
      "column-scaled design " +
      condition_text(kappa) +
      ", above 2^52 = 4.5e15), so the "
      "coefficients are not determined; drop a column (typical causes: a constant predictor "
      "beside the intercept, two proportional columns such as #vertices = 3 #polygons)");
}

// Residual SD, RSS, R^2, coefficients and standard deviations of a binary128 solution of y scaled
// by 2^-y_exponent, scaled back in binary128 before they are rounded to doubles (a coefficient
// beyond the double range then shows as 0 or infinity: require_double_range refuses it). `tss`
// as in the header.
void finish_binary128(LinearFit& fit, const Binary128Solution& s, const float128& tss,
                      int y_exponent) {
  const float128 y_scale = ldexp(float128(1), y_exponent);  // exact
  const float128 s2 = s.rss / static_cast<double>(fit.df);
  fit.rss = static_cast<double>(s.rss * y_scale * y_scale);  // inf past the double range
  fit.residual_sd = static_cast<double>(sqrt(s2) * y_scale);
  if (tss > 0) fit.r_squared = static_cast<double>(1 - s.rss / tss);
  fit.coefficients.resize(s.coefficients.size());
  fit.standard_deviations.resize(s.sd_factors.size());
  for (std::size_t j = 0; j < s.sd_factors.size(); ++j) {
    fit.coefficients[j] = static_cast<double>(s.coefficients[j] * y_scale);
    fit.standard_deviations[j] = static_cast<double>(sqrt(s2) * s.sd_factors[j] * y_scale);
  }
  fit.condition_number = s.condition_number;
  fit.method = s.factor == Binary128Factor::kCholesky ? FitMethod::kBinary128NormalEquations
                                                      : FitMethod::kBinary128Qr;
}

// Total sum of squares in binary128: about the mean with an intercept, about 0 without.
float128 total_sum_of_squares(const Vector128& y, bool centred) {
  const float128 m = centred ? float128(y.sum() / static_cast<double>(y.size())) : float128(0);
  float128 tss = 0;
  for (Eigen::Index i = 0; i < y.size(); ++i) tss += (y(i) - m) * (y(i) - m);
  return tss;
}

// The largest singular value of R over its smallest: the 2-norm condition number of the scaled
// design (double: trustworthy up to ~1e14; beyond, binary128 decides).
double condition_of(const Eigen::MatrixXd& r_factor) {
  const Eigen::VectorXd sv = Eigen::JacobiSVD<Eigen::MatrixXd>(r_factor).singularValues();
  const double smallest = sv(sv.size() - 1);
  return smallest > 0 ? sv(0) / smallest : std::numeric_limits<double>::infinity();
}

LinearFit fit_least_squares_of_scaled_y(const std::vector<std::vector<double>>& predictors,
                                        const std::vector<double>& y, bool intercept,
                                        const std::vector<std::string>& names, int y_exponent) {
  const std::size_t k = predictors.size();
  if (!names.empty() && names.size() != k) {
    throw std::invalid_argument("fit_least_squares: " + std::to_string(names.size()) +
                                " names for " + std::to_string(k) + " predictors");
  }
  std::vector<std::string> columns;
  for (std::size_t j = 0; j < k; ++j) {
    columns.push_back(names.empty() ? "x" + std::to_string(j + 1) : names[j]);
  }
  const std::size_t n = y.size();
  for (std::size_t j = 0; j < k; ++j) {
    if (predictors[j].size() != n) {
      throw util::UserError("least squares: predictor '" + columns[j] + "' has " +
                            std::to_string(predictors[j].size()) + " values but y has " +
                            std::to_string(n) + "; each observation needs a value of every column");
    }
  }
  LinearFit fit = checked_start(columns, y, intercept);
  const std::size_t p = fit.names.size();
  require_finite_column(y, "the response y");
  for (std::size_t j = 0; j < k; ++j) {
    require_finite_column(predictors[j], "predictor '" + columns[j] + "'");
  }

  // design matrix, each column scaled to unit norm: pivots become comparable across columns of
  // very different magnitudes (Pontius: 1, x ~ 1e6, x^2 ~ 1e12), and kappa measures dependence
  Eigen::MatrixXd x(n, p);
  if (intercept) x.col(0).setOnes();
  for (std::size_t j = 0; j < k; ++j) {
    x.col(static_cast<Eigen::Index>(j + intercept)) =
        Eigen::Map<const Eigen::VectorXd>(predictors[j].data(), static_cast<Eigen::Index>(n));
  }
  Eigen::VectorXd scale(p);
  for (std::size_t j = 0; j < p; ++j) {
    scale(j) = x.col(j).stableNorm();
    if (scale(j) == 0) {
      throw util::UserError("least squares: predictor '" + fit.names[j] +
                            "' is 0 in every observation; its coefficient cannot be determined");
    }
  }
  const Eigen::MatrixXd xs = x * scale.cwiseInverse().asDiagonal();
  const Eigen::Map<const Eigen::VectorXd> yv(y.data(), static_cast<Eigen::Index>(n));

  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(xs);
  const Eigen::MatrixXd r_factor = qr.matrixR().topLeftCorner(p, p).triangularView<Eigen::Upper>();
  fit.condition_number = condition_of(r_factor);
  if (fit.condition_number > kDoubleConditionLimit) {
    std::optional<Binary128Solution> normal;
    if (fit.condition_number <= kNormalEquationsLimit) {
      normal = solve_binary128_normal_equations(x, Eigen::VectorXd(yv));
    }
    const Binary128Solution s =
        normal ? *normal : solve_binary128_qr(x.cast<float128>(), yv.cast<float128>());
    if (!(s.condition_number <= kMaxCondition)) {
      // pivoting moves the columns that depend on the others to the end
      const double largest = std::abs(r_factor(0, 0));
      std::size_t m = 0;
      for (std::size_t pos = 0; pos < p; ++pos) m += std::abs(r_factor(pos, pos)) < 1e-8 * largest;
      m = std::max<std::size_t>(m, 1);
      std::vector<std::string> dependent, others;
      for (std::size_t pos = 0; pos < p; ++pos) {
        const auto j = static_cast<std::size_t>(qr.colsPermutation().indices()(pos));
        (pos + m >= p ? dependent : others).push_back(fit.names[j]);
      }
      refuse_undetermined(fit, dependent, others, s.condition_number);
    }
    finish_binary128(fit, s, total_sum_of_squares(yv.cast<float128>(), intercept), y_exponent);
    return fit;
  }

  // double precision: solve in scaled coordinates, then one step of iterative refinement on
  // the residual
  Eigen::VectorXd bs = qr.solve(yv);
  Eigen::VectorXd b = bs.cwiseQuotient(scale);
  b += qr.solve(residuals(x, yv, b)).cwiseQuotient(scale);

  const Eigen::VectorXd r = residuals(x, yv, b);
  fit.rss = static_cast<double>(sum_of_squares(r));
  fit.residual_sd = std::sqrt(fit.rss / static_cast<double>(fit.df));

  long double tss = 0;
  if (intercept) {
    const double m = mean(y);
    for (double v : y) tss += static_cast<long double>(v - m) * (v - m);
  } else {
    for (double v : y) tss += static_cast<long double>(v) * v;
  }
  if (tss > 0) fit.r_squared = static_cast<double>(1 - sum_of_squares(r) / tss);

  // var(b_j) = s^2 [(X'X)^-1]_jj; with Xs = X D^-1 = Q R P', (X'X)^-1 = D^-1 P R^-1 R^-T P' D^-1,
  // so the diagonal is the squared norm of a row of R^-1 over the squared column scale
  const Eigen::MatrixXd r_inverse =
      r_factor.triangularView<Eigen::Upper>().solve(Eigen::MatrixXd::Identity(p, p));
  fit.coefficients.assign(b.data(), b.data() + p);
  fit.standard_deviations.assign(p, 0);
  for (std::size_t pos = 0; pos < p; ++pos) {
    const auto j = static_cast<std::size_t>(qr.colsPermutation().indices()(pos));
    fit.standard_deviations[j] = fit.residual_sd * r_inverse.row(pos).norm() / scale(j);
  }
  return fit;
}

LinearFit fit_polynomial_of_scaled_y(const std::vector<double>& x, const std::vector<double>& y,
                                     int degree, bool intercept, const std::string& x_name,
                                     int y_exponent) {
  if (degree < 1) {
    throw util::UserError("least squares: polynomial degree " + std::to_string(degree) + " of '" +
                          x_name + "'; it must be 1 or more");
  }
  if (x.size() != y.size()) {
    throw util::UserError("least squares: predictor '" + x_name + "' has " +
                          std::to_string(x.size()) + " values but y has " +
                          std::to_string(y.size()) +
                          "; each observation needs a value of every column");
  }
  std::vector<std::string> columns{x_name};
  for (int d = 2; d <= degree; ++d) columns.push_back(x_name + "^" + std::to_string(d));
  LinearFit fit = checked_start(columns, y, intercept);
  require_finite_column(y, "the response y");
  require_finite_column(x, "predictor '" + x_name + "'");
  // a Vandermonde design has full rank exactly when x has as many distinct values as it has
  // columns (nonzero ones without the column of ones): a test on the data, not on rounding
  std::set<double> distinct;
  for (double v : x) {
    if (intercept || v != 0) distinct.insert(v);
  }
  if (distinct.size() < static_cast<std::size_t>(degree) + intercept) {
    throw util::UserError("least squares: a polynomial of degree " + std::to_string(degree) +
                          " in '" + x_name + "'" + (intercept ? " with" : " without") +
                          " an intercept needs " + std::to_string(degree + intercept) +
                          " distinct " + (intercept ? "" : "nonzero ") + "values of '" + x_name +
                          "', the data have " + std::to_string(distinct.size()) +
                          "; the coefficients are not determined");
  }
  const auto n = static_cast<Eigen::Index>(y.size());
  const auto p = static_cast<Eigen::Index>(fit.names.size());
  Matrix128 design(n, p);
  Vector128 y128(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    y128(i) = y[static_cast<std::size_t>(i)];
    const float128 xi = x[static_cast<std::size_t>(i)];
    float128 power = intercept ? float128(1) : xi;
    for (Eigen::Index j = 0; j < p; ++j, power *= xi) design(i, j) = power;
  }
  const Binary128Solution s = solve_binary128_qr(design, y128);
  if (!(s.condition_number <= kMaxCondition)) {
    refuse_undetermined(fit, {fit.names.back()},
                        std::vector<std::string>(fit.names.begin(), fit.names.end() - 1),
                        s.condition_number);
  }
  finish_binary128(fit, s, total_sum_of_squares(y128, intercept), y_exponent);
  return fit;
}

}  // namespace

const char* fit_method_name(FitMethod m) {
  switch (m) {
    case FitMethod::kDoubleQr: return "householder_qr_double";
    case FitMethod::kBinary128NormalEquations: return "normal_equations_binary128";
    case FitMethod::kBinary128Qr: return "householder_qr_binary128";
  }
  return "?";
}

CoefficientTest coefficient_t_test(const LinearFit& fit, std::size_t j) {
  const double sd = fit.standard_deviations.at(j);
  if (sd == 0) {
    throw std::invalid_argument("t test of '" + fit.names.at(j) +
                                "': its standard deviation is 0 (the fit is exact)");
  }
  CoefficientTest t;
  t.t = fit.coefficients.at(j) / sd;
  const boost::math::students_t dist(static_cast<double>(fit.df));
  t.p_value = std::min(1.0, 2 * boost::math::cdf(boost::math::complement(dist, std::fabs(t.t))));
  return t;
}

}  // namespace ra::stats
