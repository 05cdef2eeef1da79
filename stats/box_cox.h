// Box-Cox power transformation and two estimators of its parameter lambda.
// NIST/SEMATECH e-Handbook of Statistical Methods: 1.3.3.6 (Box-Cox normality plot), 1.3.3.21
// (normal probability plot), 1.3.3.23 and Filliben (1975) (probability plot correlation
// coefficient). The audit paper (section 4) applies its t, F and Levene tests to Box-Cox
// transformed data too.
//
//   T(y; lambda) = (y^lambda - 1) / lambda   (lambda != 0),   log(y)   (lambda = 0),   y > 0.
//
// Two estimators, which give different lambdas on the same data:
// - PPCC (the e-Handbook's Box-Cox normality plot, Dataplot's BOX-COX NORMALITY PLOT): lambda that
//   maximises the correlation between the sorted T(y; lambda) and the normal order statistic
//   medians (Filliben). SciPy: scipy.stats.boxcox_normmax(x, method='pearsonr').
// - MLE (Box and Cox 1964; R's MASS::boxcox, scipy.stats.boxcox): lambda that maximises the profile
//   log-likelihood  L(lambda) = (lambda - 1) sum log y - n/2 log(var_n(T(y; lambda))), var_n with
//   denominator n. SciPy: scipy.stats.boxcox_llf and boxcox_normmax(x, method='mle').
//
// Both are searched on a grid over [lambda_min, lambda_max] (default [-2, 2], the e-Handbook's
// range) and refined by Brent's method inside the best grid cell.
//
// Numerics: both objectives are invariant to rescaling y by a constant c (the correlation exactly;
// the log-likelihood up to the constant -n log c). They are evaluated on y / c with c the median,
// as expm1(lambda * log1p((y - c) / c)) / lambda: y - c is exact for data near c, so data like 1e9
// + small noise keep their information at every lambda, and lambda near 0 needs no special case.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace ra::stats {

// Box-Cox transform of one value y > 0 (units: those of y^lambda / lambda). Continuous in lambda:
// computed as expm1(lambda log y) / lambda, and log y at lambda = 0.
// Throws std::invalid_argument when y <= 0 or not finite.
double box_cox_transform(double y, double lambda);

// Transform of every value; same requirements as the scalar form.
std::vector<double> box_cox_transform(const std::vector<double>& values, double lambda);

// The shift Dataplot adds before transforming: 0 when every value is > 0, otherwise 1 - min
// (so y + shift = y - min + 1 >= 1). Throws std::invalid_argument on empty or non-finite input.
double box_cox_shift(const std::vector<double>& values);

// Filliben's normal order statistic medians for a sample of n (e-Handbook 1.3.3.21, 1.3.3.23):
// uniform medians m_n = 0.5^(1/n), m_1 = 1 - m_n, m_i = (i - 0.3175) / (n + 0.365) otherwise;
// returned as standard normal quantiles of those, ascending. n = 1 gives {0}.
std::vector<double> normal_order_statistic_medians(std::size_t n);

// Probability plot correlation coefficient of the transformed sample: Pearson correlation between
// sort(T(y; lambda)) and normal_order_statistic_medians(n). In [-1, 1]. `values` must be > 0.
// Returns -infinity when the transformed values are numerically constant or overflow (the objective
// is then treated as the worst possible). Throws std::invalid_argument if n < 3 or a value <= 0.
double box_cox_ppcc(const std::vector<double>& values, double lambda);

// Profile log-likelihood L(lambda) above, as scipy.stats.boxcox_llf(lambda, values) computes it.
// `values` must be > 0. Returns -infinity when the transformed values are numerically constant or
// overflow. Throws std::invalid_argument if n < 2 or a value <= 0.
double box_cox_log_likelihood(const std::vector<double>& values, double lambda);

// Which estimator chose lambda.
enum class BoxCoxMethod {
  kPpcc,  // maximum probability plot correlation (e-Handbook 1.3.3.6, Dataplot)
  kMle,   // maximum likelihood (Box and Cox 1964)
};

// "ppcc" / "mle", for reports and JSON.
const char* box_cox_method_name(BoxCoxMethod method);

struct BoxCoxOptions {
  double lambda_min = -2;  // search range, inclusive
  double lambda_max = 2;
  std::size_t grid_points = 81;  // grid before refinement (81: step 0.05 on [-2, 2])
};

// Estimated lambda. When `applicable` is false, only `reason` (and `n`, `shift`) mean anything.
struct BoxCoxResult {
  bool applicable = false;
  std::string reason;  // why not applicable; empty when applicable
  BoxCoxMethod method = BoxCoxMethod::kPpcc;
  std::size_t n = 0;  // number of values
  double shift = 0;   // added to every value before transforming (0, or 1 - min; Dataplot)
  double lambda = 0;  // the estimate (dimensionless)
  // Objective at lambda: the PPCC (in [-1, 1]) or the log-likelihood of the shifted data.
  double objective = 0;
  double ppcc_at_lambda = 0;  // PPCC of the transformed shifted data at `lambda`, for either method
  bool at_boundary = false;   // lambda is an end of the search range: the true optimum may lie out
};

// Estimates lambda of `values` (any sign; shifted by box_cox_shift()). Not applicable, with a
// reason, when n < 3 or the sample is constant. Throws std::invalid_argument on non-finite values
// or an empty / inverted search range.
BoxCoxResult box_cox_lambda(const std::vector<double>& values, BoxCoxMethod method,
                            const BoxCoxOptions& options = {});

}  // namespace ra::stats
