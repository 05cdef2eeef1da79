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

std::string join_ints(const std::vector<int>& v, const char* sep) {
  std::string s;
  for (std::size_t i = 0; i < v.size(); ++i) s += (i ? sep : "") + std::to_string(v[i]);
  return s;
}

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

stats::TableCell p_value_cell(const TestOutcome& o) {
  return o.defined ? stats::significant_cell(o.p_value, 3) : stats::text_cell("undefined");
}

stats::TableCell statistic_cell(const TestOutcome& o) {
  return o.defined ? stats::significant_cell(o.statistic, 4) : stats::text_cell("undefined");
}

namespace {

// "0.39555; 0.39716", or "no data" for an empty view.
stats::TableCell per_view_cell(const std::vector<double>& values, const std::vector<std::size_t>& n) {
  std::string text;
  std::string csv;
  for (std::size_t i = 0; i < values.size(); ++i) {
    const std::string sep = i ? "; " : "";
    const bool has = i < n.size() && n[i] > 0;
    text += sep + (has ? stats::format_significant(values[i], 5) : "no data");
    csv += sep + (has ? stats::format_significant(values[i], 9) : "no data");
  }
  return stats::TableCell{text, csv};
}

stats::TableCell n_cell(const std::vector<std::size_t>& n) {
  std::string s;
  for (std::size_t i = 0; i < n.size(); ++i) s += (i ? "; " : "") + std::to_string(n[i]);
  return stats::text_cell(s);
}

// The reasons of the undefined tests of a battery, "; "-separated.
std::string undefined_reasons(const TestBattery& b, const char* prefix) {
  std::string s;
  const std::pair<const char*, const TestOutcome*> tests[] = {{"location", &b.location},
                                                              {"Welch", &b.welch},
                                                              {"F", &b.f_test},
                                                              {"Levene (median)", &b.levene_median},
                                                              {"Levene (mean)", &b.levene_mean}};
  for (const auto& [name, o] : tests) {
    if (!o->defined && !o->reason.empty()) {
      s += std::string(s.empty() ? "" : "; ") + prefix + name + ": " + o->reason;
    }
  }
  return s;
}

std::vector<stats::TableCell> lambda_cells(const BoxCoxFit& f) {
  if (!f.applicable) {
    const stats::TableCell na = stats::text_cell("not applicable");
    return {na, na, na, na, na};
  }
  return {stats::significant_cell(f.lambda, 4), stats::significant_cell(f.shift(), 6), stats::count_cell(f.n_fit),
          stats::significant_cell(f.ppcc, 6), stats::text_cell(f.at_boundary ? "yes" : "no")};
}

}  // namespace

