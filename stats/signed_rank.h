// The Wilcoxon signed-rank test's location estimate and confidence interval for one sample of
// paired differences: the Hodges-Lehmann estimate (the median of the Walsh averages
// (d_i + d_j) / 2, i <= j) and the distribution-free interval that inverts the signed-rank test
// (Hollander, Wolfe and Chicken, Nonparametric Statistical Methods, 3rd ed., section 3.3). It
// assumes only that the differences are independent and symmetric about their centre, which the
// log of a per-primitive time ratio is far closer to than the ratio itself.
//
// The interval is [W_(C), W_(N + 1 - C)] of the N = n(n + 1)/2 sorted Walsh averages, C = N + 1 -
// t, where t is the smallest value with P(T+ >= t) <= (1 - level) / 2 under the null hypothesis
// (T+ the sum of the ranks of the positive differences). Its coverage is at least `level`; it is
// exactly the set of centres the two-sided signed-rank test does not reject at 1 - level, so it
// agrees with SciPy's `wilcoxon` (checked in the test). T+'s null distribution is computed
// exactly for n <= 300 (a subset-sum count, 13.5 million additions at n = 300) and by the normal
// approximation beyond, where the two differ by less than one Walsh average's position.
#pragma once

#include <cstddef>
#include <vector>

namespace ra::stats {

struct SignedRankInterval {
  std::size_t n = 0;      // differences used (finite ones)
  double estimate = 0;    // Hodges-Lehmann: median of the Walsh averages, units of the data
  double low = 0, high = 0;  // the interval's ends, units of the data (low <= estimate <= high)
  double level = 0.95;    // requested coverage
  bool exact = true;      // T+'s exact null distribution (n <= 300), else the normal approximation
};

// The estimate and interval of `differences` (any order; non-finite values throw
// std::invalid_argument). Needs n >= 6 at level 0.95 (with fewer, no interval of that coverage
// exists: P(T+ = N) = 2^-n > 0.025 for n <= 5); throws std::invalid_argument with the reason
// otherwise. `level` in (0, 1).
SignedRankInterval signed_rank_interval(const std::vector<double>& differences, double level = 0.95);

// P(T+ >= t) under the null hypothesis for n differences, exactly (n <= 300) or by the normal
// approximation with continuity correction. Exposed for tests.
double signed_rank_upper_tail(std::size_t n, double t);

}  // namespace ra::stats
