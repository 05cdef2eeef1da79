// Descriptive statistics; see descriptive.h. e-Handbook
// sections 1.3.5.1, 1.3.5.6, 1.3.3.7, 7.2.6.2.
#include "stats/descriptive.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>

namespace ra::stats {
namespace {

// Neumaier's compensated sum: the rounding error of each addition is kept and added back at the
// end, so long sums of residuals keep the digits that matter for the variance.
class CompensatedSum {
 public:
  void add(double x) {
    const double t = sum_ + x;
    if (std::fabs(sum_) >= std::fabs(x)) {
      compensation_ += (sum_ - t) + x;
    } else {
      compensation_ += (x - t) + sum_;
    }
    sum_ = t;
  }
  double value() const { return sum_ + compensation_; }

 private:
  double sum_ = 0;
  double compensation_ = 0;
};

void require_non_empty(const std::vector<double>& values, const char* what) {
  if (values.empty()) throw std::invalid_argument(std::string(what) + ": no values");
}

// 2^e when it is a normal double (|e| <= 1022): multiplying by it is then exact whenever the
// product is normal and rounds once otherwise, exactly as std::ldexp; nullopt outside that range.
std::optional<double> exact_power_of_two(int e) {
  if (e < std::numeric_limits<double>::min_exponent - 1 ||
      e > std::numeric_limits<double>::max_exponent - 2)
    return std::nullopt;
  return std::ldexp(1.0, e);
}

// Mean and sample variance of scale(x) over the values, scaled back by 2^e: Chan, Golub and
// LeVeque's corrected two-pass formula (see mean_and_variance()).
template <typename Scale>
MeanVariance corrected_two_pass(const std::vector<double>& values, Scale scale, int e) {
  const double n = static_cast<double>(values.size());
  // first pass: provisional mean of the values shifted by the first one, so that constant leading
  // digits cancel exactly before anything is summed
  const double shift = scale(values.front());
  CompensatedSum shifted;
  for (double x : values) shifted.add(scale(x) - shift);
  const double provisional = shift + shifted.value() / n;

  // second pass: residuals from the provisional mean; their sum corrects the mean, and subtracting
  // (sum)^2 / n corrects the sum of squares
  CompensatedSum residuals;
  CompensatedSum squares;
  for (double x : values) {
    const double r = scale(x) - provisional;
    residuals.add(r);
    squares.add(r * r);
  }
  MeanVariance result;
  result.scale_exponent = e;
  result.mean = std::ldexp(provisional + residuals.value() / n, e);
  if (values.size() >= 2) {
    const double ss = squares.value() - residuals.value() * residuals.value() / n;
    result.scaled_variance = std::max(0.0, ss) / (n - 1);
    result.sd = std::ldexp(std::sqrt(result.scaled_variance), e);
    result.variance = std::ldexp(result.scaled_variance, 2 * e);
  }
  return result;
}

}  // namespace

const char* quantile_definition_name(QuantileDefinition definition) {
  switch (definition) {
    case QuantileDefinition::kHyndmanFan6:
      return "hyndman_fan_6";
    case QuantileDefinition::kHyndmanFan7:
      return "hyndman_fan_7";
  }
  return "unknown";
}

void require_finite(const std::vector<double>& values, const char* what) {
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!std::isfinite(values[i])) {
      throw std::invalid_argument(std::string(what) + ": value " + std::to_string(i + 1) + " of " +
                                  std::to_string(values.size()) + " is not finite (" +
                                  std::to_string(values[i]) + ")");
    }
  }
}

int scale_exponent(const std::vector<double>& values) {
  double largest = 0;
  for (double x : values) largest = std::max(largest, std::fabs(x));
  if (!(largest > 0) || !std::isfinite(largest)) return 0;
  int e = 0;
  std::frexp(largest, &e);  // largest = m 2^e with 0.5 <= m < 1
  return e;
}

int scale_exponent(const std::vector<std::vector<double>>& groups) {
  int e = std::numeric_limits<int>::min();
  for (const auto& g : groups)
    if (std::any_of(g.begin(), g.end(), [](double x) { return x != 0; }))
      e = std::max(e, scale_exponent(g));
  return e == std::numeric_limits<int>::min() ? 0 : e;
}

std::vector<double> scaled(const std::vector<double>& values, int e) {
  std::vector<double> out(values.size());
  if (const std::optional<double> factor = exact_power_of_two(-e)) {
    const double f = *factor;
    std::transform(values.begin(), values.end(), out.begin(), [f](double x) { return x * f; });
  } else {
    std::transform(values.begin(), values.end(), out.begin(),
                   [e](double x) { return std::ldexp(x, -e); });
  }
  return out;
}

MeanVariance mean_and_variance(const std::vector<double>& unscaled) {
  require_non_empty(unscaled, "mean_and_variance");
  require_finite(unscaled, "mean_and_variance");
  const int e = scale_exponent(unscaled);
  // every scaled |x| < 1; the scaling is applied on the fly where 2^-e is a normal double (one
  // multiplication, the same rounding as ldexp), so the data are not copied
  if (const std::optional<double> factor = exact_power_of_two(-e)) {
    const double f = *factor;
    return corrected_two_pass(unscaled, [f](double x) { return x * f; }, e);
  }
  return corrected_two_pass(scaled(unscaled, e), [](double x) { return x; }, e);
}

double mean(const std::vector<double>& values) { return mean_and_variance(values).mean; }

