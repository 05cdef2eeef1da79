// Tests of the view-equivalence procedure: the test battery on raw and Box-Cox data, the decision
// rule (location t / ANOVA and Levene median on raw data), pairs made deliberately not equivalent,
// degenerate samples without NaN, and the reports.
#include "analysis/view_equivalence.h"
#include "analysis/view_equivalence_report.h"

#include <gtest/gtest.h>

#include "stats/box_cox.h"
#include "stats/hypothesis_tests.h"
#include "analysis/records_testing.h"

namespace ra::analysis {
namespace {

using stats::testing::normal_sample;
using testing::point;
using testing::write_records;

std::vector<double> uniform_sample(std::size_t n, double lo, double hi, std::uint64_t seed) {
  stats::testing::Generator g(seed);
  std::vector<double> v(n);
  for (double& x : v) x = lo + (hi - lo) * g.uniform();
  return v;
}

TEST(ViewEquivalence, BatteryMatchesTheLibrary) {
  const auto a = normal_sample(300, 5, 1, 1), b = normal_sample(200, 5.1, 1.2, 2);
  const SampleComparison c = compare_samples({a, b});
  EXPECT_EQ(c.n, (std::vector<std::size_t>{300, 200}));
  EXPECT_EQ(c.raw.location_name, "t (pooled)");
  EXPECT_DOUBLE_EQ(c.raw.location.p_value, stats::t_test_pooled(a, b).p_value);
  EXPECT_DOUBLE_EQ(c.raw.welch.p_value, stats::t_test_welch(a, b).p_value);
  EXPECT_DOUBLE_EQ(c.raw.f_test.p_value, stats::f_test_variances(a, b).p_value);
  EXPECT_DOUBLE_EQ(c.raw.levene_median.statistic,
                   stats::levene_test({a, b}, stats::LeveneCenter::kMedian).statistic);
  EXPECT_DOUBLE_EQ(c.raw.levene_mean.p_value,
                   stats::levene_test({a, b}, stats::LeveneCenter::kMean).p_value);
  // Box-Cox: lambda of the pooled data (all positive, n < subsample: every value), same lambda for
  // both samples
  std::vector<double> pooled = a;
  pooled.insert(pooled.end(), b.begin(), b.end());
  ASSERT_TRUE(c.box_cox.applicable);
  EXPECT_FALSE(c.box_cox.shifted);
  EXPECT_EQ(c.box_cox.n_fit, 500u);
  stats::BoxCoxOptions grid;
  grid.grid_points = 41;
  EXPECT_NEAR(c.box_cox.lambda,
              stats::box_cox_lambda(pooled, stats::BoxCoxMethod::kPpcc, grid).lambda, 1e-9);
  const auto ta = stats::box_cox_transform(a, c.box_cox.lambda);
  const auto tb = stats::box_cox_transform(b, c.box_cox.lambda);
  EXPECT_DOUBLE_EQ(c.transformed.location.p_value, stats::t_test_pooled(ta, tb).p_value);
  EXPECT_DOUBLE_EQ(c.transformed.levene_median.p_value,
                   stats::levene_test({ta, tb}, stats::LeveneCenter::kMedian).p_value);
}

TEST(ViewEquivalence, ThreeOrientationsUseAnova) {
  const auto a = normal_sample(100, 1, 1, 3), b = normal_sample(100, 1, 1, 4),
             c = normal_sample(100, 1, 1, 5);
  const SampleComparison r = compare_samples({a, b, c});
  EXPECT_EQ(r.raw.location_name, "one-way ANOVA");
  EXPECT_DOUBLE_EQ(r.raw.location.p_value, stats::one_way_anova({a, b, c}).p_value);
  EXPECT_FALSE(r.raw.welch.defined);
  EXPECT_FALSE(r.raw.f_test.defined);
  EXPECT_NE(r.raw.f_test.reason.find("two samples only"), std::string::npos);
  std::string why;
  EXPECT_EQ(decide_equivalence({a, b, c}, r, 0.05, &why), Verdict::kEquivalent) << why;
}

TEST(ViewEquivalence, ShiftsDataWithZerosOrNegatives) {
  std::vector<double> a = normal_sample(400, 0, 1, 6), b = normal_sample(400, 0, 1, 7);
  a[0] = 0;
  const SampleComparison c = compare_samples({a, b});
  ASSERT_TRUE(c.box_cox.applicable);
  EXPECT_TRUE(c.box_cox.shifted);
  double lowest = 0;
  for (const auto* s : {&a, &b}) {
    for (double x : *s) lowest = std::min(lowest, x);
  }
  EXPECT_EQ(c.box_cox.pooled_min, lowest);
  EXPECT_DOUBLE_EQ(c.box_cox.shift(), 1 - lowest);
  EXPECT_TRUE(c.transformed.location.defined);
}

TEST(ViewEquivalence, SubsampleChoosesLambdaCloseToTheFullSample) {
  const auto v = stats::testing::lognormal_sample(50000, 0, 0.5, 8);
  ComparisonOptions sub;  // defaults: 10000 order statistics
  ComparisonOptions full;
  full.box_cox_subsample = v.size();
  const BoxCoxFit a = fit_box_cox(v, sub), b = fit_box_cox(v, full);
  EXPECT_EQ(a.n_fit, 10000u);
  EXPECT_EQ(b.n_fit, 50000u);
  EXPECT_NEAR(a.lambda, b.lambda, 0.01);
  EXPECT_NEAR(b.lambda, 0, 0.05);  // log-normal: lambda near 0
}

TEST(ViewEquivalence, DifferentSpreadIsNotEquivalent) {
  const auto a = uniform_sample(3000, 0.35, 0.45, 9), b = uniform_sample(3000, 0.1, 0.7, 10);
  const SampleComparison c = compare_samples({a, b});
  std::string why;
  EXPECT_EQ(decide_equivalence({a, b}, c, 0.05, &why), Verdict::kNotEquivalent);
  EXPECT_NE(why.find("spread differs"), std::string::npos) << why;
  EXPECT_NE(why.find("Levene (median) p = "), std::string::npos) << why;
}

TEST(ViewEquivalence, DifferentLocationIsNotEquivalent) {
  const auto a = normal_sample(2000, 1, 0.2, 11), b = normal_sample(2000, 1.2, 0.2, 12);
  std::string why;
  EXPECT_EQ(decide_equivalence({a, b}, compare_samples({a, b}), 0.05, &why),
            Verdict::kNotEquivalent);
  EXPECT_NE(why.find("location differs"), std::string::npos) << why;
}

TEST(ViewEquivalence, DegenerateSamplesGiveReasonsNotNaN) {
  const std::vector<double> c1(5, 0.2), c2(4, 0.2), c3(4, 0.3), empty;
  std::string why;
  SampleComparison c = compare_samples({c1, c2});
  EXPECT_FALSE(c.raw.location.defined);
  EXPECT_FALSE(c.raw.location.reason.empty());
  EXPECT_FALSE(c.box_cox.applicable);
  EXPECT_EQ(c.box_cox.reason, "all values are equal");
  EXPECT_FALSE(c.transformed.levene_median.defined);
  EXPECT_EQ(decide_equivalence({c1, c2}, c, 0.05, &why), Verdict::kEquivalent);
  EXPECT_NE(why.find("same constant 0.2"), std::string::npos) << why;
  EXPECT_EQ(decide_equivalence({c1, c3}, compare_samples({c1, c3}), 0.05, &why),
            Verdict::kNotEquivalent);
  c = compare_samples({c1, empty});
  EXPECT_EQ(decide_equivalence({c1, empty}, c, 0.05, &why), Verdict::kUndecided);
  EXPECT_EQ(decide_equivalence({empty, empty}, compare_samples({empty, empty}), 0.05, &why),
            Verdict::kNoComparison);
  EXPECT_EQ(decide_equivalence({c1}, SampleComparison{}, 0.05, &why), Verdict::kNoComparison);
  EXPECT_EQ(p_value_cell(c.raw.location).text, "undefined");
}

// A run with a deliberately non-equivalent pair: view group A equivalent (same distribution),
// group B not (view 4 has three times the spread of view 3).
TEST(ViewEquivalence, RunReportSaysWhichPairIsNotEquivalentAndPools) {
  const testing::ScopedTempDir scoped("equivalence_run");
  const std::filesystem::path& dir = scoped.path;
  std::vector<metrics::Record> rs;
  std::uint64_t i = 0;
  for (double x : uniform_sample(2000, 0, 0.7, 20)) rs.push_back(point("p", 1, i++, x));
  for (double x : uniform_sample(2000, 0, 0.7, 21)) rs.push_back(point("p", 2, i++, x));
  for (double x : uniform_sample(2000, 0.3, 0.5, 22)) rs.push_back(point("p", 3, i++, x));
  for (double x : uniform_sample(2000, 0.1, 0.7, 23)) rs.push_back(point("p", 4, i++, x));
  write_records(dir, rs);
  const RunRecords run = load_run_records(dir.string());
  EquivalenceOptions o;
  const auto results = assess_view_equivalence(run, o);
  ASSERT_EQ(results.size(), 4u);  // 2 metrics x 2 groups
  const ViewEquivalence& a = results[0];
  EXPECT_EQ(a.label, "A");
  EXPECT_EQ(a.views, (std::vector<int>{1, 2}));
  EXPECT_EQ(a.verdict, Verdict::kEquivalent) << a.explanation;
  const ViewEquivalence& b = results[1];
  EXPECT_EQ(b.label, "B");
  EXPECT_EQ(b.verdict, Verdict::kNotEquivalent);
  EXPECT_NE(b.explanation.find("spread differs"), std::string::npos) << b.explanation;

  const std::string md = view_equivalence_markdown(run, results, o);
  EXPECT_NE(md.find("- **NOT equivalent**: p, points, PE, view group B (views 3, 4): spread "
                    "differs"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("pooled into view groups anyway"), std::string::npos) << md;
  EXPECT_NE(md.find("trusted Levene"), std::string::npos);
  const std::string csv = stats::render_csv(view_equivalence_table(run, results, o));
  EXPECT_NE(csv.find("p,point,pe,B,3;4,1;2,2000; 2000"), std::string::npos) << csv.substr(0, 2000);
  EXPECT_EQ(csv.find("nan"), std::string::npos);
}


// One orientation per view group (views 1 and 3 of Table 1): nothing is pooled or tested, and the
// file says so in one paragraph, with no table of "undefined" rows and no claim that the views
// were found equivalent.
TEST(ViewEquivalence, OneOrientationPerGroupSaysNothingWasTested) {
  const testing::ScopedTempDir scoped("equivalence_one_orientation");
  std::vector<metrics::Record> rs;
  std::uint64_t i = 0;
  for (double x : uniform_sample(500, 0, 0.7, 30)) rs.push_back(point("p", 1, i++, x));
  for (double x : uniform_sample(500, 0, 0.7, 31)) rs.push_back(point("p", 3, i++, x));
  write_records(scoped.path, rs);
  const RunRecords run = load_run_records(scoped.path.string());
  EquivalenceOptions o;
  const auto results = assess_view_equivalence(run, o);
  ASSERT_FALSE(results.empty());
  for (const ViewEquivalence& r : results) EXPECT_EQ(r.verdict, Verdict::kNoComparison);
  const std::string md = view_equivalence_markdown(run, results, o);
  EXPECT_NE(md.find("one camera orientation per view group"), std::string::npos) << md;
  EXPECT_EQ(md.find("found the orientation views equivalent"), std::string::npos) << md;
  EXPECT_EQ(md.find("undefined"), std::string::npos) << md;
  EXPECT_EQ(md.find('|'), std::string::npos) << md;  // no table
}

}  // namespace
}  // namespace ra::analysis
