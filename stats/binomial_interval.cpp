#include "stats/binomial_interval.h"

#include <boost/math/distributions/binomial.hpp>
#include <stdexcept>

namespace ra::stats {

ProportionInterval clopper_pearson(std::uint64_t k, std::uint64_t n, double confidence) {
  if (k > n) throw std::invalid_argument("clopper_pearson: more successes than trials");
  if (!(confidence > 0 && confidence < 1))
    throw std::invalid_argument("clopper_pearson: confidence must lie in (0, 1)");
  if (n == 0) return {0, 1};
  using boost::math::binomial_distribution;
  const double tail = (1 - confidence) / 2;
  // Boost's Clopper-Pearson bounds: each one-sided at `tail`.
  return {binomial_distribution<>::find_lower_bound_on_p(double(n), double(k), tail),
          binomial_distribution<>::find_upper_bound_on_p(double(n), double(k), tail)};
}

}  // namespace ra::stats
