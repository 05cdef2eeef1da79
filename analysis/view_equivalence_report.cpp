// The view-equivalence results written out: the long table and the report (view_equivalence_report.h).
#include "analysis/view_equivalence_report.h"

namespace ra::analysis {
namespace {

std::string p_text(double p) { return stats::format_significant(p, 3); }

std::string join_ints(const std::vector<int>& v, const char* sep) {
  std::string s;
  for (std::size_t i = 0; i < v.size(); ++i) s += (i ? sep : "") + std::to_string(v[i]);
  return s;
}

}  // namespace

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
