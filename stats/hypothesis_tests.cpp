// Two-sample and k-sample tests; see hypothesis_tests.h. e-Handbook 1.3.5.3, 1.3.5.9, 1.3.5.10,
// 1.3.5.4 and 7.4.3.
#include "stats/hypothesis_tests.h"

#include <algorithm>
#include <boost/math/distributions/fisher_f.hpp>
#include <boost/math/distributions/students_t.hpp>
#include <cmath>
#include <stdexcept>
#include <string>

#include "stats/descriptive.h"

namespace ra::stats {
namespace {

// Mean and variance of `values` - `reference`. Subtracting a common reference from both samples
// before their means are formed keeps the mean difference exact to a few ulps of the difference,
// not of the data (1e9 + noise would otherwise lose 9 digits of it).
MeanVariance shifted_moments(const std::vector<double>& values, double reference) {
  std::vector<double> shifted(values.size());
  std::transform(values.begin(), values.end(), shifted.begin(),
                 [reference](double x) { return x - reference; });
  return mean_and_variance(shifted);
}

void require_size(const std::vector<double>& sample, std::size_t minimum, const char* test,
                  const char* which) {
  if (sample.size() < minimum) {
    throw std::invalid_argument(std::string(test) + ": " + which + " has " +
                                std::to_string(sample.size()) + " value(s); at least " +
                                std::to_string(minimum) + " needed");
  }
}

// The checks every two-sample test starts with: at least `minimum` values in each sample, and all
// of them finite.
void require_two_samples(const std::vector<double>& sample1, const std::vector<double>& sample2,
                         std::size_t minimum, const char* test) {
  require_size(sample1, minimum, test, "sample 1");
  require_size(sample2, minimum, test, "sample 2");
  require_finite(sample1, (std::string(test) + ", sample 1").c_str());
  require_finite(sample2, (std::string(test) + ", sample 2").c_str());
}

// Moments of both samples, shifted by the same reference (see shifted_moments), and their sizes.
struct TwoSampleMoments {
  MeanVariance a, b;
  double n1 = 0, n2 = 0;
};

TwoSampleMoments two_sample_moments(const std::vector<double>& sample1,
                                    const std::vector<double>& sample2) {
  const double reference = sample1.front();
  return {shifted_moments(sample1, reference), shifted_moments(sample2, reference),
          static_cast<double>(sample1.size()), static_cast<double>(sample2.size())};
}

double two_sided_t_p(double t, double df) {
  const boost::math::students_t dist(df);
  return std::min(1.0, 2 * boost::math::cdf(boost::math::complement(dist, std::fabs(t))));
}

double upper_f_p(double f, double df1, double df2) {
  const boost::math::fisher_f dist(df1, df2);
  return boost::math::cdf(boost::math::complement(dist, f));
}

// Neumaier-compensated sum, for the between-groups sum of squares.
double compensated_sum(const std::vector<double>& terms) {
  double sum = 0;
  double compensation = 0;
  for (double x : terms) {
    const double t = sum + x;
    compensation += std::fabs(sum) >= std::fabs(x) ? (sum - t) + x : (x - t) + sum;
    sum = t;
  }
  return sum + compensation;
}

}  // namespace

TTestResult t_test_pooled(const std::vector<double>& sample1, const std::vector<double>& sample2) {
  require_two_samples(sample1, sample2, 1, "pooled t test");
  if (sample1.size() + sample2.size() < 3) {
    throw std::invalid_argument("pooled t test: n1 + n2 = 2; at least 3 values needed");
  }
  // Both samples scaled by one power of two (exact): t is scale-free, and nothing squared can
  // overflow or underflow; the results in data units are scaled back.
  const int e = scale_exponent({sample1, sample2});
  const auto [a, b, n1, n2] = two_sample_moments(scaled(sample1, e), scaled(sample2, e));

  TTestResult r;
  r.df = n1 + n2 - 2;
  const double pooled_variance = ((n1 - 1) * a.variance + (n2 - 1) * b.variance) / r.df;
  if (!(pooled_variance > 0)) {
    throw std::invalid_argument("pooled t test: both samples are constant (pooled sd = 0)");
  }
  const double pooled_sd = std::sqrt(pooled_variance);
  const double difference = a.mean - b.mean;
  const double standard_error = pooled_sd * std::sqrt(1 / n1 + 1 / n2);
  r.statistic = difference / standard_error;
  r.pooled_sd = std::ldexp(pooled_sd, e);
  r.mean_difference = std::ldexp(difference, e);
  r.standard_error = std::ldexp(standard_error, e);
  r.p_value = two_sided_t_p(r.statistic, r.df);
  return r;
}

TTestResult t_test_welch(const std::vector<double>& sample1, const std::vector<double>& sample2) {
  require_two_samples(sample1, sample2, 2, "Welch t test");
  const int e = scale_exponent({sample1, sample2});  // as in t_test_pooled
  const auto [a, b, n1, n2] = two_sample_moments(scaled(sample1, e), scaled(sample2, e));

  const double v1 = a.variance / n1;  // squared standard errors of the two means
  const double v2 = b.variance / n2;
  if (!(v1 + v2 > 0)) {
    throw std::invalid_argument("Welch t test: both samples are constant (standard error = 0)");
  }
  TTestResult r;
  r.statistic = (a.mean - b.mean) / std::sqrt(v1 + v2);
  r.mean_difference = std::ldexp(a.mean - b.mean, e);
  r.standard_error = std::ldexp(std::sqrt(v1 + v2), e);
  // Welch-Satterthwaite degrees of freedom
  r.df = (v1 + v2) * (v1 + v2) / (v1 * v1 / (n1 - 1) + v2 * v2 / (n2 - 1));
  r.p_value = two_sided_t_p(r.statistic, r.df);
  return r;
}

FTestResult f_test_variances(const std::vector<double>& sample1,
                             const std::vector<double>& sample2) {
  require_two_samples(sample1, sample2, 2, "F test");
  const int e = scale_exponent({sample1, sample2});  // the ratio is scale-free
  const double var1 = mean_and_variance(scaled(sample1, e)).variance;
  const double var2 = mean_and_variance(scaled(sample2, e)).variance;
  if (!(var2 > 0)) {
    throw std::invalid_argument(
        "F test: sample 2 is constant (its variance, the denominator, is 0)");
  }
  FTestResult r;
  r.statistic = var1 / var2;
  r.df1 = static_cast<double>(sample1.size() - 1);
  r.df2 = static_cast<double>(sample2.size() - 1);
  const boost::math::fisher_f dist(r.df1, r.df2);
  const double lower = boost::math::cdf(dist, r.statistic);
  const double upper = boost::math::cdf(boost::math::complement(dist, r.statistic));
  r.p_value = std::min(1.0, 2 * std::min(lower, upper));
  return r;
}

const char* levene_center_name(LeveneCenter center) {
  switch (center) {
    case LeveneCenter::kMean:
      return "mean";
    case LeveneCenter::kMedian:
      return "median";
    case LeveneCenter::kTrimmedMean:
      return "trimmed_mean";
  }
  return "unknown";
}

FTestResult levene_test(const std::vector<std::vector<double>>& groups, LeveneCenter center) {
  if (groups.size() < 2) {
    throw std::invalid_argument("Levene test: " + std::to_string(groups.size()) +
                                " group(s); at least 2 needed");
  }
  std::vector<std::vector<double>> deviations;
  deviations.reserve(groups.size());
  double reference = 0;
  for (std::size_t g = 0; g < groups.size(); ++g) {
    if (groups[g].empty()) {
      throw std::invalid_argument("Levene test: group " + std::to_string(g + 1) + " is empty");
    }
    require_finite(groups[g], "Levene test");
  }
  // W is scale-free: one power of two for all groups, so deviations never overflow
  const int e = scale_exponent(groups);
  for (std::size_t g = 0; g < groups.size(); ++g) {
    const std::vector<double> group = scaled(groups[g], e);
    if (g == 0) reference = group.front();
    // centres and deviations are formed relative to one reference value (W is shift-invariant):
    // a centre of data near 1e9 would otherwise be rounded to 1e-7 before any deviation is taken
    std::vector<double> y(group.size());
    std::transform(group.begin(), group.end(), y.begin(),
                   [reference](double x) { return x - reference; });
    double c = 0;
    switch (center) {
      case LeveneCenter::kMean:
        c = mean(y);
        break;
      case LeveneCenter::kMedian: {
        // groups usually come sorted (the analysis keeps every sample ascending), and y keeps
        // their order: subtracting one value is monotone
        if (std::is_sorted(y.begin(), y.end())) {
          c = quantile_sorted(y, 0.5);  // every quantile definition agrees on the median
        } else {
          std::vector<double> sorted = y;
          std::sort(sorted.begin(), sorted.end());
          c = quantile_sorted(sorted, 0.5);
        }
        break;
      }
      case LeveneCenter::kTrimmedMean:
        c = trimmed_mean(y, 0.1);
        break;
    }
    std::vector<double> z(y.size());
    std::transform(y.begin(), y.end(), z.begin(), [c](double x) { return std::fabs(x - c); });
    deviations.push_back(std::move(z));
  }
  AnovaResult a;
  try {
    a = one_way_anova(deviations);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("Levene test (") + levene_center_name(center) +
                                " centre) on absolute deviations: " + e.what());
  }
  return FTestResult{a.f, a.df_between, a.df_within, a.p_value};
}

