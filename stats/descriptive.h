// Descriptive statistics of one sample: mean, standard deviation, quantiles, box-plot numbers,
// trimmed mean. NIST/SEMATECH e-Handbook of Statistical Methods, sections 1.3.5.1 (measures of
// location), 1.3.5.6 (measures of scale), 1.3.3.7 (box plot) and 7.2.6.2 (percentiles).
//
// Conventions:
// - All results are in the units of the data, except counts.
// - Quantiles default to Hyndman-Fan definition 6 (position p(n+1), linear interpolation between
//   order statistics), the convention of the NIST e-Handbook (section 7.2.6.2) and of its software
//   Dataplot, which the authors of the audit paper used. Definition 7 (position 1 + p(n-1)) is R's
//   and NumPy's default and is offered for comparison with those tools.
// - Non-finite values (NaN, +-Inf) are rejected with std::invalid_argument: a NaN in a report must
//   come from a deliberate decision, never from arithmetic on bad input. Callers turn the exception
//   into a located message (ra::util::UserError) where they know the file and line.
// - Mean and standard deviation are accurate on data with many constant leading digits (NIST StRD
//   NUMACC1-4): the data are shifted by their first value, summed with compensation, and the mean
//   is corrected by a second pass over the residuals.
#pragma once

#include <cstddef>
#include <vector>

