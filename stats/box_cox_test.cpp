// Tests of stats/box_cox.h: the transform, Filliben's medians, both objectives and both lambda
// estimates against SciPy on the same data, and the hard cases (zeros, constant, tiny n, 1e9
// offset).
#include "stats/box_cox.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "stats/stats_testing.h"

namespace ra::stats {
namespace {

using testing::relative_difference;

TEST(BoxCoxTransform, DefinitionAndContinuityAtZero) {
  EXPECT_DOUBLE_EQ(box_cox_transform(4.0, 0.5), (2.0 - 1) / 0.5);
  EXPECT_DOUBLE_EQ(box_cox_transform(3.0, 1.0), 2.0);
  EXPECT_DOUBLE_EQ(box_cox_transform(2.0, -1.0), 0.5);
  EXPECT_DOUBLE_EQ(box_cox_transform(5.0, 0.0), std::log(5.0));
  // near lambda = 0 the transform tends to log y without cancellation (expm1)
  for (double lambda : {1e-8, -1e-8, 1e-14, 1e-300}) {
    EXPECT_LT(relative_difference(box_cox_transform(5.0, lambda), std::log(5.0)), 1e-7)
        << "lambda " << lambda;
  }
  EXPECT_THROW(box_cox_transform(0.0, 1), std::invalid_argument);
  EXPECT_THROW(box_cox_transform(-1.0, 1), std::invalid_argument);
}

TEST(BoxCoxMedians, FillibenFormula) {
  const auto m = normal_order_statistic_medians(5);
  ASSERT_EQ(m.size(), 5u);
  EXPECT_NEAR(m[2], 0, 1e-15);    // the middle one of an odd n is the median, 0
  EXPECT_DOUBLE_EQ(m[0], -m[4]);  // symmetric
  EXPECT_TRUE(std::is_sorted(m.begin(), m.end()));
  EXPECT_EQ(normal_order_statistic_medians(1), std::vector<double>{0.0});
  EXPECT_TRUE(normal_order_statistic_medians(0).empty());
}

TEST(BoxCoxHardCases, ConstantAndTinySamplesAreNotApplicable) {
  for (auto method : {BoxCoxMethod::kPpcc, BoxCoxMethod::kMle}) {
    const BoxCoxResult c = box_cox_lambda(std::vector<double>(50, 2.5), method);
    EXPECT_FALSE(c.applicable);
    EXPECT_NE(c.reason.find("equal"), std::string::npos) << c.reason;
    const BoxCoxResult two = box_cox_lambda({1.0, 2.0}, method);
    EXPECT_FALSE(two.applicable);
    EXPECT_FALSE(two.reason.empty());
    EXPECT_FALSE(box_cox_lambda({}, method).applicable);
    EXPECT_FALSE(box_cox_lambda({1.0}, method).applicable);
    EXPECT_THROW(box_cox_lambda({1.0, NAN, 2.0}, method), std::invalid_argument);
  }
}

// Zeros and negatives: shifted the Dataplot way, y - min + 1, and the shift is reported; the result
// equals the estimate on the shifted data.
TEST(BoxCoxHardCases, ZerosAreShifted) {
  auto x = testing::exponential_sample(80, 2, 51);
  for (std::size_t i = 0; i < 10; ++i) x[i] = 0;
  x[10] = -0.5;
  std::vector<double> shifted = x;
  for (auto& y : shifted) y = (y + 0.5) + 1;
  for (auto method : {BoxCoxMethod::kPpcc, BoxCoxMethod::kMle}) {
    const BoxCoxResult r = box_cox_lambda(x, method);
    ASSERT_TRUE(r.applicable) << r.reason;
    EXPECT_EQ(r.shift, 1.5);
    const BoxCoxResult s = box_cox_lambda(shifted, method);
    EXPECT_EQ(s.shift, 0);
    EXPECT_NEAR(r.lambda, s.lambda, 1e-9);
    EXPECT_TRUE(std::isfinite(r.objective));
  }
  EXPECT_EQ(box_cox_shift({3, 0, 5}), 1);
  EXPECT_EQ(box_cox_shift({3, 1e-3}), 0);
}

// Data near 1e9 with tiny noise: the objectives stay finite and the estimate exists; both
// objectives are invariant to rescaling, so 1e9 + noise and (1e9 + noise) / 1e9 give one lambda.
TEST(BoxCoxHardCases, HugeOffsetAndScaleInvariance) {
  const auto x = testing::plus(testing::lognormal_sample(200, 0, 0.5, 52), 1e9);
  for (auto method : {BoxCoxMethod::kPpcc, BoxCoxMethod::kMle}) {
    const BoxCoxResult r = box_cox_lambda(x, method);
    ASSERT_TRUE(r.applicable) << r.reason;
    EXPECT_TRUE(std::isfinite(r.lambda));
    EXPECT_TRUE(std::isfinite(r.objective));
    EXPECT_GT(r.ppcc_at_lambda, 0.5);
  }
  const auto y = testing::lognormal_sample(150, 1, 0.8, 53);
  std::vector<double> scaled = y;
  for (auto& v : scaled) v *= 1024;  // exact, so the data are the same up to scale
  for (auto method : {BoxCoxMethod::kPpcc, BoxCoxMethod::kMle}) {
    EXPECT_NEAR(box_cox_lambda(y, method).lambda, box_cox_lambda(scaled, method).lambda, 1e-7);
  }
  // the log-likelihood shifts by exactly -n log 1024 under the scaling
  EXPECT_NEAR(box_cox_log_likelihood(scaled, 0.3) - box_cox_log_likelihood(y, 0.3),
              -150 * std::log(1024.0), 1e-9);
}

// A range that excludes the optimum: the end of the range is returned and flagged.
TEST(BoxCoxSearch, OptimumOutsideTheRangeIsFlagged) {
  const auto x = testing::lognormal_sample(300, 0, 1, 54);  // lambda near 0
  BoxCoxOptions o;
  o.lambda_min = 0.5;
  o.lambda_max = 2;
  const BoxCoxResult r = box_cox_lambda(x, BoxCoxMethod::kMle, o);
  ASSERT_TRUE(r.applicable);
  EXPECT_TRUE(r.at_boundary);
  EXPECT_EQ(r.lambda, 0.5);
  EXPECT_FALSE(box_cox_lambda(x, BoxCoxMethod::kMle).at_boundary);
}

// SciPy on the same data:
// - scipy.special.boxcox (transform), scipy.stats.probplot (Filliben medians, and r of the normal
//   probability plot of the transformed data = our PPCC objective), scipy.stats.boxcox_llf (our
//   log-likelihood): same formulas at fixed lambdas, compared to 1e-10 relative;
// - scipy.stats.boxcox_normmax(method='pearsonr') (maximises the same Filliben PPCC) and
//   (method='mle'): both found by an iterative optimiser (SciPy: Brent from the bracket (-2, 2),
//   xtol 1.5e-8; ours: grid + Brent to sqrt(eps)). The objectives are flat at the optimum, so
//   lambda agrees to about sqrt(eps) times its curvature scale: compared to 1e-6 absolute, and the
//   objective values at the two lambdas to 1e-12 relative.
TEST(BoxCoxScipy, AgreesWithScipy) {
  auto zeros = testing::exponential_sample(60, 1, 64);
  for (std::size_t i = 0; i < 6; ++i) zeros[i] = 0;
  std::vector<std::vector<double>> samples{
      testing::lognormal_sample(120, 0, 1, 61),                 // lambda near 0
      testing::exponential_sample(200, 2, 62),                  // lambda near 0.27
      testing::plus(testing::normal_sample(90, 0, 1, 63), 10),  // lambda near 1
      zeros,                                                    // shifted by 1 (Dataplot)
      testing::lognormal_sample(25, 2, 0.3, 65),                // small n
      testing::lognormal_sample(2000, -1, 0.2, 66),
  };
  const std::vector<double> lambdas{-2, -1, -0.5, -1e-3, 0, 0.25, 0.5, 1, 2};
  nlohmann::json input = nlohmann::json::array();
  std::vector<std::vector<double>> prepared;  // what SciPy sees: the data after the shift
  for (const auto& x : samples) {
    const double shift = box_cox_shift(x);
    std::vector<double> y = x;
    if (shift != 0) {
      const double lowest = *std::min_element(x.begin(), x.end());
      for (auto& v : y) v = (v - lowest) + 1;
    }
    prepared.push_back(y);
    input.push_back({{"x", y}, {"lambdas", lambdas}});
  }
  const nlohmann::json ref = testing::run_scipy(R"(
st = scipy.stats
out = []
for case in inp:
    x = np.array(case['x'])
    r = {'osm': [float(v) for v in st.probplot(x, dist='norm', fit=False)[0]],
         'ppcc': [], 'llf': [], 'transform_first': []}
    for l in case['lambdas']:
        r['ppcc'].append(float(st.probplot(st.boxcox(x, l), dist='norm')[1][2]))
        r['llf'].append(float(st.boxcox_llf(l, x)))
        r['transform_first'].append(float(scipy.special.boxcox(x[0], l)))
    lp = float(st.boxcox_normmax(x, method='pearsonr'))
    lm = float(st.boxcox_normmax(x, method='mle'))
    r['lambda_ppcc'] = lp
    r['lambda_mle'] = lm
    out.append(r)
)",
                                                input);
  double worst_objective = 0;
  double worst_lambda = 0;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const auto& x = samples[i];
    const auto& y = prepared[i];
    const auto& r = ref.at(i);
    const std::string tag = "sample " + std::to_string(i) + " ";

