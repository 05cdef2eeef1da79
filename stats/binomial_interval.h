// Confidence intervals for a binomial proportion (the share of records in a class): the
// Clopper-Pearson "exact" interval, by Boost.Math's beta quantiles. Never narrower than its
// nominal level; the same as R's binom.test and SciPy's binomtest(...).proportion_ci("exact").
#pragma once

#include <cstdint>

namespace ra::stats {

struct ProportionInterval {
  double low = 0, high = 1;  // proportions, 0 to 1
};

// The two-sided interval for k successes in n trials at `confidence` (0 < confidence < 1); n = 0
// gives [0, 1]. Throws std::invalid_argument when k > n.
ProportionInterval clopper_pearson(std::uint64_t k, std::uint64_t n, double confidence = 0.95);

}  // namespace ra::stats
