// Box-Cox transformation and lambda estimation; see box_cox.h. e-Handbook 1.3.3.6 (Box-Cox
// normality plot), 1.3.3.21 and 1.3.3.23 (normal order statistic medians, PPCC).
#include "stats/box_cox.h"

#include <algorithm>
#include <boost/math/distributions/normal.hpp>
#include <boost/math/tools/minima.hpp>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <stdexcept>

#include "stats/descriptive.h"

namespace ra::stats {
namespace {

constexpr double kMinusInfinity = -std::numeric_limits<double>::infinity();

// A positive sample prepared for fast, accurate evaluation of both objectives at many lambdas:
// sorted once (every T(.; lambda) is increasing in y, so the order never changes) and expressed as
// log(y / c) with c the median, computed as log1p((y - c) / c).
struct ScaledSample {
  std::vector<double> log_ratio;  // log(y_(i) / c), ascending
  double log_c = 0;               // log c
  double sum_log_ratio = 0;       // sum of log_ratio
};

ScaledSample scale(std::vector<double> values) {
  for (double y : values) {
    if (!(y > 0)) {
      throw std::invalid_argument("Box-Cox: value " + std::to_string(y) +
                                  " is not positive (shift the data first)");
    }
  }
  sort_ascending(values);
  const double c = quantile_sorted(values, 0.5);
  ScaledSample s;
  s.log_c = std::log(c);
  s.log_ratio.reserve(values.size());
  for (double y : values) s.log_ratio.push_back(std::log1p((y - c) / c));
  s.sum_log_ratio = 0;
  double compensation = 0;  // Neumaier, as the sum multiplies (lambda - 1) in the likelihood
  for (double l : s.log_ratio) {
    const double t = s.sum_log_ratio + l;
    compensation += std::fabs(s.sum_log_ratio) >= std::fabs(l) ? (s.sum_log_ratio - t) + l
                                                               : (l - t) + s.sum_log_ratio;
    s.sum_log_ratio = t;
  }
  s.sum_log_ratio += compensation;
  return s;
}

// T(y / c; lambda) for every value, ascending. False when a value overflows.
bool transform_scaled(const ScaledSample& s, double lambda, std::vector<double>& out) {
  out.resize(s.log_ratio.size());
  for (std::size_t i = 0; i < out.size(); ++i) {
    const double l = s.log_ratio[i];
    out[i] = lambda == 0 ? l : std::expm1(lambda * l) / lambda;
    if (!std::isfinite(out[i])) return false;
  }
  return true;
}

// The normal order statistic medians as the PPCC needs them at every lambda: centred on their
// mean, with their sum of squares (computed once per sample, not at every lambda).
struct CentredMedians {
  explicit CentredMedians(const std::vector<double>& medians) : centred(medians.size()) {
    const double m_mean = mean(medians);
    for (std::size_t i = 0; i < medians.size(); ++i) {
      centred[i] = medians[i] - m_mean;
      sum_of_squares += centred[i] * centred[i];
    }
  }
  std::vector<double> centred;
  double sum_of_squares = 0;
};

double ppcc_scaled(const ScaledSample& s, const CentredMedians& medians, double lambda) {
  std::vector<double> t;
  if (!transform_scaled(s, lambda, t)) return kMinusInfinity;
  const double t_mean = mean(t);
  double sxy = 0;
  double sxx = 0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    const double dx = t[i] - t_mean;
    sxy += dx * medians.centred[i];
    sxx += dx * dx;
  }
  if (!(sxx > 0) || !std::isfinite(sxx)) return kMinusInfinity;
  return std::clamp(sxy / std::sqrt(sxx * medians.sum_of_squares), -1.0, 1.0);
}

double log_likelihood_scaled(const ScaledSample& s, double lambda) {
  std::vector<double> t;
  if (!transform_scaled(s, lambda, t)) return kMinusInfinity;
  const double n = static_cast<double>(t.size());
  const double variance_n = mean_and_variance(t).variance * (n - 1) / n;
  if (!(variance_n > 0) || !std::isfinite(variance_n)) return kMinusInfinity;
  // L(y) = L(y / c) - n log c; see box_cox.h
  return (lambda - 1) * s.sum_log_ratio - n / 2 * std::log(variance_n) - n * s.log_c;
}

}  // namespace

double box_cox_transform(double y, double lambda) {
  if (!(y > 0) || !std::isfinite(y)) {
    throw std::invalid_argument("box_cox_transform: y = " + std::to_string(y) +
                                " must be positive and finite");
  }
  const double l = std::log(y);
  return lambda == 0 ? l : std::expm1(lambda * l) / lambda;
}

std::vector<double> box_cox_transform(const std::vector<double>& values, double lambda) {
  std::vector<double> out;
  out.reserve(values.size());
  for (double y : values) out.push_back(box_cox_transform(y, lambda));
  return out;
}

