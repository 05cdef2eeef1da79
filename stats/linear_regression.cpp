// Least squares by column-scaled, column-pivoted Householder QR; see linear_regression.h.
// Golub and Van Loan, Matrix Computations (4th ed.), 5.4.2 (QR with column pivoting) and 5.3
// (least-squares sensitivity); checked against NIST StRD linear regression (Norris, Pontius).
#include "stats/linear_regression.h"

#include <Eigen/Dense>
#include <algorithm>
#include <boost/math/distributions/students_t.hpp>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "stats/descriptive.h"
#include "util/errors.h"

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
                                        const std::vector<std::string>& names);
}  // namespace

// y is scaled by a power of two first (exact): the residual sum of squares of y near 1e200 would
// be near 1e400; t, p and R^2 are scale-free, coefficients and their standard deviations scale
// with y and are scaled back. (The predictors' columns are scaled to unit norm below.)
LinearFit fit_least_squares(const std::vector<std::vector<double>>& predictors,
                            const std::vector<double>& y, bool intercept,
                            const std::vector<std::string>& names) {
  const int e = scale_exponent(y);
  LinearFit fit = fit_least_squares_of_scaled_y(predictors, scaled(y, e), intercept, names);
  for (double& b : fit.coefficients) b = std::ldexp(b, e);
  for (double& sd : fit.standard_deviations) sd = std::ldexp(sd, e);
  fit.residual_sd = std::ldexp(fit.residual_sd, e);
  fit.rss = std::ldexp(fit.rss, 2 * e);  // inf when it leaves the double range
  return fit;
}

namespace {
LinearFit fit_least_squares_of_scaled_y(const std::vector<std::vector<double>>& predictors,
                                        const std::vector<double>& y, bool intercept,
                                        const std::vector<std::string>& names) {
  // check the input before any arithmetic, so that every message names what is wrong
  const std::size_t k = predictors.size();
  if (!names.empty() && names.size() != k) {
    throw std::invalid_argument("fit_least_squares: " + std::to_string(names.size()) +
                                " names for " + std::to_string(k) + " predictors");
  }
  LinearFit fit;
  fit.intercept = intercept;
  fit.r_squared_centred = intercept;
  if (intercept) fit.names.push_back(kInterceptName);
  for (std::size_t j = 0; j < k; ++j) {
    fit.names.push_back(names.empty() ? "x" + std::to_string(j + 1) : names[j]);
  }
  const std::size_t p = fit.names.size();
  const std::size_t n = y.size();
  if (p == 0) {
    throw UserError("least squares: no parameters to fit (no predictors and no intercept)");
  }
  for (std::size_t j = 0; j < k; ++j) {
    if (predictors[j].size() != n) {
      throw UserError("least squares: predictor '" + fit.names[j + intercept] + "' has " +
                      std::to_string(predictors[j].size()) + " values but y has " +
                      std::to_string(n) + "; each observation needs a value of every column");
    }
  }
  if (n <= p) {
    throw UserError("least squares: " + std::to_string(n) + " observation(s) for " +
                    std::to_string(p) + " parameter(s) (" + quoted_list(fit.names) +
                    "); at least " + std::to_string(p + 1) +
                    " are needed, so that the residual standard deviation is defined");
  }
  const auto require_finite_column = [](const std::vector<double>& v, const std::string& what) {
    for (std::size_t i = 0; i < v.size(); ++i) {
      if (!std::isfinite(v[i])) {
        throw UserError("least squares: " + what + ", observation " + std::to_string(i + 1) +
                        " of " + std::to_string(v.size()) + ", is " + std::to_string(v[i]) +
                        "; only finite numbers can be fitted");
      }
    }
  };
  require_finite_column(y, "the response y");
  for (std::size_t j = 0; j < k; ++j) {
    require_finite_column(predictors[j], "predictor '" + fit.names[j + intercept] + "'");
  }

  // design matrix, each column scaled to unit norm: pivots become comparable across columns of
  // very different magnitudes (Pontius: 1, x ~ 1e6, x^2 ~ 1e12), so the rank test is meaningful
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
      throw UserError("least squares: predictor '" + fit.names[j] +
                      "' is 0 in every observation; its coefficient cannot be determined");
    }
  }
  const Eigen::MatrixXd xs = x * scale.cwiseInverse().asDiagonal();
  const Eigen::Map<const Eigen::VectorXd> yv(y.data(), static_cast<Eigen::Index>(n));

  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(xs.rows(), xs.cols());
  qr.setThreshold(kRankTolerance);
  qr.compute(xs);
  fit.rank = static_cast<std::size_t>(qr.rank());
  if (fit.rank < p) {
    // pivoting moves the columns that depend on the others to the end
    std::vector<std::string> dependent, others;
    for (std::size_t pos = 0; pos < p; ++pos) {
      const auto j = static_cast<std::size_t>(qr.colsPermutation().indices()(pos));
      (pos < fit.rank ? others : dependent).push_back(fit.names[j]);
    }
    char tolerance[32];
    std::snprintf(tolerance, sizeof tolerance, "%g", kRankTolerance);
    throw UserError("least squares: the design has rank " + std::to_string(fit.rank) + " for " +
                    std::to_string(p) + " parameters: " + quoted_list(dependent) +
                    (dependent.size() == 1 ? " is" : " are") + " (to within a relative " +
                    tolerance + ") a linear combination of " + quoted_list(others) +
                    ", so the coefficients are not determined; drop a column (typical causes: a "
                    "constant predictor beside the intercept, two proportional columns such as "
                    "#vertices = 3 #polygons)");
  }

  // solve in scaled coordinates, then one step of iterative refinement on the residual
  Eigen::VectorXd bs = qr.solve(yv);
  Eigen::VectorXd b = bs.cwiseQuotient(scale);
  b += qr.solve(residuals(x, yv, b)).cwiseQuotient(scale);

  const Eigen::VectorXd r = residuals(x, yv, b);
  fit.n = n;
  fit.df = n - p;
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
  const Eigen::MatrixXd r_factor = qr.matrixR().topLeftCorner(p, p).triangularView<Eigen::Upper>();
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
}  // namespace

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
