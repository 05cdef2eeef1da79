// Per-distribution comparison of an audit: for each platform pair, kind, view group and error
// metric, the baseline sample against the current sample (true-visible `ok` records, pooled over
// the group's orientation views as in analysis/run_records.h), with
// - location: Welch's t test (variances not assumed equal: a driver change may change the spread
//   as well as the location, and the pooled t test is then miscalibrated); e-Handbook 1.3.5.3;
// - spread: Levene's test with median centre (Brown-Forsythe), robust to these far-from-normal
//   error distributions (the paper's reason to prefer it to F); e-Handbook 1.3.5.10;
// - both again on Box-Cox transformed data when every value of both samples is > 0 (the transform
//   is defined for y > 0; Dataplot's shift of non-positive data, 1 - min, would move the zeros the
//   metric means literally, e.g. TEu = 0 for a perfect triangle, so it is not used here). One
//   lambda for both samples, chosen by maximum PPCC on the pooled data (analysis/view_equivalence.h
//   fit_box_cox): the samples must be transformed alike to be compared at all; a lambda per side
//   would put them on different scales, where a t test of equal means tests nothing. The lambda is
//   reported.
// - Multiple testing: Holm-Bonferroni over every defined test of the audit (raw and Box-Cox, all
//   pairs, kinds, groups and metrics), which controls the family-wise error rate at alpha under any
//   dependence between the tests (they are strongly dependent: the same data, several metrics).
// - Effect sizes in the metric's units: difference of medians and of IQRs (current - baseline),
//   quantiles Hyndman-Fan 6 as in the rest of the analysis.
// The statistics are analysis/'s (hypothesis_tests.h, box_cox.h via view_equivalence.h); only
// Holm's step-down adjustment is new here.
//
// Also: the visibility-class counts of each group on both sides (records with status `ok`; crash,
// timeout and invalid records counted as their status).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "analysis/run_records.h"
#include "analysis/view_equivalence.h"
#include "audit/audit_compare.h"

namespace ra::audit {

// One test of one comparison.
struct DistributionTest {
  std::string test;               // "welch_t" or "levene_median"
  std::string data;               // "raw" or "box_cox"
  analysis::TestOutcome outcome;  // statistic, df, p-value (two-sided t; upper-tail W), or reason
  double p_adjusted = 1;          // Holm-adjusted p-value (defined tests only), in [0, 1]
  bool significant = false;       // p_adjusted < alpha
};

// Baseline against current for one pair, kind, view group and metric.
struct DistributionComparison {
  std::size_t pair = 0;
  geometry::Kind kind = geometry::Kind::kPoint;
  int view_group = 0;      // 0 = A
  std::string label;       // "A", ...
  std::size_t metric = 0;  // index into analysis::kind_metrics(kind)
  std::size_t n_before = 0, n_after = 0;
  // HF6 median and IQR, metric units; NaN when the sample is empty.
  double median_before = metrics::kNA, median_after = metrics::kNA, iqr_before = metrics::kNA,
         iqr_after = metrics::kNA;
  double median_difference() const { return median_after - median_before; }
  double iqr_difference() const { return iqr_after - iqr_before; }
  analysis::BoxCoxFit box_cox;  // lambda of the pooled data; applicable only when all values > 0
  std::vector<DistributionTest> tests;  // raw Welch, raw Levene, Box-Cox Welch, Box-Cox Levene
  bool significant() const;
};

struct DistributionAudit {
  double alpha = 0.05;
  std::size_t family_size = 0;                      // defined tests Holm corrected for
  std::size_t significant = 0;                      // tests with p_adjusted < alpha
  std::vector<DistributionComparison> comparisons;  // by pair, kind, view group, metric
};

// Holm-Bonferroni (Holm 1979) adjusted p-values, in the input's order: with p sorted ascending,
// adjusted_(i) = max over j <= i of min(1, (m - j + 1) p_(j)), i = 1..m. Rejecting where the
// adjusted value is < alpha is Holm's step-down procedure at level alpha.
std::vector<double> holm_adjust(const std::vector<double>& p_values);

// The tests above for every pair, kind, view group (present on either side) and metric. Groups
// with no values on either side are left out. `jobs` threads (0: the number of cores).
DistributionAudit audit_distributions(const analysis::RunRecords& baseline,
                                      const analysis::RunRecords& current,
                                      const std::vector<PlatformPair>& pairs, double alpha,
                                      unsigned jobs = 0);

// Visibility-class (and non-ok status) counts of one pair, kind and view group on both sides.
struct ClassCountChange {
  std::size_t pair = 0;
  geometry::Kind kind = geometry::Kind::kPoint;
  int view_group = 0;
  std::string label;
  std::string visibility;  // "true-visible", ..., or "invalid", "crash", "timeout"
  uint64_t before = 0, after = 0;
};

// Every class of every pair, kind and view group present on either side (unchanged ones included).
std::vector<ClassCountChange> compare_class_counts(const analysis::RunRecords& baseline,
                                                   const analysis::RunRecords& current,
                                                   const std::vector<PlatformPair>& pairs);

// Class counts of one view group (by class name, the records' spelling, then the statuses).
std::vector<std::pair<std::string, uint64_t>> class_counts(const analysis::VisibilityCounts& c);

// The index of `platform` in run.platforms, or run.platforms.size() when absent.
std::size_t platform_index(const analysis::RunRecords& run, const std::string& platform);

}  // namespace ra::audit
