// Least squares in binary128; see binary128_least_squares.h. Golub and Van Loan, Matrix
// Computations (4th ed.), 5.3.2-5.3.3 (normal equations and QR for least squares), 5.3.8
// (sensitivity).
// Eigen's triangular matrix-vector kernel, instantiated on float128, trips GCC's
// -Wmaybe-uninitialized on a temporary it assigns before use.
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include "stats/binary128_least_squares.h"

#include <cmath>
#include <limits>

namespace ra::stats {

namespace {

// Largest singular value of a small square matrix, computed in double from its binary128 entries:
// double keeps the singular values to ~16 digits relative to the largest, and the condition
// number needs only the largest of R and of R^-1.
double largest_singular_value(const Matrix128& m) {
  const Eigen::MatrixXd d = m.unaryExpr([](const float128& v) { return static_cast<double>(v); });
  return Eigen::JacobiSVD<Eigen::MatrixXd>(d).singularValues()(0);
}

// Everything after the factor: R (R'R = Xs'Xs for the column-scaled Xs = X D^-1), the scaled
// solution bs and the scales D give b, the condition number, the residual sum of squares and the
// standard-deviation factors. X is read entry by entry (double or binary128).
template <typename Design, typename Response>
Binary128Solution finish(const Design& x, const Response& y, const Matrix128& r,
                         const Vector128& bs, const Vector128& scale) {
  const Eigen::Index p = r.cols();
  Binary128Solution s;
  bool singular = false;
  for (Eigen::Index j = 0; j < p; ++j) singular = singular || r(j, j) == 0;
  if (singular) {
    s.condition_number = std::numeric_limits<double>::infinity();
    return s;
  }
  const Matrix128 r_inverse = r.triangularView<Eigen::Upper>().solve(Matrix128::Identity(p, p));
  s.condition_number = largest_singular_value(r) * largest_singular_value(r_inverse);
  const Vector128 b = bs.cwiseQuotient(scale);
  for (Eigen::Index i = 0; i < x.rows(); ++i) {
    float128 residual = y(i);
    for (Eigen::Index j = 0; j < p; ++j) residual -= float128(x(i, j)) * b(j);
    s.rss += residual * residual;
  }
  s.coefficients.resize(static_cast<std::size_t>(p));
  s.sd_factors.resize(static_cast<std::size_t>(p));
  // (X'X)^-1 = D^-1 R^-1 R^-T D^-1: row norms of R^-1 over the scales
  for (Eigen::Index j = 0; j < p; ++j) {
    s.coefficients[static_cast<std::size_t>(j)] = b(j);
    s.sd_factors[static_cast<std::size_t>(j)] = sqrt(r_inverse.row(j).squaredNorm()) / scale(j);
  }
  return s;
}

}  // namespace

Binary128Solution solve_binary128_qr(const Matrix128& x, const Vector128& y) {
  const Eigen::Index p = x.cols();
  // unit column norms: the condition number then measures dependence, not units
  Vector128 scale(p);
  for (Eigen::Index j = 0; j < p; ++j) scale(j) = sqrt(x.col(j).squaredNorm());
  const Matrix128 xs = x * scale.cwiseInverse().asDiagonal();
  const Eigen::HouseholderQR<Matrix128> qr(xs);
  const Matrix128 r = qr.matrixQR().topLeftCorner(p, p).triangularView<Eigen::Upper>();
  Binary128Solution s = finish(x, y, r, qr.solve(y), scale);
  s.factor = Binary128Factor::kHouseholderQr;
  return s;
}

std::optional<Binary128Solution> solve_binary128_normal_equations(const Eigen::MatrixXd& x,
                                                                  const Eigen::VectorXd& y) {
  const Eigen::Index n = x.rows(), p = x.cols();
  // X'X and X'y in one pass; a product of two doubles is exact in binary128
  Matrix128 gram = Matrix128::Zero(p, p);
  Vector128 xty = Vector128::Zero(p);
  for (Eigen::Index i = 0; i < n; ++i) {
    for (Eigen::Index j = 0; j < p; ++j) {
      const float128 xij = x(i, j);
      xty(j) += xij * y(i);
      for (Eigen::Index k = 0; k <= j; ++k) gram(j, k) += xij * x(i, k);
    }
  }
  Vector128 scale(p);
  for (Eigen::Index j = 0; j < p; ++j) scale(j) = sqrt(gram(j, j));
  for (Eigen::Index j = 0; j < p; ++j) {
    xty(j) /= scale(j);
    for (Eigen::Index k = 0; k <= j; ++k) {
      gram(j, k) /= scale(j) * scale(k);
      gram(k, j) = gram(j, k);
    }
  }
  const Eigen::LLT<Matrix128> llt(gram);
  if (llt.info() != Eigen::Success) return std::nullopt;
  const Matrix128 r = llt.matrixU();
  Binary128Solution s = finish(x, y, r, llt.solve(xty), scale);
  s.factor = Binary128Factor::kCholesky;
  return s;
}

}  // namespace ra::stats
