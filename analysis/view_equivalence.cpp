// Equivalence of views that differ only by camera orientation; see view_equivalence.h.
#include "analysis/view_equivalence.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "stats/box_cox.h"
#include "stats/hypothesis_tests.h"

namespace ra::analysis {
namespace {

// Runs one test; an undefined result (std::invalid_argument from the library, or a non-finite
// number, which the library promises never to return) becomes a reason instead of a number.
template <typename Compute>
TestOutcome outcome(Compute compute) {
  try {
    TestOutcome o = compute();
    if (!std::isfinite(o.statistic) || !std::isfinite(o.p_value) || !std::isfinite(o.df1) ||
        !std::isfinite(o.df2)) {
      return TestOutcome{false, 0, 0, 0, 1, "the statistic is not finite for these data"};
    }
    o.defined = true;
    return o;
  } catch (const std::invalid_argument& e) {
    return TestOutcome{false, 0, 0, 0, 1, e.what()};
  }
}

TestOutcome from_t(const stats::TTestResult& t) {
  return TestOutcome{true, t.statistic, t.df, 0, t.p_value, ""};
}
TestOutcome from_f(const stats::FTestResult& f) {
  return TestOutcome{true, f.statistic, f.df1, f.df2, f.p_value, ""};
}

TestOutcome not_run(const std::string& reason) { return TestOutcome{false, 0, 0, 0, 1, reason}; }

TestBattery run_battery(const std::vector<std::vector<double>>& s) {
  TestBattery b;
  if (s.size() == 2) {
    b.location_name = "t (pooled)";
    b.location = outcome([&] { return from_t(stats::t_test_pooled(s[0], s[1])); });
    b.welch = outcome([&] { return from_t(stats::t_test_welch(s[0], s[1])); });
    b.f_test = outcome([&] { return from_f(stats::f_test_variances(s[0], s[1])); });
  } else {
    b.location_name = "one-way ANOVA";
    b.location = outcome([&] {
      const stats::AnovaResult a = stats::one_way_anova(s);
      return TestOutcome{true, a.f, a.df_between, a.df_within, a.p_value, ""};
    });
    const std::string why = "two samples only (here " + std::to_string(s.size()) + ")";
    b.welch = not_run(why);
    b.f_test = not_run(why);
  }
  b.levene_median =
      outcome([&] { return from_f(stats::levene_test(s, stats::LeveneCenter::kMedian)); });
  b.levene_mean =
      outcome([&] { return from_f(stats::levene_test(s, stats::LeveneCenter::kMean)); });
  return b;
}

TestBattery battery_not_run(const std::string& reason, std::size_t k) {
  TestBattery b;
  b.location_name = k > 2 ? "one-way ANOVA" : "t (pooled)";
  b.location = b.welch = b.f_test = b.levene_median = b.levene_mean = not_run(reason);
  return b;
}

std::string p_text(double p) { return stats::format_significant(p, 3); }

}  // namespace

BoxCoxFit fit_box_cox(const std::vector<double>& pooled, const ComparisonOptions& options) {
  BoxCoxFit f;
  f.n = pooled.size();
  if (pooled.size() < 3) {
    f.reason = "fewer than 3 values";
    return f;
  }
  std::vector<double> sorted = pooled;
  if (!std::is_sorted(sorted.begin(), sorted.end())) std::sort(sorted.begin(), sorted.end());
  if (sorted.front() == sorted.back()) {
    f.reason = "all values are equal";
    return f;
  }
  f.pooled_min = sorted.front();
  f.shifted = f.pooled_min <= 0;
  if (f.shifted) {
    for (double& y : sorted) y = (y - f.pooled_min) + 1;  // Dataplot: y - min + 1, still ascending
  }
  const std::size_t n = sorted.size();
  const std::size_t m = std::min(n, std::max<std::size_t>(3, options.box_cox_subsample));
  std::vector<double> fit_values;
  if (m == n) {
    fit_values = std::move(sorted);
  } else {
    fit_values.reserve(m);
    for (std::size_t i = 0; i < m; ++i) {
      const double rank =
          (static_cast<double>(i) + 0.5) * static_cast<double>(n) / static_cast<double>(m);
      fit_values.push_back(sorted[std::min(n - 1, static_cast<std::size_t>(rank))]);
    }
  }
  f.n_fit = m;
  stats::BoxCoxOptions search;
  search.grid_points = std::max<std::size_t>(2, options.box_cox_grid_points);
  const stats::BoxCoxResult r =
      stats::box_cox_lambda(fit_values, stats::BoxCoxMethod::kPpcc, search);
  if (!r.applicable) {
    f.reason = r.reason;
    if (m < n) f.reason += " (in the subsample of " + std::to_string(m) + " order statistics)";
    return f;
  }
  f.applicable = true;
  f.lambda = r.lambda;
  f.ppcc = r.ppcc_at_lambda;
  f.at_boundary = r.at_boundary;
  return f;
}

std::vector<double> apply_box_cox(const std::vector<double>& values, const BoxCoxFit& fit) {
  if (!fit.applicable) throw std::logic_error("apply_box_cox: the fit is not applicable");
  std::vector<double> out;
  out.reserve(values.size());
  for (double y : values) {
    out.push_back(stats::box_cox_transform(fit.shifted ? (y - fit.pooled_min) + 1 : y, fit.lambda));
  }
  return out;
}

SampleComparison compare_samples(const std::vector<std::vector<double>>& samples,
                                 const ComparisonOptions& options) {
  if (samples.size() < 2) throw std::logic_error("compare_samples: fewer than 2 samples");
  SampleComparison c;
  std::vector<const std::vector<double>*> parts;
  bool ascending = true;
  for (const auto& s : samples) {
    c.n.push_back(s.size());
    parts.push_back(&s);
    ascending = ascending && std::is_sorted(s.begin(), s.end());
  }
  std::vector<double> pooled;
  if (ascending) {
    pooled = merge_sorted(parts);  // the run's samples are kept sorted: no sort needed
  } else {
    for (const auto* s : parts) pooled.insert(pooled.end(), s->begin(), s->end());
  }
  c.raw = run_battery(samples);
  c.box_cox = fit_box_cox(pooled, options);
  if (!c.box_cox.applicable) {
    c.transformed = battery_not_run("Box-Cox not applicable: " + c.box_cox.reason, samples.size());
    return c;
  }
  std::vector<std::vector<double>> transformed;
  transformed.reserve(samples.size());
  for (const auto& s : samples) transformed.push_back(apply_box_cox(s, c.box_cox));
  c.transformed = run_battery(transformed);
  return c;
}

const char* verdict_name(Verdict v) {
  switch (v) {
    case Verdict::kEquivalent:
      return "equivalent";
    case Verdict::kNotEquivalent:
      return "NOT equivalent";
    case Verdict::kUndecided:
      return "undecided";
    case Verdict::kNoComparison:
      return "no comparison";
  }
  return "unknown";
}

Verdict decide_equivalence(const std::vector<std::vector<double>>& samples,
                           const SampleComparison& c, double alpha, std::string* explanation) {
  std::string why;
  Verdict v = Verdict::kUndecided;
  std::size_t empty = 0;
  for (const auto& s : samples) empty += s.empty();
  if (samples.size() < 2) {
    why = "only one orientation: nothing to compare";
    v = Verdict::kNoComparison;
  } else if (empty == samples.size()) {
    why = "no values in any view (metric not measured, or nothing true-visible)";
    v = Verdict::kNoComparison;
  } else if (empty > 0) {
    why = std::to_string(empty) + " of the " + std::to_string(samples.size()) +
          " views have no values";
  } else {
    bool all_constant = true;
    for (const auto& s : samples) {
      const auto [lo, hi] = std::minmax_element(s.begin(), s.end());
      all_constant = all_constant && *lo == *hi;
    }
    if (all_constant) {
      bool same = true;
      for (const auto& s : samples) same = same && s.front() == samples.front().front();
      v = same ? Verdict::kEquivalent : Verdict::kNotEquivalent;
      why = same ? "every view is the same constant " + stats::format_significant(samples[0][0], 6)
                 : "every view is constant, with different values";
    } else if (!c.raw.location.defined || !c.raw.levene_median.defined) {
      why = !c.raw.location.defined ? c.raw.location_name + " undefined: " + c.raw.location.reason
                                    : "Levene (median) undefined: " + c.raw.levene_median.reason;
    } else {
      const std::string a = p_text(alpha);
      const bool location_ok = c.raw.location.p_value >= alpha;
      const bool spread_ok = c.raw.levene_median.p_value >= alpha;
      const std::string loc = c.raw.location_name + " p = " + p_text(c.raw.location.p_value) +
                              (location_ok ? " >= " : " < ") + a;
      const std::string spread = "Levene (median) p = " + p_text(c.raw.levene_median.p_value) +
                                 (spread_ok ? " >= " : " < ") + a;
      if (location_ok && spread_ok) {
        v = Verdict::kEquivalent;
        why = loc + "; " + spread;
      } else {
        v = Verdict::kNotEquivalent;
        why = std::string(!location_ok && !spread_ok ? "location and spread differ"
                          : !location_ok             ? "location differs"
                                                     : "spread differs") +
              ": " + loc + "; " + spread;
      }
      if (spread_ok && c.raw.f_test.defined && c.raw.f_test.p_value < alpha) {
        why += " (F test p = " + p_text(c.raw.f_test.p_value) + " < " + a +
               ", but F is not robust to non-normal data; Levene decides)";
      }
    }
  }
  if (explanation) *explanation = why;
  return v;
}

std::vector<ViewEquivalence> assess_view_equivalence(const RunRecords& run,
                                                     const EquivalenceOptions& options) {
  struct Task {
    const ViewGroup* group;
    std::size_t metric;
  };
  std::vector<Task> tasks;
  for (std::size_t p = 0; p < run.platforms.size(); ++p) {
    for (geometry::Kind kind : run.kinds()) {
      for (std::size_t m = 0; m < kind_metrics(kind).size(); ++m) {
        for (const ViewGroup* g : run.groups_of(p, kind)) tasks.push_back({g, m});
      }
    }
  }
  std::vector<ViewEquivalence> results(tasks.size());
  util::run_in_parallel(tasks.size(), options.jobs, [&](std::size_t i) {
    const ViewGroup& g = *tasks[i].group;
    const std::size_t m = tasks[i].metric;
    ViewEquivalence& r = results[i];
    r.platform = g.platform;
    r.kind = g.kind;
    r.metric = m;
    r.view_group = g.view_group;
    r.label = g.label;
    std::vector<std::vector<double>> samples;
    for (const ViewData* v : g.views) {
      r.views.push_back(v->meta.view);
      r.orientations.push_back(v->meta.orientation);
      samples.push_back(v->values[m]);
      if (v->values[m].empty()) {
        r.medians.push_back(0);
        r.iqrs.push_back(0);
      } else {
        const stats::Description d = describe_sorted(v->values[m], options.quantiles);
        r.medians.push_back(d.median);
        r.iqrs.push_back(d.iqr);
      }
    }
    if (samples.size() >= 2) {
      r.comparison = compare_samples(samples, options.comparison);
    } else {
      for (const auto& s : samples) r.comparison.n.push_back(s.size());
      r.comparison.raw = battery_not_run("only one orientation", 2);
      r.comparison.transformed = r.comparison.raw;
      r.comparison.box_cox.reason = "only one orientation";
      r.comparison.box_cox.n = samples.empty() ? 0 : samples[0].size();
    }
    r.verdict = decide_equivalence(samples, r.comparison, options.alpha, &r.explanation);
  });
  return results;
}


}  // namespace ra::analysis