stats::Table view_equivalence_table(const RunRecords& run, const std::vector<ViewEquivalence>& results,
                             const EquivalenceOptions& options) {
  stats::Table t;
  t.file_stem = "view_equivalence";
  t.title =
      "View equivalence (paper section 4, p. 228): orientation views compared per platform, "
      "kind, metric and view group; raw and Box-Cox data; alpha = " +
      p_text(options.alpha) + "; medians and IQRs by quartiles " +
      (options.quantiles == stats::QuantileDefinition::kHyndmanFan6 ? "Hyndman-Fan 6"
                                                                    : "Hyndman-Fan 7");
  t.notes = {
      "verdict: equivalent when location (pooled t; one-way ANOVA for more than 2 views) and "
      "Levene median-centred p >= alpha on raw data; F and Box-Cox tests are reported, not "
      "deciding",
      "Box-Cox: lambda by maximum PPCC on the pooled group, chosen on at most " +
          std::to_string(options.comparison.box_cox_subsample) +
          " systematic order statistics; shift = 1 - min when min <= 0 (Dataplot)",
      "p-values two-sided for t and F, upper tail for ANOVA and Levene W; 'undefined' tests give "
      "their reason in the notes column"};
  const char* columns[] = {"platform",
                           "kind",
                           "metric",
                           "view_group",
                           "views",
                           "orientations",
                           "n",
                           "median",
                           "iqr",
                           "verdict",
                           "location_test",
                           "raw_location_statistic",
                           "raw_location_df1",
                           "raw_location_df2",
                           "raw_location_p",
                           "raw_welch_t",
                           "raw_welch_p",
                           "raw_f",
                           "raw_f_p",
                           "raw_levene_median_w",
                           "raw_levene_median_p",
                           "raw_levene_mean_w",
                           "raw_levene_mean_p",
                           "box_cox_lambda",
                           "box_cox_shift",
                           "box_cox_n_fit",
                           "box_cox_ppcc",
                           "box_cox_at_boundary",
                           "bc_location_statistic",
                           "bc_location_p",
                           "bc_welch_t",
                           "bc_welch_p",
                           "bc_f",
                           "bc_f_p",
                           "bc_levene_median_w",
                           "bc_levene_median_p",
                           "bc_levene_mean_w",
                           "bc_levene_mean_p",
                           "explanation",
                           "notes"};
  for (const char* c : columns) t.columns.push_back({c, stats::Align::kLeft});
  for (const ViewEquivalence& r : results) {
    const MetricSpec& spec = kind_metrics(r.kind)[r.metric];
    const SampleComparison& c = r.comparison;
    const auto df_cell = [](const TestOutcome& o, double df) {
      return o.defined ? stats::significant_cell(df, 6) : stats::text_cell("undefined");
    };
    std::vector<stats::TableCell> row = {stats::text_cell(run.platforms[r.platform]),
                                  stats::text_cell(kind_name(r.kind)),
                                  stats::text_cell(spec.column),
                                  stats::text_cell(r.label),
                                  stats::text_cell(join_ints(r.views, ";")),
                                  stats::text_cell(join_ints(r.orientations, ";")),
                                  n_cell(c.n),
                                  per_view_cell(r.medians, c.n),
                                  per_view_cell(r.iqrs, c.n),
                                  stats::text_cell(verdict_name(r.verdict)),
                                  stats::text_cell(c.raw.location_name),
                                  statistic_cell(c.raw.location),
                                  df_cell(c.raw.location, c.raw.location.df1),
                                  c.raw.location_name == "one-way ANOVA"
                                      ? df_cell(c.raw.location, c.raw.location.df2)
                                      : stats::text_cell("n/a"),
                                  p_value_cell(c.raw.location),
                                  statistic_cell(c.raw.welch),
                                  p_value_cell(c.raw.welch),
                                  statistic_cell(c.raw.f_test),
                                  p_value_cell(c.raw.f_test),
                                  statistic_cell(c.raw.levene_median),
                                  p_value_cell(c.raw.levene_median),
                                  statistic_cell(c.raw.levene_mean),
                                  p_value_cell(c.raw.levene_mean)};
    for (stats::TableCell& cell : lambda_cells(c.box_cox)) row.push_back(std::move(cell));
    for (const TestOutcome* o :
         {&c.transformed.location, &c.transformed.welch, &c.transformed.f_test,
          &c.transformed.levene_median, &c.transformed.levene_mean}) {
      row.push_back(statistic_cell(*o));
      row.push_back(p_value_cell(*o));
    }
    row.push_back(stats::text_cell(r.explanation));
    std::string notes = undefined_reasons(c.raw, "raw ");
    const std::string bc = c.box_cox.applicable ? undefined_reasons(c.transformed, "Box-Cox ")
                                                : "Box-Cox not applicable: " + c.box_cox.reason;
    if (!bc.empty()) notes += (notes.empty() ? "" : "; ") + bc;
    row.push_back(stats::text_cell(notes));
    t.rows.push_back(std::move(row));
  }
  return t;
}

