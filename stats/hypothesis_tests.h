// Tests that compare samples: two-sample t tests (pooled and Welch), the F test for equal
// variances, Levene's test (mean, median and trimmed-mean centres) and one-way ANOVA.
// NIST/SEMATECH e-Handbook of Statistical Methods: 1.3.5.3 (two-sample t test), 1.3.5.9 (F test),
// 1.3.5.10 (Levene test), 1.3.5.4 and 7.4.3 (one-way ANOVA); the audit paper uses them in section 4
// to decide whether views that differ only in camera orientation are equivalent.
//
// Conventions:
// - p-values come from Boost.Math distributions; upper tails are taken with complement(), so very
//   small p-values (1e-300) keep their relative accuracy instead of rounding to 0 as 1 - cdf would.
// - Sums of squares are formed from residuals about accurately computed means (descriptive.h), so
//   data with many constant leading digits (NIST StRD SmLs04-09) keep their precision.
// - Degenerate input (too few values, zero variance where a ratio needs it, non-finite values)
//   throws std::invalid_argument with the reason; the statistic would be Inf or NaN. Callers that
//   report several tests catch it per test and print the reason instead of a number.
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

namespace ra::stats {

// Result of a two-sample t test for equal means (H0: mean1 = mean2).
struct TTestResult {
  double statistic = 0;             // t = (mean1 - mean2) / standard_error (dimensionless)
  double df = 0;                    // degrees of freedom (n1 + n2 - 2 pooled; Welch-Satterthwaite)
  double p_value = 1;               // two-sided: P(|T| >= |t|)
  double mean_difference = 0;       // mean1 - mean2, units of the data
  double standard_error = 0;        // of the mean difference, units of the data
  std::optional<double> pooled_sd;  // pooled test only: sp, units of the data
};

// Student's two-sample t test assuming equal variances (e-Handbook 1.3.5.3):
// sp^2 = ((n1-1)s1^2 + (n2-1)s2^2)/(n1+n2-2), t = (m1-m2)/(sp sqrt(1/n1 + 1/n2)).
// Needs n1, n2 >= 1 and n1 + n2 >= 3. Throws std::invalid_argument when both samples are constant
// (t undefined), too small or non-finite.
TTestResult t_test_pooled(const std::vector<double>& sample1, const std::vector<double>& sample2);

// Welch's t test, variances not assumed equal (e-Handbook 1.3.5.3): t = (m1-m2)/sqrt(s1^2/n1 +
// s2^2/n2), df by Welch-Satterthwaite. Needs n1, n2 >= 2. Throws std::invalid_argument when both
// samples are constant, too small or non-finite.
TTestResult t_test_welch(const std::vector<double>& sample1, const std::vector<double>& sample2);

// Result of a test whose statistic follows an F distribution under H0.
struct FTestResult {
  double statistic = 0;  // F (dimensionless)
  double df1 = 0;        // numerator degrees of freedom
  double df2 = 0;        // denominator degrees of freedom
  double p_value = 1;    // see the function that produced it for the tail(s)
};

// F test for equal variances (e-Handbook 1.3.5.9): F = s1^2 / s2^2 with (n1-1, n2-1) df; two-sided
// p = 2 min(P(F' <= F), P(F' >= F)), at most 1. Needs n1, n2 >= 2. Throws std::invalid_argument
// when sample 2 is constant (F undefined), too small or non-finite.
FTestResult f_test_variances(const std::vector<double>& sample1,
                             const std::vector<double>& sample2);

// What Levene's test measures the spread about (e-Handbook 1.3.5.10).
enum class LeveneCenter {
  kMean,    // Levene (1960)
  kMedian,  // Brown and Forsythe (1974): the e-Handbook's and Dataplot's default; robust
  // Brown and Forsythe's 10% trimmed mean (floor(0.1 n) cut from each end, as SciPy's trim_mean).
  // As in the e-Handbook's formula, the deviations of *all* values from it enter the test.
  // note: scipy.stats.levene(center='trimmed') instead drops the trimmed values from the test
  // itself (its df2 = trimmed N - k); the two agree only when nothing is trimmed (every n < 10).
  kTrimmedMean,
};

// Name for reports and JSON: "mean", "median", "trimmed_mean".
const char* levene_center_name(LeveneCenter center);

// Levene's test for equal variances of k >= 2 groups (e-Handbook 1.3.5.10): the one-way ANOVA F of
// z_ij = |y_ij - centre_i|. statistic = W, df1 = k - 1, df2 = N - k, p = P(F' >= W) (upper tail).
// Each group needs at least 1 value and N > k. Throws std::invalid_argument when every z_ij equals
// its group mean (W undefined), on too few values or non-finite values.
FTestResult levene_test(const std::vector<std::vector<double>>& groups,
                        LeveneCenter center = LeveneCenter::kMedian);

// One-way analysis of variance of k groups (e-Handbook 1.3.5.4, 7.4.3; NIST StRD ANOVA).
struct AnovaResult {
  std::size_t k = 0;       // number of groups
  std::size_t n = 0;       // number of values in all groups
  double df_between = 0;   // k - 1
  double df_within = 0;    // n - k
  double ss_between = 0;   // sum_i n_i (mean_i - grand mean)^2, units of the data squared
  double ss_within = 0;    // sum_ij (y_ij - mean_i)^2, units of the data squared
  double ms_between = 0;   // ss_between / df_between
  double ms_within = 0;    // ss_within / df_within
  double f = 0;            // ms_between / ms_within (dimensionless)
  double p_value = 1;      // P(F' >= f), upper tail of F(df_between, df_within)
  double r_squared = 0;    // ss_between / (ss_between + ss_within), in [0, 1]
  double residual_sd = 0;  // sqrt(ms_within), units of the data
};

// One-way ANOVA (fixed effects) of `groups`. Needs k >= 2, every group non-empty and n > k.
// Throws std::invalid_argument when ss_within = 0 (F undefined), on too few values or non-finite
// values.
AnovaResult one_way_anova(const std::vector<std::vector<double>>& groups);

}  // namespace ra::stats