    const auto medians = normal_order_statistic_medians(y.size());
    for (std::size_t k = 0; k < medians.size(); ++k) {
      EXPECT_NEAR(medians[k], r["osm"][k].get<double>(), 1e-12) << tag << "median " << k;
    }
    for (std::size_t j = 0; j < lambdas.size(); ++j) {
      const double ppcc = box_cox_ppcc(y, lambdas[j]);
      const double llf = box_cox_log_likelihood(y, lambdas[j]);
      const double d1 = relative_difference(ppcc, r["ppcc"][j]);
      const double d2 = relative_difference(llf, r["llf"][j]);
      worst_objective = std::max({worst_objective, d1, d2});
      EXPECT_LT(d1, 1e-10) << tag << "PPCC at " << lambdas[j] << ": " << ppcc << " vs "
                           << r["ppcc"][j];
      EXPECT_LT(d2, 1e-10) << tag << "log-likelihood at " << lambdas[j] << ": " << llf << " vs "
                           << r["llf"][j];
      EXPECT_LT(relative_difference(box_cox_transform(y[0], lambdas[j]), r["transform_first"][j]),
                1e-13)
          << tag << "transform at " << lambdas[j];
    }

    const BoxCoxResult p = box_cox_lambda(x, BoxCoxMethod::kPpcc);
    const BoxCoxResult m = box_cox_lambda(x, BoxCoxMethod::kMle);
    ASSERT_TRUE(p.applicable && m.applicable) << tag << p.reason << m.reason;
    const double lp = r["lambda_ppcc"];
    const double lm = r["lambda_mle"];
    worst_lambda = std::max({worst_lambda, std::fabs(p.lambda - lp), std::fabs(m.lambda - lm)});
    std::printf("  %slambda PPCC %.9f (SciPy %.9f)  MLE %.9f (SciPy %.9f)\n", tag.c_str(), p.lambda,
                lp, m.lambda, lm);
    EXPECT_NEAR(p.lambda, lp, 1e-6) << tag << "PPCC lambda";
    EXPECT_NEAR(m.lambda, lm, 1e-6) << tag << "MLE lambda";
    // ours is at least as good an optimum as SciPy's, up to rounding
    EXPECT_GE(p.objective, box_cox_ppcc(y, lp) - 1e-12 * std::fabs(p.objective)) << tag;
    EXPECT_GE(m.objective, box_cox_log_likelihood(y, lm) - 1e-12 * std::fabs(m.objective)) << tag;
    EXPECT_DOUBLE_EQ(p.ppcc_at_lambda, p.objective);
  }
  std::printf(
      "  Box-Cox vs SciPy: objectives worst relative difference %.2g; lambdas worst "
      "absolute difference %.2g\n",
      worst_objective, worst_lambda);
}

}  // namespace
}  // namespace ra::stats
