// Are views that differ only by camera orientation equivalent? The paper (section 4, p. 228):
// "We used the usual t tests and F tests to try to confirm that these pairs of camera orientation
// cases were equivalent in both mean and variance for each error metric ... we supplemented the F
// test with the Levene test of variance, which is more robust for non-normal data. We applied these
// tests both to the raw data as well as to Box-Cox transformed data when possible." It then pooled
// the views into view groups A-D anyway.
//
// The battery (compare_samples), for k samples:
// - k = 2: pooled t test (location), Welch t test, F test of variances, Levene with median centre
//   (Brown-Forsythe) and with mean centre; k > 2: one-way ANOVA (location) and the two Levene
//   tests. NIST e-Handbook 1.3.5.3, 1.3.5.9, 1.3.5.10, 1.3.5.4; stats/hypothesis_tests.h.
// - The same tests on Box-Cox transformed data: lambda by maximum PPCC (e-Handbook 1.3.3.6,
//   stats/box_cox.h) on the pooled data of all k samples, the same lambda (and shift) for every
//   sample. Data with a value <= 0 are shifted first as Dataplot does: y - min + 1, min over the
//   pooled data. For speed lambda is chosen on a systematic subsample of the sorted pooled data (at
//   most `box_cox_subsample` = 10000 order statistics at ranks floor((i + 1/2) n / m), i = 0..m-1:
//   they follow the distribution's shape, which is all the PPCC looks at) with a grid of step 0.1
//   before Brent's refinement; on 200,000 values shaped like PE, TEu (with zeros), TEs and LSEs
//   this lambda is within 0.002 of the one chosen on every value with the default grid (step 0.05),
//   at a tenth of the cost (bench/analysis_bench.cpp). The tests then use every value. "Not
//   applicable" (with the reason) for fewer than 3 values or a constant (sub)sample.
// - A test that is undefined for the data (both samples constant, a sample too small) is reported
//   with its reason instead of a number; nothing here is ever NaN.
//
// The decision (decide_equivalence): the views are "equivalent" when, on the raw data, the location
// test (pooled t; ANOVA for k > 2) and Levene's test with median centre both have p >= alpha.
// Levene decides the spread, not F: the F test is not robust to non-normal data (the paper's
// reason), and these error distributions are far from normal (PE is the distance to a pixel
// centre, bounded by sqrt(2)/2; the line and triangle errors have spikes at 0). Box-Cox results
// and the F test are reported for the reader, as the paper did, but do not decide.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "stats/descriptive.h"
#include "analysis/run_records.h"

namespace ra::analysis {

// One test on one version of the data.
struct TestOutcome {
  bool defined = false;
  double statistic = 0;  // t, F or W (dimensionless)
  double df1 = 0;        // t: its df; F, W, ANOVA: numerator df
  double df2 = 0;        // F, W, ANOVA: denominator df; t: 0
  double p_value = 1;    // two-sided for t and F, upper tail for W and ANOVA
  std::string reason;    // why undefined (defined == false)
};

struct TestBattery {
  std::string location_name;  // "t (pooled)" or "one-way ANOVA"
  TestOutcome location;       // pooled t (k = 2) or one-way ANOVA F (k > 2)
  TestOutcome welch;          // Welch t; k = 2 only
  TestOutcome f_test;         // F = s1^2 / s2^2; k = 2 only
  TestOutcome levene_median;  // Brown-Forsythe
  TestOutcome levene_mean;    // Levene (1960)
};

// Box-Cox lambda chosen for pooled data, and how to apply it.
struct BoxCoxFit {
  bool applicable = false;
  std::string reason;        // why not applicable
  bool shifted = false;      // values are transformed as (y - pooled_min) + 1
  double pooled_min = 0;     // minimum of the pooled data
  double lambda = 0;         // dimensionless
  double ppcc = 0;           // correlation of the normal probability plot at lambda (subsample)
  bool at_boundary = false;  // lambda at an end of [-2, 2]
  std::size_t n = 0;         // pooled values
  std::size_t n_fit = 0;     // values lambda was chosen on
  double shift() const { return shifted ? 1 - pooled_min : 0; }  // Dataplot's shift
};

struct ComparisonOptions {
  std::size_t box_cox_subsample = 10000;  // at most this many order statistics choose lambda
  std::size_t box_cox_grid_points = 41;   // grid on [-2, 2] (step 0.1) before Brent's refinement
};

// Lambda by maximum PPCC for `pooled` (any order, any sign); see the header comment.
BoxCoxFit fit_box_cox(const std::vector<double>& pooled, const ComparisonOptions& options = {});

// T(y (+ shift); lambda) of every value. Requires fit.applicable.
std::vector<double> apply_box_cox(const std::vector<double>& values, const BoxCoxFit& fit);

struct SampleComparison {
  std::vector<std::size_t> n;  // size of each sample
  TestBattery raw;
  BoxCoxFit box_cox;
  TestBattery transformed;  // every outcome undefined, with the reason, when not applicable
};

// The battery on k >= 2 samples (std::logic_error for fewer). Samples may be empty or tiny: the
// tests that cannot run say why.
SampleComparison compare_samples(const std::vector<std::vector<double>>& samples,
                                 const ComparisonOptions& options = {});

enum class Verdict {
  kEquivalent,     // location and spread tests both p >= alpha on raw data
  kNotEquivalent,  // one of them p < alpha (or constant views with different values)
  kUndecided,      // a deciding test is undefined for the data (the reason is given)
  kNoComparison,   // fewer than two orientations, or no data at all
};
const char* verdict_name(
    Verdict v);  // "equivalent", "NOT equivalent", "undecided", "no comparison"

// The decision rule above; `explanation` says which p-values decided (or why none could).
Verdict decide_equivalence(const std::vector<std::vector<double>>& samples,
                           const SampleComparison& comparison, double alpha,
                           std::string* explanation);

// The orientation views of one platform, kind, metric and view group compared.
struct ViewEquivalence {
  std::size_t platform = 0;
  geometry::Kind kind = geometry::Kind::kPoint;
  std::size_t metric = 0;  // index into kind_metrics(kind)
  int view_group = 0;
  std::string label;  // "A", ...
  std::vector<int> views;
  std::vector<int> orientations;
  std::vector<double> medians;  // per view, units of the metric; empty view: 0 (n says it)
  std::vector<double> iqrs;
  SampleComparison comparison;
  Verdict verdict = Verdict::kNoComparison;
  std::string explanation;
};

struct EquivalenceOptions {
  double alpha = 0.05;
  stats::QuantileDefinition quantiles = stats::QuantileDefinition::kHyndmanFan6;
  ComparisonOptions comparison;
  unsigned jobs = 0;  // threads; 0: the number of cores
};

// Every platform, kind, metric and view group of the run, in that order.
std::vector<ViewEquivalence> assess_view_equivalence(const RunRecords& run,
                                                     const EquivalenceOptions& options);

}  // namespace ra::analysis
