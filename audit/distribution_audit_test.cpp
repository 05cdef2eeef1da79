// Distribution tests of an audit: Holm's adjustment, which tests run, effect sizes, class counts.
#include "audit/distribution_audit.h"

#include <gtest/gtest.h>

#include "audit/audit_testing.h"

namespace ra::audit {
namespace {

using testing::experiment_text;
using testing::fresh_dir;
using testing::point_record;
using testing::write_points;
using testing::write_run;

// R: p.adjust(c(0.01, 0.04, 0.03, 0.005), "holm") = 0.03 0.06 0.06 0.02 (the third is raised to
// the running maximum: step-down monotonicity).
TEST(HolmAdjust, MatchesR) {
  const std::vector<double> adj = holm_adjust({0.01, 0.04, 0.03, 0.005});
  ASSERT_EQ(adj.size(), 4u);
  EXPECT_DOUBLE_EQ(adj[0], 0.03);
  EXPECT_DOUBLE_EQ(adj[1], 0.06);
  EXPECT_DOUBLE_EQ(adj[2], 0.06);
  EXPECT_DOUBLE_EQ(adj[3], 0.02);
  EXPECT_DOUBLE_EQ(holm_adjust({0.4, 0.9})[1], 0.9);  // R: 0.8 0.9
  EXPECT_DOUBLE_EQ(holm_adjust({0.6, 0.9})[0], 1.0);  // 2 x 0.6, capped at 1
  EXPECT_DOUBLE_EQ(holm_adjust({0.6, 0.9})[1], 1.0);  // raised to the running maximum
  EXPECT_TRUE(holm_adjust({}).empty());
}

// Two runs of 400 points in two orientation views (one group): PE uniform-ish in (0, 0.7) in the
// baseline; in the current run `shift` is added to every value. Returns the loaded records.
struct TwoRuns {
  analysis::RunRecords baseline, current;
};
TwoRuns make_runs(const std::string& tag, double shift, double offset = 0.01) {
  const std::string a = fresh_dir(tag + "_a"), b = fresh_dir(tag + "_b");
  const std::string text = experiment_text("\"reference\"", 400, 400, 5, 2);
  const rundir::Experiment exp = write_run(a, text);
  write_run(b, text);
  auto pe = [&](uint64_t i) { return offset + 0.7 * double((i * 37) % 400) / 400.0; };
  write_points(a, exp, "reference",
               [&](int v, uint64_t i) { return point_record(exp, "reference", v, i, i, pe(i)); });
  write_points(b, exp, "reference", [&](int v, uint64_t i) {
    return point_record(exp, "reference", v, i, i, pe(i) + shift);
  });
  return {analysis::load_run_records(a, {1}), analysis::load_run_records(b, {1})};
}

const DistributionComparison& find(const DistributionAudit& d, const char* metric) {
  for (const auto& c : d.comparisons)
    if (analysis::kind_metrics(c.kind)[c.metric].column == std::string(metric)) return c;
  throw std::logic_error("no comparison of that metric");
}

TEST(DistributionAudit, IdenticalSamplesAreNotSignificant) {
  const TwoRuns runs = make_runs("same", 0);
  const DistributionAudit d =
      audit_distributions(runs.baseline, runs.current, {{"reference", "reference"}}, 0.05, 1);
  ASSERT_EQ(d.comparisons.size(), 2u);  // pe and pe_norm of group A
  EXPECT_EQ(d.significant, 0u);
  EXPECT_EQ(d.family_size, 8u);  // Welch + Levene, raw + Box-Cox, two metrics
  const DistributionComparison& pe = find(d, "pe");
  EXPECT_EQ(pe.n_before, 800u);
  EXPECT_DOUBLE_EQ(pe.median_difference(), 0);
  EXPECT_DOUBLE_EQ(pe.iqr_difference(), 0);
  EXPECT_TRUE(pe.box_cox.applicable);
}

// A shift of 0.2 px in every PE: Welch finds it (raw and Box-Cox), Levene on raw data does not (the
// spread is unchanged); the effect sizes are the shift and 0.
TEST(DistributionAudit, AShiftIsFoundWithItsEffectSize) {
  const TwoRuns runs = make_runs("shift", 0.2);
  const DistributionAudit d =
      audit_distributions(runs.baseline, runs.current, {{"reference", "reference"}}, 0.05, 1);
  const DistributionComparison& pe = find(d, "pe");
  EXPECT_NEAR(pe.median_difference(), 0.2, 1e-12);
  EXPECT_NEAR(pe.iqr_difference(), 0, 1e-12);
  ASSERT_EQ(pe.tests.size(), 4u);
  EXPECT_EQ(pe.tests[0].test, "welch_t");
  EXPECT_EQ(pe.tests[0].data, "raw");
  EXPECT_TRUE(pe.tests[0].significant);
  EXPECT_GE(pe.tests[0].p_adjusted, pe.tests[0].outcome.p_value);
  EXPECT_EQ(pe.tests[1].test, "levene_median");
  EXPECT_FALSE(pe.tests[1].significant);
  EXPECT_EQ(pe.tests[2].data, "box_cox");
  EXPECT_TRUE(pe.tests[2].significant);
  EXPECT_TRUE(pe.significant());
  EXPECT_GE(d.significant, 2u);
}

// Zeros in the data: no Box-Cox (the transform needs y > 0), said with the reason.
TEST(DistributionAudit, BoxCoxOnlyOnPositiveData) {
  const TwoRuns runs = make_runs("zeros", 0, 0.0);
  const DistributionAudit d =
      audit_distributions(runs.baseline, runs.current, {{"reference", "reference"}}, 0.05, 1);
  const DistributionComparison& pe = find(d, "pe");
  EXPECT_FALSE(pe.box_cox.applicable);
  EXPECT_FALSE(pe.tests[2].outcome.defined);
  EXPECT_NE(pe.tests[2].outcome.reason.find("y > 0"), std::string::npos)
      << pe.tests[2].outcome.reason;
  EXPECT_EQ(d.family_size, 4u);  // raw tests only
}

TEST(DistributionAudit, ClassCountsOfBothSides) {
  const TwoRuns runs = make_runs("classes", 0);
  const auto classes =
      compare_class_counts(runs.baseline, runs.current, {{"reference", "reference"}});
  ASSERT_EQ(classes.size(), 8u);  // five classes and three statuses of group A
  EXPECT_EQ(classes[0].visibility, "true-visible");
  EXPECT_EQ(classes[0].before, 800u);
  EXPECT_EQ(classes[0].after, 800u);
  EXPECT_EQ(classes[7].visibility, "timeout");
}

}  // namespace
}  // namespace ra::audit
