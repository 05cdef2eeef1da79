// Clopper-Pearson intervals against SciPy 1.10's binomtest(k, n).proportion_ci(0.95, "exact")
// (Debian 12's python3-scipy), to 1e-9.
#include "stats/binomial_interval.h"

#include <gtest/gtest.h>

#include <stdexcept>

namespace ra::stats {
namespace {

TEST(BinomialInterval, ClopperPearsonEqualsSciPy) {
  struct Case {
    std::uint64_t k, n;
    double low, high;
  };
  const Case cases[] = {
      {0, 10, 0.0, 0.30849710781876294},
      {3, 10, 0.06673951117773447, 0.652452850060008},
      {97, 100, 0.9148239470257197, 0.9937700284616938},
      {1500, 1500, 0.9975437685158015, 1.0},
      {62, 1500, 0.03183425005411852, 0.05267679224668432},
  };
  for (const Case& c : cases) {
    const ProportionInterval ci = clopper_pearson(c.k, c.n);
    EXPECT_NEAR(ci.low, c.low, 1e-9) << c.k << "/" << c.n;
    EXPECT_NEAR(ci.high, c.high, 1e-9) << c.k << "/" << c.n;
  }
  EXPECT_EQ(clopper_pearson(0, 0).low, 0.0);
  EXPECT_EQ(clopper_pearson(0, 0).high, 1.0);
  EXPECT_THROW(clopper_pearson(3, 2), std::invalid_argument);
}

}  // namespace
}  // namespace ra::stats
