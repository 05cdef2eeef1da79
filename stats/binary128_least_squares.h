// Least squares in IEEE binary128 (113-bit significand, ~34 digits) of a design whose columns are
// scaled to unit norm: a triangular factor R (Householder QR, or the Cholesky factor of the
// scaled X'X), the solution, the residuals and R^-1, all in binary128, with the 2-norm condition
// number kappa of the scaled design. The Cholesky factor costs n p^2 / 2 operations against
// Householder's 2 n p^2 and loses log10(kappa^2) digits instead of log10(kappa): at kappa <= 1e6
// at least 20 of the 34 digits remain, so the callers use it there. Used by fit_least_squares() and
// fit_polynomial() (stats/linear_regression.h) when double precision would lose too many digits.
// Boost.Multiprecision's float128 wraps GCC's __float128 (libquadmath); its eigen.hpp lets Eigen's
// HouseholderQR run on it.
#pragma once

#include <Eigen/Dense>
#include <boost/multiprecision/eigen.hpp>
#include <boost/multiprecision/float128.hpp>
#include <optional>
#include <vector>

namespace ra::stats {

using float128 = boost::multiprecision::float128;
using Matrix128 = Eigen::Matrix<float128, Eigen::Dynamic, Eigen::Dynamic>;
using Vector128 = Eigen::Matrix<float128, Eigen::Dynamic, 1>;

enum class Binary128Factor { kHouseholderQr, kCholesky };

struct Binary128Solution {
  Binary128Factor factor = Binary128Factor::kHouseholderQr;  // the one used
  // b, units of y per unit of each column; in binary128, whose range (about 1e+-4932) holds
  // coefficients that a double cannot (the x^2 of x near 1e300 is about 1e-600)
  std::vector<float128> coefficients;
  // sqrt([(X'X)^-1]_jj) per column j (units of 1 / column): the standard deviation of b_j is the
  // residual standard deviation times this
  std::vector<float128> sd_factors;
  float128 rss = 0;             // sum (y - X b)^2 with b unrounded, units of y squared
  double condition_number = 0;  // of the column-scaled design; +infinity when R is singular
};

// x: n x p design (no column of zeros; the caller checks), y: n values, n > p.
Binary128Solution solve_binary128_qr(const Matrix128& x, const Vector128& y);
// The same by the normal equations of the double data; nullopt when their Cholesky factorisation
// fails (kappa far beyond the limit the callers use it to).
std::optional<Binary128Solution> solve_binary128_normal_equations(const Eigen::MatrixXd& x,
                                                                  const Eigen::VectorXd& y);

}  // namespace ra::stats