std::string view_equivalence_markdown(const RunRecords& run,
                                      const std::vector<ViewEquivalence>& results,
                                      const EquivalenceOptions& options) {
  const std::string a = p_text(options.alpha);
  std::size_t counts[4] = {0, 0, 0, 0};
  for (const ViewEquivalence& r : results) ++counts[static_cast<int>(r.verdict)];
  if (counts[static_cast<int>(Verdict::kNoComparison)] == results.size())
    return "# View equivalence\n\n"
           "The experiment has one camera orientation per view group (`[views] orientations = 1`), "
           "or no data where there are more, so no views are pooled and nothing is tested: each "
           "view group is its one view. The paper compared the orientation views of each group "
           "with t, F and Levene tests before pooling them (section 4, p. 228); an experiment with "
           "more orientations gets those tests here.\n";
  std::string md =
      "# View equivalence\n\n"
      "The paper (section 4, p. 228) compared the views that differ only by camera orientation "
      "with t tests, F tests and Levene tests, on raw and Box-Cox transformed data, and then "
      "pooled them into view groups A-D. This file does the same for every platform, kind, metric "
      "and view group of the run (`" +
      run.run_dir +
      "`).\n\n"
      "**Rule.** The views of a group are *equivalent* when, on the raw data, the location test "
      "(pooled t test; one-way ANOVA for more than two orientations) and Levene's test with median "
      "centre (Brown-Forsythe, spread) both have p >= alpha = " +
      a +
      ". The paper trusted Levene "
      "over the F test for these non-normal data (the F test is not robust to non-normality), and "
      "so does this rule: the F test, Levene with mean centre and all Box-Cox results are reported "
      "but do not decide.\n\n"
      "**Box-Cox.** lambda maximises the probability plot correlation (PPCC, e-Handbook 1.3.3.6) "
      "of the group's pooled data, searched on [-2, 2]; it is chosen on a systematic subsample of "
      "at most " +
      std::to_string(options.comparison.box_cox_subsample) +
      " order statistics of the sorted pooled data (ranks floor((i + 1/2) n / m)), and the tests "
      "then use every value. Data with a value <= 0 are shifted by 1 - min first (Dataplot). The "
      "same lambda and shift apply to every view of the group. That shift does not scale with the "
      "data: for signed metrics of tiny magnitude (LSEs-norm, TEs-norm, around 1e-6) the shifted "
      "values all lie within about 1e-3 of 1, where every power is nearly linear, so lambda runs "
      "to an end of [-2, 2] (`box_cox_at_boundary` in the CSV) and the transformed tests repeat "
      "the raw ones; the Box-Cox results of the same metrics in pixels (LSEs, TEs) are the "
      "informative ones.\n\n"
      "Full statistics (t, F, W, degrees of freedom, lambda, shift): `view_equivalence.csv`.\n\n";

  md += "## Verdicts\n\n";
  md += "- " + std::to_string(results.size()) + " comparisons: " + std::to_string(counts[0]) +
        " equivalent, " + std::to_string(counts[1]) + " NOT equivalent, " +
        std::to_string(counts[2]) + " undecided, " + std::to_string(counts[3]) +
        " without comparison (one orientation or no data; not listed in the tables below).\n";
  for (const ViewEquivalence& r : results) {
    if (r.verdict != Verdict::kNotEquivalent && r.verdict != Verdict::kUndecided) continue;
    md += std::string("- **") + verdict_name(r.verdict) + "**: " + run.platforms[r.platform] +
          ", " + kind_label_plural(r.kind) + ", " + kind_metrics(r.kind)[r.metric].symbol +
          ", view group " + r.label + " (views " + join_ints(r.views, ", ") +
          "): " + r.explanation + ".\n";
  }
  md += "\n";
  if (counts[1] + counts[2] > 0) {
    md +=
        "**Pooling.** The views were pooled into view groups anyway, as the paper did: the "
        "tables describe the pooled groups, and for the groups listed above the pooled "
        "distribution mixes views that the tests could not show to be equivalent.\n\n";
  } else {
    md +=
        "**Pooling.** Every comparison that could be made found the orientation views "
        "equivalent; the views are pooled into view groups, as the paper did.\n\n";
  }

  for (std::size_t p = 0; p < run.platforms.size(); ++p) {
    for (geometry::Kind kind : run.kinds()) {
      stats::Table t;
      t.title = run.platforms[p] + ", " + kind_label_plural(kind) + ": p-values (raw | Box-Cox)";
      for (const char* c : {"metric", "group", "views", "n", "median"}) {
        t.columns.push_back({c, stats::Align::kLeft});
      }
      for (const char* c :
           {"location p", "Welch p", "F p", "Levene med p", "Levene mean p", "BC lambda",
            "BC location p", "BC F p", "BC Levene med p", "BC Levene mean p"}) {
        t.columns.push_back({c, stats::Align::kRight});
      }
      t.columns.push_back({"verdict", stats::Align::kLeft});
      for (const ViewEquivalence& r : results) {
        if (r.platform != p || r.kind != kind || r.verdict == Verdict::kNoComparison) continue;
        const SampleComparison& c = r.comparison;
        t.rows.push_back(
            {stats::text_cell(kind_metrics(kind)[r.metric].symbol), stats::text_cell(r.label),
             stats::text_cell(join_ints(r.views, ", ")), n_cell(c.n), per_view_cell(r.medians, c.n),
             p_value_cell(c.raw.location), p_value_cell(c.raw.welch), p_value_cell(c.raw.f_test),
             p_value_cell(c.raw.levene_median), p_value_cell(c.raw.levene_mean),
             c.box_cox.applicable ? stats::significant_cell(c.box_cox.lambda, 3) : stats::text_cell("n/a"),
             p_value_cell(c.transformed.location), p_value_cell(c.transformed.f_test),
             p_value_cell(c.transformed.levene_median), p_value_cell(c.transformed.levene_mean),
             stats::text_cell(verdict_name(r.verdict))});
      }
      if (t.rows.empty()) continue;
      md += stats::render_markdown(t) + "\n";
    }
  }
  md +=
      "'undefined': the test cannot be computed for these data (reason in "
      "`view_equivalence.csv`, column notes); 'n/a': Box-Cox not applicable.\n";
  return md;
}

}  // namespace ra::analysis