double box_cox_shift(const std::vector<double>& values) {
  if (values.empty()) throw std::invalid_argument("box_cox_shift: no values");
  require_finite(values, "box_cox_shift");
  const double lowest = *std::min_element(values.begin(), values.end());
  return lowest > 0 ? 0.0 : 1 - lowest;
}

std::vector<double> normal_order_statistic_medians(std::size_t n) {
  std::vector<double> m(n);
  if (n == 0) return m;
  const double nd = static_cast<double>(n);
  const double last = std::pow(0.5, 1 / nd);  // median of the largest of n uniforms
  const boost::math::normal standard;
  for (std::size_t i = 1; i <= n; ++i) {
    double u = (static_cast<double>(i) - 0.3175) / (nd + 0.365);
    if (i == 1) u = 1 - last;
    if (i == n) u = last;
    m[i - 1] = boost::math::quantile(standard, u);
  }
  return m;
}

double box_cox_ppcc(const std::vector<double>& values, double lambda) {
  if (values.size() < 3) throw std::invalid_argument("box_cox_ppcc: fewer than 3 values");
  require_finite(values, "box_cox_ppcc");
  return ppcc_scaled(scale(values), CentredMedians(normal_order_statistic_medians(values.size())),
                     lambda);
}

double box_cox_log_likelihood(const std::vector<double>& values, double lambda) {
  if (values.size() < 2) throw std::invalid_argument("box_cox_log_likelihood: fewer than 2 values");
  require_finite(values, "box_cox_log_likelihood");
  return log_likelihood_scaled(scale(values), lambda);
}

const char* box_cox_method_name(BoxCoxMethod method) {
  switch (method) {
    case BoxCoxMethod::kPpcc:
      return "ppcc";
    case BoxCoxMethod::kMle:
      return "mle";
  }
  return "unknown";
}

BoxCoxResult box_cox_lambda(const std::vector<double>& values, BoxCoxMethod method,
                            const BoxCoxOptions& options) {
  if (!(options.lambda_min < options.lambda_max) || options.grid_points < 2 ||
      !std::isfinite(options.lambda_min) || !std::isfinite(options.lambda_max)) {
    throw std::invalid_argument("box_cox_lambda: empty search range or fewer than 2 grid points");
  }
  BoxCoxResult r;
  r.method = method;
  r.n = values.size();
  if (values.size() < 3) {
    r.reason = "fewer than 3 values";
    return r;
  }
  r.shift = box_cox_shift(values);  // also rejects non-finite values
  const auto [lowest, highest] = std::minmax_element(values.begin(), values.end());
  if (*lowest == *highest) {
    r.reason = "all values are equal: no power transformation makes a constant sample normal";
    return r;
  }
  std::vector<double> shifted = values;
  if (r.shift != 0) {
    // Dataplot's y - min + 1, in that order: y - min is exact for data close to the minimum
    for (double& y : shifted) y = (y - *lowest) + 1;
  }
  const ScaledSample s = scale(shifted);
  const CentredMedians medians(normal_order_statistic_medians(values.size()));
  const std::function<double(double)> objective = [&](double lambda) {
    return method == BoxCoxMethod::kPpcc ? ppcc_scaled(s, medians, lambda)
                                         : log_likelihood_scaled(s, lambda);
  };

  // grid search, then Brent's method inside the cells either side of the best grid point
  const std::size_t g = options.grid_points;
  const double step = (options.lambda_max - options.lambda_min) / static_cast<double>(g - 1);
  auto grid = [&](std::size_t j) {
    return j + 1 == g ? options.lambda_max : options.lambda_min + step * static_cast<double>(j);
  };
  std::size_t best = 0;
  double best_value = kMinusInfinity;
  for (std::size_t j = 0; j < g; ++j) {
    const double v = objective(grid(j));
    if (v > best_value) {
      best_value = v;
      best = j;
    }
  }
  if (best_value == kMinusInfinity) {
    r.reason = "the transformed data overflow or are numerically constant at every lambda";
    return r;
  }
  const double lo = grid(best == 0 ? 0 : best - 1);
  const double hi = grid(std::min(best + 1, g - 1));
  const int bits = std::numeric_limits<double>::digits / 2;  // the attainable accuracy: sqrt(eps)
  std::uintmax_t max_iterations = 200;
  const auto minimum = boost::math::tools::brent_find_minima(
      [&](double lambda) { return -objective(lambda); }, lo, hi, bits, max_iterations);
  r.lambda = minimum.first;
  r.objective = -minimum.second;
  if (best_value > r.objective) {  // Brent never does worse than the grid; keep this honest anyway
    r.lambda = grid(best);
    r.objective = best_value;
  }
  // an optimum at the end of the range: report the end itself and say so
  for (double end : {options.lambda_min, options.lambda_max}) {
    if (std::fabs(r.lambda - end) <= step) {
      const double v = objective(end);
      if (v >= r.objective) {
        r.lambda = end;
        r.objective = v;
        r.at_boundary = true;
      }
    }
  }
  r.ppcc_at_lambda = ppcc_scaled(s, medians, r.lambda);
  r.applicable = true;
  return r;
}

}  // namespace ra::stats
