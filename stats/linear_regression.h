// Ordinary least squares y = b0 + b1 x1 + ... + bk xk + e: coefficients (units of y per unit of
// their predictor), their standard deviations, the residual standard deviation (units of y) and
// R-squared. Used to fit rendering-time models (Wimmer and Wonka's heuristics H1..H4: frame time as
// a linear function of #polygons, #vertices, #pixels); checked against every NIST StRD linear
// regression set (Norris, Pontius, NoInt1, NoInt2, Filip, Longley, Wampler1-5).
//
// Method: the design matrix (a column of ones first when there is an intercept) is scaled to unit
// column norms and factored by Householder QR with column pivoting in double precision (Eigen's
// ColPivHouseholderQR). Its 2-norm condition number kappa (from the singular values of R) picks the
// precision of the solution:
// - kappa <= kDoubleConditionLimit: the double factor is used, with one step of iterative
//   refinement on a long-double residual. Every digit it loses is a factor of kappa (and kappa^2
//   times the relative residual): at kappa <= 100 at least 13 digits remain on the StRD sets.
// - above: the problem is solved again in IEEE binary128 (113-bit significand, ~34 digits;
//   Boost.Multiprecision float128 over GCC's libquadmath): the solution, its residuals and R^-1
//   all in binary128, the triangular factor R from the Cholesky factor of the scaled X'X up to
//   kNormalEquationsLimit (they lose 2 log10(kappa) <= 12 of the 34 digits and cost a quarter of
//   a QR: the timing study's H3 refits many ill-conditioned subsets), from Householder QR beyond.
//   Double QR with refinement would not do: past kappa ~ 1e3 its R keeps too few digits for the
//   standard deviations, and the kappa^2 term of large residuals defeats refinement (Wampler4/5:
//   7.9 and 5.9 digits).
// Polynomial designs (fit_polynomial) form the powers x^k of the double x in binary128 and always
// take the binary128 Householder path: a design of powers rounded to doubles has lost digits
// before any solver sees it (NIST Filip, kappa 5e9: its rounded powers determine 7.6 digits, its
// exact powers 14).
//
// Rank: a column is dropped by nobody. The fit is refused (UserError naming the columns) only when
// the data do not determine its coefficients: kappa of the scaled design (from the binary128 factor
// when double cannot tell) above kMaxCondition = 2^52, where rounding each datum in its last bit
// could change the solution by 100 %. Exact dependence (#vertices = 3 #polygons, a constant beside
// the intercept) gives kappa ~ 1e30 and more in binary128.
//
// Conventions:
// - R-squared is 1 - RSS / TSS. With an intercept TSS is centred, sum (y - mean y)^2; without one
//   it is uncentred, sum y^2, as NIST StRD certifies it for its no-intercept models (NoInt1,
//   NoInt2) and as R's summary.lm reports it. `r_squared_centred` says which.
// - Bad input throws ra::util::UserError naming what is wrong: fewer observations than parameters plus
//   one, predictors of another length than y, a NaN or infinite value (which column, which
//   observation), a design whose coefficients the data do not determine (which columns).
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace ra::stats {

// Condition numbers (2-norm, column-scaled design, dimensionless) that choose the method.
constexpr double kDoubleConditionLimit = 100;  // up to here: double QR and refinement
constexpr double kNormalEquationsLimit = 1e6;  // up to here: binary128 normal equations
constexpr double kMaxCondition = 4503599627370496.0;  // 2^52: beyond, the fit is refused

enum class FitMethod {
  kDoubleQr,  // Householder QR in double, one refinement step (long-double residuals)
  kBinary128NormalEquations,  // Cholesky of the scaled X'X; solution, residuals, R^-1 in binary128
  kBinary128Qr,               // Householder QR; solution, residuals and R^-1 in binary128
};
// "householder_qr_double", "normal_equations_binary128" or "householder_qr_binary128"
const char* fit_method_name(FitMethod m);

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
  // 2-norm condition number of the design with its columns scaled to unit norm (dimensionless):
  // about 10^d means d of the data's 16 digits are lost to any solution of the double data
  double condition_number = 1;
  FitMethod method = FitMethod::kDoubleQr;
};

// Least-squares fit of y on the predictor columns.
// - predictors: one vector per predictor, each with y.size() values (observation i at index i);
//   may be empty when `intercept` is true (the fit is then the mean of y).
// - y: the response.
// - intercept: whether to fit b0 (a column of ones).
// - names: one per predictor, for results and messages; empty means "x1", "x2", ...
// Throws ra::util::UserError on the bad input listed above.
LinearFit fit_least_squares(const std::vector<std::vector<double>>& predictors,
                            const std::vector<double>& y, bool intercept,
                            const std::vector<std::string>& names = {});

// Least-squares fit of a polynomial in x of the given degree: y = b0 + b1 x + ... + bd x^d (b0
// only with `intercept`). The powers of the double x are formed in binary128, not rounded to
// doubles, and the fit is always solved in binary128 (see above). Parameters are named
// "(intercept)", x_name, x_name^2, ... Throws ra::util::UserError on the bad input listed above, and
// when x has fewer distinct values (nonzero ones without an intercept) than the degree needs: the
// design of powers then has exactly dependent columns.
LinearFit fit_polynomial(const std::vector<double>& x, const std::vector<double>& y, int degree,
                         bool intercept, const std::string& x_name = "x");

// t test of H0: coefficient j = 0 with the fit's residual degrees of freedom.
struct CoefficientTest {
  double t = 0;        // coefficient / its standard deviation (dimensionless)
  double p_value = 1;  // two-sided, P(|T| >= |t|), Student's t with fit.df degrees of freedom
};

// Throws std::invalid_argument when the coefficient's standard deviation is 0 (an exact fit): t is
// then undefined. std::out_of_range when j is not a parameter of the fit.
CoefficientTest coefficient_t_test(const LinearFit& fit, std::size_t j);

}  // namespace ra::stats
