// Ordinary least squares y = b0 + b1 x1 + ... + bk xk + e: coefficients (units of y per unit of
// their predictor), their standard deviations, the residual standard deviation (units of y) and
// R-squared. Used to fit rendering-time models (Wimmer and Wonka's heuristics H1..H4: frame time as
// a linear function of #polygons, #vertices, #pixels); checked against NIST StRD Norris and
// Pontius.
//
// Method: the design matrix (a column of ones first when there is an intercept) is scaled to unit
// column norms and factored by Householder QR with column pivoting (Eigen's ColPivHouseholderQR);
// one step of iterative refinement on the residual follows (on StRD Norris and Pontius it raises
// the worst coefficient from 12.5 to 13.5 correct digits). The normal equations X'X b = X'y are
// never formed: they square the condition number (on Pontius, with x up to 3e6 and x^2 up to 9e12,
// NumPy's normal-equations solution keeps 11.2 digits of B0; on NIST's harder sets, none).
// Standard deviations come from R^-1 (the diagonal of (X'X)^-1 = P R^-1 R^-T P', scaled back), not
// from inverting X'X.
//
// Conventions:
// - R-squared is 1 - RSS / TSS. With an intercept TSS is centred, sum (y - mean y)^2; without one
//   it is uncentred, sum y^2, as NIST StRD certifies it for its no-intercept models (NoInt1,
//   NoInt2) and as R's summary.lm reports it. `r_squared_centred` says which.
// - Bad input throws ra::UserError naming what is wrong: fewer observations than parameters plus
//   one, predictors of another length than y, a NaN or infinite value (which column, which
//   observation), a rank-deficient design (which columns depend on the others).
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace ra::stats {

// Columns whose pivot in the scaled QR factor is below this fraction of the largest pivot are
// taken as linear combinations of the others, and the fit is refused. Same tolerance as R's lm()
// (LINPACK dqrdc2, tol = 1e-7): past a condition number of about 1e7 a double-precision solution
// may have no correct digit when the residuals are not small.
constexpr double kRankTolerance = 1e-7;

// Result of fit_least_squares(). Parameter j is the intercept (j = 0) when there is one, then the
// predictors in the order given.
struct LinearFit {
  std::vector<std::string> names;    // of the parameters: "(intercept)", then the predictors
  std::vector<double> coefficients;  // units of y per unit of the predictor (of y: intercept)
  std::vector<double> standard_deviations;  // of each coefficient (standard errors), same units
  double residual_sd = 0;                   // sqrt(rss / df), units of y
  double rss = 0;                           // residual sum of squares, units of y squared
  // 1 - rss / tss (dimensionless, <= 1; centred or uncentred, see above). nullopt when tss = 0
  // (y constant with an intercept, or y all zero without one): R-squared is then undefined.
  std::optional<double> r_squared;
  bool r_squared_centred = true;  // true with an intercept (centred TSS), false without
  bool intercept = true;
  std::size_t n = 0;     // observations
  std::size_t rank = 0;  // numerical rank of the design; always the number of parameters
  std::size_t df = 0;    // residual degrees of freedom, n - number of parameters
};

// Least-squares fit of y on the predictor columns.
// - predictors: one vector per predictor, each with y.size() values (observation i at index i);
//   may be empty when `intercept` is true (the fit is then the mean of y).
// - y: the response.
// - intercept: whether to fit b0 (a column of ones).
// - names: one per predictor, for results and messages; empty means "x1", "x2", ...
// Throws ra::UserError on the bad input listed above.
LinearFit fit_least_squares(const std::vector<std::vector<double>>& predictors,
                            const std::vector<double>& y, bool intercept,
                            const std::vector<std::string>& names = {});

// t test of H0: coefficient j = 0 with the fit's residual degrees of freedom.
struct CoefficientTest {
  double t = 0;        // coefficient / its standard deviation (dimensionless)
  double p_value = 1;  // two-sided, P(|T| >= |t|), Student's t with fit.df degrees of freedom
};

// Throws std::invalid_argument when the coefficient's standard deviation is 0 (an exact fit): t is
// then undefined. std::out_of_range when j is not a parameter of the fit.
CoefficientTest coefficient_t_test(const LinearFit& fit, std::size_t j);

}  // namespace ra::stats