AnovaResult one_way_anova(const std::vector<std::vector<double>>& groups) {
  AnovaResult r;
  r.k = groups.size();
  if (r.k < 2) {
    throw std::invalid_argument("one-way ANOVA: " + std::to_string(r.k) +
                                " group(s); at least 2 needed");
  }
  for (std::size_t g = 0; g < r.k; ++g) {
    if (groups[g].empty()) {
      throw std::invalid_argument("one-way ANOVA: group " + std::to_string(g + 1) + " is empty");
    }
    require_finite(groups[g], "one-way ANOVA");
    r.n += groups[g].size();
  }
  if (r.n <= r.k) {
    throw std::invalid_argument("one-way ANOVA: " + std::to_string(r.n) + " values in " +
                                std::to_string(r.k) + " groups; more values than groups needed");
  }

  // scale every group by one power of two (exact; F is scale-free, sums of squares are scaled
  // back), then center every value on one reference before any sum is formed, so that leading
  // digits shared by all data (StRD SmLs04: 1000000.4) cancel exactly
  const int e = scale_exponent(groups);
  const double reference = std::ldexp(groups.front().front(), -e);
  std::vector<MeanVariance> moments;
  std::vector<double> all_shifted;
  all_shifted.reserve(r.n);
  for (const auto& unscaled_group : groups) {
    const std::vector<double> y = scaled(unscaled_group, e);
    moments.push_back(shifted_moments(y, reference));
    for (double x : y) all_shifted.push_back(x - reference);
  }
  const double grand_mean = mean(all_shifted);

  std::vector<double> between_terms;
  std::vector<double> within_terms;
  for (std::size_t g = 0; g < r.k; ++g) {
    const double n_g = static_cast<double>(groups[g].size());
    const double d = moments[g].mean - grand_mean;
    between_terms.push_back(n_g * d * d);
    within_terms.push_back((n_g - 1) * moments[g].variance);
  }
  const double ss_between = compensated_sum(between_terms);  // scaled units
  const double ss_within = compensated_sum(within_terms);
  r.df_between = static_cast<double>(r.k - 1);
  r.df_within = static_cast<double>(r.n - r.k);
  const double ms_between = ss_between / r.df_between;
  const double ms_within = ss_within / r.df_within;
  if (!(ms_within > 0)) {
    throw std::invalid_argument("one-way ANOVA: every group is constant (within-group SS = 0)");
  }
  r.f = ms_between / ms_within;
  r.p_value = upper_f_p(r.f, r.df_between, r.df_within);
  r.r_squared = ss_between / (ss_between + ss_within);
  r.residual_sd = std::ldexp(std::sqrt(ms_within), e);
  // Sums and means of squares in data units squared: inf or 0 when they leave the double range
  // (data near 1e200 have squares near 1e400); F, p and R^2 above do not depend on them.
  r.ss_between = std::ldexp(ss_between, 2 * e);
  r.ss_within = std::ldexp(ss_within, 2 * e);
  r.ms_between = std::ldexp(ms_between, 2 * e);
  r.ms_within = std::ldexp(ms_within, 2 * e);
  return r;
}

}  // namespace ra::stats