double quantile_sorted(const std::vector<double>& sorted, double p, QuantileDefinition definition) {
  require_non_empty(sorted, "quantile_sorted");
  if (!(p >= 0 && p <= 1)) {
    throw std::invalid_argument("quantile_sorted: p = " + std::to_string(p) + " is outside [0, 1]");
  }
  const double n = static_cast<double>(sorted.size());
  // 1-based position of the quantile among the order statistics
  double h = 0;
  switch (definition) {
    case QuantileDefinition::kHyndmanFan6:
      h = p * (n + 1);
      break;
    case QuantileDefinition::kHyndmanFan7:
      h = 1 + p * (n - 1);
      break;
  }
  if (h <= 1) return sorted.front();
  if (h >= n) return sorted.back();
  const double k = std::floor(h);
  const double fraction = h - k;
  const std::size_t below = static_cast<std::size_t>(k) - 1;  // 0-based index of x_(k)
  const double lo = sorted[below];
  const double hi = sorted[below + 1];
  // note: lo + f * (hi - lo) is exact when lo == hi and stays inside [lo, hi]; when hi - lo
  // overflows (values of both signs near 1e308) the same is formed on halves (exact but for
  // subnormals, which cannot occur beside a difference that overflows)
  const double gap = hi - lo;
  if (std::isfinite(gap)) return lo + fraction * gap;
  return 2 * (lo / 2 + fraction * (hi / 2 - lo / 2));
}

void sort_ascending(std::vector<double>& values) {
  if (!std::is_sorted(values.begin(), values.end())) std::sort(values.begin(), values.end());
}

std::vector<double> merged_ascending(const std::vector<double>& a, const std::vector<double>& b) {
  std::vector<double> out(a.size() + b.size());
  if (std::is_sorted(a.begin(), a.end()) && std::is_sorted(b.begin(), b.end())) {
    std::merge(a.begin(), a.end(), b.begin(), b.end(), out.begin());
  } else {
    std::copy(b.begin(), b.end(), std::copy(a.begin(), a.end(), out.begin()));
    std::sort(out.begin(), out.end());
  }
  return out;
}

double quantile(std::vector<double> values, double p, QuantileDefinition definition) {
  require_non_empty(values, "quantile");
  sort_ascending(values);
  return quantile_sorted(values, p, definition);
}

double median(std::vector<double> values) { return quantile(std::move(values), 0.5); }

double median_or_nan(std::vector<double> values) {
  return values.empty() ? std::numeric_limits<double>::quiet_NaN() : median(std::move(values));
}

Description describe(std::vector<double> values, QuantileDefinition definition) {
  require_non_empty(values, "describe");
  require_finite(values, "describe");
  const MeanVariance mv = mean_and_variance(values);
  sort_ascending(values);
  Description d;
  d.n = values.size();
  d.mean = mv.mean;
  d.sd = mv.sd;
  d.median = quantile_sorted(values, 0.5, definition);
  d.q1 = quantile_sorted(values, 0.25, definition);
  d.q3 = quantile_sorted(values, 0.75, definition);
  d.iqr = d.q3 - d.q1;
  d.min = values.front();
  d.max = values.back();
  return d;
}

std::size_t trimmed_count(std::size_t n, double proportion) {
  // the product is formed in double as SciPy does (int(proportiontocut * n))
  return static_cast<std::size_t>(std::floor(proportion * static_cast<double>(n)));
}

double trimmed_mean(std::vector<double> values, double proportion) {
  require_non_empty(values, "trimmed_mean");
  require_finite(values, "trimmed_mean");
  if (!(proportion >= 0 && proportion < 0.5)) {
    throw std::invalid_argument("trimmed_mean: proportion " + std::to_string(proportion) +
                                " is outside [0, 0.5)");
  }
  sort_ascending(values);
  const std::size_t cut = trimmed_count(values.size(), proportion);
  // cut < n / 2 because proportion < 0.5, so at least one value is left
  std::vector<double> kept(values.begin() + static_cast<std::ptrdiff_t>(cut),
                           values.end() - static_cast<std::ptrdiff_t>(cut));
  return mean(kept);
}

BoxPlotData box_plot(std::vector<double> values, QuantileDefinition definition,
                     std::size_t max_outliers) {
  require_non_empty(values, "box_plot");
  require_finite(values, "box_plot");
  sort_ascending(values);
  BoxPlotData b;
  b.n = values.size();
  b.q1 = quantile_sorted(values, 0.25, definition);
  b.median = quantile_sorted(values, 0.5, definition);
  b.q3 = quantile_sorted(values, 0.75, definition);
  const double iqr = b.q3 - b.q1;
  b.lower_fence = b.q1 - 1.5 * iqr;
  b.upper_fence = b.q3 + 1.5 * iqr;

  // values are sorted: the inside range is [first >= lower fence, last <= upper fence]; it is never
  // empty because the median lies inside the fences
  const auto first_inside = std::lower_bound(values.begin(), values.end(), b.lower_fence);
  const auto past_inside = std::upper_bound(values.begin(), values.end(), b.upper_fence);
  b.lower_whisker = *first_inside;
  b.upper_whisker = *(past_inside - 1);
  b.n_outliers_low = static_cast<std::size_t>(first_inside - values.begin());
  b.n_outliers_high = static_cast<std::size_t>(values.end() - past_inside);

  // keep the most extreme outliers, alternating between the two ends
  std::size_t take_low = 0;
  std::size_t take_high = 0;
  while (take_low + take_high < max_outliers &&
         (take_low < b.n_outliers_low || take_high < b.n_outliers_high)) {
    if (take_low < b.n_outliers_low) ++take_low;
    if (take_low + take_high < max_outliers && take_high < b.n_outliers_high) ++take_high;
  }
  b.outliers.assign(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(take_low));
  b.outliers.insert(b.outliers.end(), values.end() - static_cast<std::ptrdiff_t>(take_high),
                    values.end());
  b.outliers_truncated = take_low + take_high < b.n_outliers_low + b.n_outliers_high;
  return b;
}

}  // namespace ra::stats
