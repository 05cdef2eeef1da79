// Statistics across the whole double range (issue: sd 0 for 1e200, "every group is constant", NaN
// and inf printed near 1e308). The same small data sets are multiplied by 1e-300, 1e-170, 1e154,
// 1e200 and 1e300 (and mixed); the references are computed independently by /usr/bin/python3 from
// the very same doubles: exact rational arithmetic (fractions.Fraction) for means, variances, t and
// F, SciPy (levene, f.sf, t.sf, linregress) on the data divided by a power of two, which is exact.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <vector>

#include "stats/descriptive.h"
#include "stats/hypothesis_tests.h"
#include "stats/linear_regression.h"
#include "stats/stats_testing.h"

namespace ra::stats {
namespace {

const std::vector<double> kMagnitudes = {1e-300, 1e-170, 1e154, 1e200, 1e300};
// Three groups with different means and spreads (units: 1).
const std::vector<std::vector<double>> kBase = {
    {1.0, 1.5, 2.25, 0.75, 1.125, 1.9},
    {2.5, 3.0, 2.0, 3.75, 2.2, 2.9, 3.1},
    {1.8, 2.6, 2.4, 1.1, 2.0}};

std::vector<std::vector<double>> groups_at(double m) {
  std::vector<std::vector<double>> g = kBase;
  for (auto& v : g)
    for (double& x : v) x *= m;  // the test's data: whatever doubles this gives
  return g;
}

// The reference values for every magnitude, computed once by Python from the doubles themselves.
const nlohmann::json& reference() {
  static const nlohmann::json ref = [] {
    nlohmann::json input = nlohmann::json::array();
    for (double m : kMagnitudes) input.push_back(groups_at(m));
    return testing::run_scipy(R"(
from fractions import Fraction as F
def scale_exp(groups):  # 2^e above every |x|, as the library's scale_exponent
    big = max(abs(x) for g in groups for x in g)
    return math.frexp(big)[1]
def mv(xs):
    xs = [F(x) for x in xs]; n = len(xs); m = sum(xs) / n
    return m, sum((x - m) ** 2 for x in xs) / (n - 1)
def sqrt_scaled(v, e):  # sqrt of an exact variance in data units squared, as a float, via 2^e
    return math.ldexp(math.sqrt(float(v / F(2) ** (2 * e))), e)
out = []
for groups in inp:
    e = scale_exp(groups)
    a, b = groups[0], groups[1]
    ma, va = mv(a); mb, vb = mv(b)
    n1, n2 = len(a), len(b)
    sp2 = ((n1 - 1) * va + (n2 - 1) * vb) / (n1 + n2 - 2)
    t = float((ma - mb) / F(2) ** e) / math.sqrt(float(sp2 * (F(1, n1) + F(1, n2)) / F(2) ** (2 * e)))
    fvar = float(va / vb)
    allv = [F(x) for g in groups for x in g]; gm = sum(allv) / len(allv)
    ssb = sum(len(g) * (mv(g)[0] - gm) ** 2 for g in groups)
    ssw = sum((len(g) - 1) * mv(g)[1] for g in groups)
    dfb, dfw = len(groups) - 1, len(allv) - len(groups)
    fst = float((ssb / dfb) / (ssw / dfw))
    scaled = [[math.ldexp(x, -e) for x in g] for g in groups]
    lev = scipy.stats.levene(*scaled, center='median')
    # regression of y = group 1 on x = 1..n (x unscaled, y scaled exactly)
    ys = scaled[1]; xs = list(range(1, len(ys) + 1))
    lr = scipy.stats.linregress(xs, ys)
    out.append({
        'mean0': float(ma), 'sd0': sqrt_scaled(va, e),
        't': t, 't_p': float(2 * scipy.stats.t.sf(abs(t), n1 + n2 - 2)),
        'sp': sqrt_scaled(sp2, e), 'diff': float(ma - mb),
        'f_var': fvar, 'anova_f': fst, 'anova_p': float(scipy.stats.f.sf(fst, dfb, dfw)),
        'residual_sd': sqrt_scaled(ssw / dfw, e),
        'levene_w': float(lev.statistic), 'levene_p': float(lev.pvalue),
        'slope': math.ldexp(lr.slope, e), 'slope_p': float(lr.pvalue)})
)", input);
  }();
  return ref;
}

void expect_close(double got, double want, const char* what, double m) {
  EXPECT_TRUE(std::isfinite(got)) << what << " at " << m << ": " << got;
  EXPECT_LE(testing::relative_difference(got, want), 1e-12)
      << what << " at magnitude " << m << ": got " << got << ", exact " << want;
}

TEST(ExtremeValues, DescribeIsRightAtEveryMagnitude) {
  for (std::size_t i = 0; i < kMagnitudes.size(); ++i) {
    const double m = kMagnitudes[i];
    const auto& ref = reference()[i];
    const Description d = describe(groups_at(m)[0]);
    expect_close(d.mean, ref["mean0"], "mean", m);
    expect_close(d.sd, ref["sd0"], "sd", m);
    EXPECT_GT(d.iqr, 0) << m;
  }
}

TEST(ExtremeValues, TTestsAndFTestAreRightAtEveryMagnitude) {
  for (std::size_t i = 0; i < kMagnitudes.size(); ++i) {
    const double m = kMagnitudes[i];
    const auto& ref = reference()[i];
    const auto g = groups_at(m);
    const TTestResult t = t_test_pooled(g[0], g[1]);
    expect_close(t.statistic, ref["t"], "pooled t", m);
    expect_close(t.p_value, ref["t_p"], "pooled t p", m);
    expect_close(*t.pooled_sd, ref["sp"], "pooled sd", m);
    expect_close(t.mean_difference, ref["diff"], "mean difference", m);
    const TTestResult w = t_test_welch(g[0], g[1]);
    EXPECT_TRUE(std::isfinite(w.statistic) && std::isfinite(w.p_value) && w.p_value < 1) << m;
    expect_close(f_test_variances(g[0], g[1]).statistic, ref["f_var"], "F", m);
  }
}

TEST(ExtremeValues, AnovaAndLeveneAreRightAtEveryMagnitude) {
  for (std::size_t i = 0; i < kMagnitudes.size(); ++i) {
    const double m = kMagnitudes[i];
    const auto& ref = reference()[i];
    const AnovaResult a = one_way_anova(groups_at(m));
    expect_close(a.f, ref["anova_f"], "ANOVA F", m);
    expect_close(a.p_value, ref["anova_p"], "ANOVA p", m);
    expect_close(a.residual_sd, ref["residual_sd"], "ANOVA residual sd", m);
    const FTestResult l = levene_test(groups_at(m), LeveneCenter::kMedian);
    expect_close(l.statistic, ref["levene_w"], "Levene W", m);
    expect_close(l.p_value, ref["levene_p"], "Levene p", m);
  }
}

TEST(ExtremeValues, RegressionIsRightAtEveryMagnitude) {
  for (std::size_t i = 0; i < kMagnitudes.size(); ++i) {
    const double m = kMagnitudes[i];
    const auto& ref = reference()[i];
    const std::vector<double> y = groups_at(m)[1];
    std::vector<double> x(y.size());
    for (std::size_t k = 0; k < x.size(); ++k) x[k] = double(k + 1);
    const LinearFit fit = fit_least_squares({x}, y, true);
    expect_close(fit.coefficients[1], ref["slope"], "slope", m);
    expect_close(coefficient_t_test(fit, 1).p_value, ref["slope_p"], "slope p", m);
    EXPECT_TRUE(std::isfinite(fit.residual_sd)) << m;
  }
}

// Near the top of the range: results that exist are right, and those that do not (an sd or IQR
// above 1.8e308) are infinite in the library and never NaN.
TEST(ExtremeValues, NearTheTopOfTheRangeNothingIsNaN) {
  const std::vector<double> v = {1.7e308, -1.7e308, 1.6e308, 1.0e308};
  const Description d = describe(v);
  // exact mean: (1.7 - 1.7 + 1.6 + 1.0)e308 / 4 = 0.65e308
  EXPECT_LE(testing::relative_difference(d.mean, 0.65e308), 1e-15) << d.mean;
  // Hyndman-Fan 6: position 1.25, a quarter of the way from -1.7e308 to 1.0e308, whose gap
  // (2.7e308) overflows: -1.7e308 + 0.25 x 2.7e308 = -1.025e308
  EXPECT_LE(testing::relative_difference(d.q1, -1.025e308), 1e-15) << d.q1;
  EXPECT_FALSE(std::isnan(d.sd));
  EXPECT_TRUE(std::isinf(d.iqr) || d.iqr > 0);
  EXPECT_FALSE(std::isnan(d.median));
  EXPECT_LE(testing::relative_difference(d.median, 1.3e308), 1e-15) << d.median;
}

// Mixed magnitudes: values below one ulp of the largest change nothing, and nothing breaks.
TEST(ExtremeValues, MixedMagnitudesKeepTheLargeValuesExact) {
  const std::vector<double> v = {1e300, 3e300, 1e-300, 2e300, 5e-310};
  const MeanVariance mv = mean_and_variance(v);
  // exact mean = (6e300 + tiny) / 5 = 1.2e300 to double precision; sd = sqrt(var) with var of
  // {1, 3, 0, 2, 0} x 1e300: mean 1.2, ss = 0.04+3.24+1.44+0.64+1.44 = 6.8, var = 1.7
  EXPECT_LE(testing::relative_difference(mv.mean, 1.2e300), 1e-15);
  EXPECT_LE(testing::relative_difference(mv.sd, std::sqrt(1.7) * 1e300), 1e-14);
}

}  // namespace
}  // namespace ra::stats
