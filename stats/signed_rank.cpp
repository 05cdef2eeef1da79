#include "stats/signed_rank.h"

#include <algorithm>
#include <boost/math/distributions/normal.hpp>
#include <cmath>
#include <stdexcept>
#include <string>

namespace ra::stats {
namespace {

constexpr std::size_t kExactLimit = 300;

// P(T+ = s), s = 0..n(n+1)/2, under the null hypothesis: each rank k is in the positive set with
// probability 1/2, independently. Halving at every step keeps the values probabilities (no 2^n).
std::vector<double> null_distribution(std::size_t n) {
  const std::size_t total = n * (n + 1) / 2;
  std::vector<double> p(total + 1, 0.0);
  p[0] = 1;
  std::size_t reach = 0;
  for (std::size_t k = 1; k <= n; ++k) {
    reach += k;
    for (std::size_t s = reach; s >= k; --s) p[s] = 0.5 * (p[s] + p[s - k]);
    for (std::size_t s = std::min(k, reach + 1); s-- > 0;) p[s] *= 0.5;
  }
  return p;
}

double normal_upper_tail(std::size_t n, double t) {
  const double nd = double(n);
  const double mean = nd * (nd + 1) / 4;
  const double sd = std::sqrt(nd * (nd + 1) * (2 * nd + 1) / 24);
  const boost::math::normal z;
  return boost::math::cdf(boost::math::complement(z, (t - 0.5 - mean) / sd));
}

// The smallest t with P(T+ >= t) <= tail.
std::size_t upper_critical_value(std::size_t n, double tail) {
  const std::size_t total = n * (n + 1) / 2;
  if (n <= kExactLimit) {
    const std::vector<double> p = null_distribution(n);
    double sum = 0;
    std::size_t t = total + 1;
    while (t > 0 && sum + p[t - 1] <= tail) sum += p[--t];
    return t;
  }
  const double nd = double(n);
  const double mean = nd * (nd + 1) / 4;
  const double sd = std::sqrt(nd * (nd + 1) * (2 * nd + 1) / 24);
  const boost::math::normal z;
  const double q = boost::math::quantile(boost::math::complement(z, tail));
  auto t = std::size_t(std::ceil(mean + 0.5 + q * sd));
  while (t > 0 && normal_upper_tail(n, double(t - 1)) <= tail) --t;  // the smallest such t
  while (normal_upper_tail(n, double(t)) > tail) ++t;
  return std::min(t, total + 1);
}

// The k-th smallest (1-based) of `values`, which it reorders.
double kth_smallest(std::vector<double>& values, std::size_t k) {
  std::nth_element(values.begin(), values.begin() + long(k - 1), values.end());
  return values[k - 1];
}

}  // namespace

double signed_rank_upper_tail(std::size_t n, double t) {
  if (n == 0) return t <= 0 ? 1.0 : 0.0;
  if (n > kExactLimit) return normal_upper_tail(n, t);
  const std::vector<double> p = null_distribution(n);
  double sum = 0;
  for (std::size_t s = p.size(); s-- > 0 && double(s) >= t;) sum += p[s];
  return std::min(1.0, sum);
}

SignedRankInterval signed_rank_interval(const std::vector<double>& differences, double level) {
  if (!(level > 0 && level < 1))
    throw std::invalid_argument("signed-rank interval: level must be in (0, 1)");
  for (double d : differences)
    if (!std::isfinite(d))
      throw std::invalid_argument("signed-rank interval: a difference is not finite");
  const std::size_t n = differences.size();
  const std::size_t total = n * (n + 1) / 2;
  const double tail = (1 - level) / 2;
  // With all n differences positive T+ = N, the most extreme value: no interval of this coverage
  // exists while that alone is more probable than the tail.
  if (n == 0 || std::ldexp(1.0, -int(std::min<std::size_t>(n, 1000))) > tail)
    throw std::invalid_argument("signed-rank interval: " + std::to_string(n) +
                                " differences are too few for a " +
                                std::to_string(int(std::lround(level * 100))) + "% interval");
  std::vector<double> walsh;
  walsh.reserve(total);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i; j < n; ++j) walsh.push_back(0.5 * (differences[i] + differences[j]));

  SignedRankInterval out;
  out.n = n;
  out.level = level;
  out.exact = n <= kExactLimit;
  // The median of N values: the middle one, or the mean of the two middle ones.
  const double upper_middle = kth_smallest(walsh, total / 2 + 1);
  out.estimate = total % 2 ? upper_middle
                           : 0.5 * (upper_middle + kth_smallest(walsh, total / 2));
  const std::size_t t = upper_critical_value(n, tail);
  const std::size_t c = total + 1 - t;  // 1-based positions c and t bound the interval
  out.low = kth_smallest(walsh, c);
  out.high = kth_smallest(walsh, t);
  return out;
}

}  // namespace ra::stats