namespace ra::stats {

// How a quantile is interpolated between order statistics (Hyndman and Fan, 1996).
enum class QuantileDefinition {
  kHyndmanFan6,  // position h = p(n+1): NIST e-Handbook / Dataplot; NumPy method='weibull'
  kHyndmanFan7,  // position h = 1 + p(n-1): R type 7, NumPy method='linear' (default)
};

// Human-readable name of a definition ("hyndman_fan_6" / "hyndman_fan_7"), for reports and JSON.
const char* quantile_definition_name(QuantileDefinition definition);

// Throws std::invalid_argument naming `what` and the index of the first non-finite value, if any.
void require_finite(const std::vector<double>& values, const char* what);

// Mean of `values` (units of the data). Shifted, compensated, corrected sum: accurate to a few ulps
// on data like 1e13 + small integers. Throws std::invalid_argument when empty or non-finite.
double mean(const std::vector<double>& values);

// Mean and sample variance (denominator n - 1) computed together; see mean_and_variance().
struct MeanVariance {
  double mean = 0;      // units of the data
  double variance = 0;  // units of the data, squared; 0 when n = 1 (no spread can be estimated).
                        // inf (or 0) when sd^2 leaves the double range (sd above 1.3e154 or
                        // below 1e-162): use `sd`, which is always right, or scaled_variance
  double sd = 0;        // units of the data: sqrt(variance), computed without squaring the data
  double scaled_variance = 0;  // variance / 4^scale_exponent, always representable
  int scale_exponent = 0;      // the data were divided by 2^scale_exponent (scale_exponent())
};

// A power of two 2^e with every |x| / 2^e below 1 (e = 0 when all values are 0). Dividing by it is
// exact, and squares and sums of the scaled values can neither overflow nor underflow, so the
// statistics hold across the whole double range (1e-300 to 1e308); values that underflow when
// scaled are below one ulp of the largest and change no result.
int scale_exponent(const std::vector<double>& values);
int scale_exponent(const std::vector<std::vector<double>>& groups);
// values x 2^-e, exactly.
std::vector<double> scaled(const std::vector<double>& values, int e);

// Mean and sample variance (denominator n - 1) of the values scaled by scale_exponent, by the
// corrected two-pass algorithm (Chan, Golub and LeVeque 1983): sum of squared residuals minus (sum of residuals)^2 / n. Variance of a single
// value is reported as 0, not NaN; callers that need a spread estimate must check n >= 2
// themselves. Throws std::invalid_argument when empty or non-finite.
MeanVariance mean_and_variance(const std::vector<double>& values);

// Sorts the values ascending unless they already are: the analysis keeps its samples sorted, and
// checking costs one pass where sorting a sorted vector costs many.
void sort_ascending(std::vector<double>& values);
// The values of two samples together, ascending: merged when both are ascending, else sorted.
std::vector<double> merged_ascending(const std::vector<double>& a, const std::vector<double>& b);

// Quantile p (0 <= p <= 1) of `sorted` (ascending, finite, non-empty) by the given definition.
// Positions outside [1, n] are clamped to the first / last order statistic (as Dataplot and NumPy
// do). Units of the data. Throws std::invalid_argument on an empty vector or p outside [0, 1].
double quantile_sorted(const std::vector<double>& sorted, double p,
                       QuantileDefinition definition = QuantileDefinition::kHyndmanFan6);

// The same of unsorted values (sorted here, on a copy); median = quantile 0.5 (every definition
// agrees on it). Throw std::invalid_argument when empty, like quantile_sorted.
double quantile(std::vector<double> values, double p,
                QuantileDefinition definition = QuantileDefinition::kHyndmanFan6);
double median(std::vector<double> values);
// The median, or NaN for no values (e.g. a timer that measured nothing); never throws.
double median_or_nan(std::vector<double> values);

// Summary of one sample. All fields but n are in the units of the data.
struct Description {
  std::size_t n = 0;  // number of values
  double mean = 0;
  double sd = 0;      // sample standard deviation, denominator n - 1; 0 when n = 1 (undefined)
  double median = 0;  // quantile 0.5
  double q1 = 0;      // quantile 0.25 (lower quartile)
  double q3 = 0;      // quantile 0.75 (upper quartile)
  double iqr = 0;     // q3 - q1
  double min = 0;
  double max = 0;
};

// Describes `values` (taken by value: they are sorted in place). n = 1 gives sd = 0 and all
// quantiles equal to the value. Throws std::invalid_argument when empty or non-finite.
Description describe(std::vector<double> values,
                     QuantileDefinition definition = QuantileDefinition::kHyndmanFan6);

// Number of values cut from each end by a trimmed mean: floor(proportion * n), as in SciPy's
// trim_mean / levene(center='trimmed') and the e-Handbook's trimmed mean (section 1.3.5.1).
std::size_t trimmed_count(std::size_t n, double proportion);

// Mean of `values` after removing floor(proportion * n) values from each end of the sorted sample.
// proportion in [0, 0.5); the mean of what is left (at least one value). Units of the data.
// Throws std::invalid_argument when empty, non-finite or proportion outside [0, 0.5).
double trimmed_mean(std::vector<double> values, double proportion);

// The numbers a box plot draws (e-Handbook 1.3.3.7): quartiles, Tukey's fences at 1.5 IQR beyond
// the quartiles, whiskers at the most extreme data inside the fences, and the points outside.
struct BoxPlotData {
  double lower_whisker = 0;  // smallest value >= lower_fence
  double q1 = 0;
  double median = 0;
  double q3 = 0;
  double upper_whisker = 0;  // largest value <= upper_fence
  double lower_fence = 0;    // q1 - 1.5 * iqr
  double upper_fence = 0;    // q3 + 1.5 * iqr
  std::size_t n = 0;
  std::size_t n_outliers_low = 0;   // values < lower_fence
  std::size_t n_outliers_high = 0;  // values > upper_fence
  // The outside values, ascending; at most `max_outliers` of them (the most extreme ones: taken
  // alternately from both ends), so a sample of millions cannot make a plot file explode.
  std::vector<double> outliers;
  bool outliers_truncated = false;  // true when outliers holds fewer than n_outliers_low + _high
};

// Box-plot numbers of `values` (sorted in place). Quartiles by `definition` (the default, HF6, is
// Dataplot's; Tukey's original hinges, medians of the two halves, differ slightly for small n).
// Throws std::invalid_argument when empty or non-finite.
BoxPlotData box_plot(std::vector<double> values,
                     QuantileDefinition definition = QuantileDefinition::kHyndmanFan6,
                     std::size_t max_outliers = 1000);

}  // namespace ra::stats
