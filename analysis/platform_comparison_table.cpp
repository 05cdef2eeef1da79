// The comparison of platforms per view group and metric (paper_tables.h): Welch t and Levene
// tests on raw and Box-Cox transformed data.
#include "analysis/paper_tables.h"

#include <cmath>

#include "analysis/paper_table_parts.h"
#include "analysis/view_equivalence_report.h"

namespace ra::analysis {

using namespace table_parts;
using stats::Description;
using stats::QuantileDefinition;

std::vector<PlatformComparison> compare_platforms(const RunRecords& run,
                                                  const GroupSummaries& summaries,
                                                  const TableOptions& options) {
  std::vector<PlatformComparison> out;
  for (geometry::Kind kind : run.kinds()) {
    for (std::size_t m = 0; m < kind_metrics(kind).size(); ++m) {
      for (int g : run.view_groups(kind)) {
        for (std::size_t a = 0; a < run.platforms.size(); ++a) {
          for (std::size_t b = a + 1; b < run.platforms.size(); ++b) {
            if (!run.find_group(a, kind, g) || !run.find_group(b, kind, g)) continue;
            PlatformComparison c;
            c.kind = kind;
            c.metric = m;
            c.view_group = g;
            c.label = view_group_label(g);
            c.platform_a = a;
            c.platform_b = b;
            out.push_back(std::move(c));
          }
        }
      }
    }
  }
  util::run_in_parallel(out.size(), options.jobs, [&](std::size_t i) {
    PlatformComparison& c = out[i];
    std::vector<std::vector<double>> samples = {
        run.find_group(c.platform_a, c.kind, c.view_group)->pooled(c.metric),
        run.find_group(c.platform_b, c.kind, c.view_group)->pooled(c.metric)};
    const auto summary = [&](std::size_t p) -> std::optional<Description> {
      const Description* d = summaries.find(p, c.kind, c.metric, c.view_group);
      return d ? std::optional<Description>(*d) : std::nullopt;
    };
    c.a = summary(c.platform_a);
    c.b = summary(c.platform_b);
    if (c.a && c.b) c.comparison = compare_samples(samples, options.comparison);
  });
  return out;
}

stats::Table cross_platform_table(const RunRecords& run, const std::vector<PlatformComparison>& rows,
                           const TableOptions& options) {
  stats::Table t;
  t.file_stem = "cross_platform";
  t.title =
      "Cross-platform comparison per view group and metric (paper section 4, Figs. 5, 7, 9, "
      "13): medians and IQRs, differences a - b in metric units, p-values on raw and "
      "Box-Cox data, alpha = " +
      stats::format_significant(options.alpha, 3) + "; quartiles " + quantile_label(options.quantiles);
  for (const char* c : {"Kind", "Metric", "Units", "View", "Platform a", "Platform b"}) {
    t.columns.push_back({c, stats::Align::kLeft});
  }
  for (const char* c : {"n a", "n b", "Median a", "Median b", "Median a-b", "IQR a", "IQR b",
                        "IQR a-b", "t pooled p", "Welch p", "F p", "Levene med p", "BC lambda",
                        "BC t pooled p", "BC Welch p", "BC F p", "BC Levene med p"}) {
    t.columns.push_back({c, stats::Align::kRight});
  }
  t.columns.push_back({"Location", stats::Align::kLeft});
  t.columns.push_back({"Spread", stats::Align::kLeft});
  const auto flag = [&](const TestOutcome& o) {
    if (!o.defined) return stats::text_cell("undefined");
    return stats::text_cell(o.p_value < options.alpha ? "differs" : "same");
  };
  for (const PlatformComparison& c : rows) {
    const MetricSpec& spec = kind_metrics(c.kind)[c.metric];
    std::vector<stats::TableCell> row = {
        stats::text_cell(kind_name(c.kind)),           stats::text_cell(spec.symbol),
        stats::text_cell(unit_name(spec.unit)),        stats::text_cell(c.label),
        stats::text_cell(run.platforms[c.platform_a]), stats::text_cell(run.platforms[c.platform_b]),
        stats::count_cell(c.a ? c.a->n : 0),           stats::count_cell(c.b ? c.b->n : 0)};
    const stats::TableCell none = stats::text_cell("no data");
    if (c.a && c.b) {
      row.push_back(stats::significant_cell(c.a->median, 5));
      row.push_back(stats::significant_cell(c.b->median, 5));
      row.push_back(stats::significant_cell(c.a->median - c.b->median, 4));
      row.push_back(stats::significant_cell(c.a->iqr, 5));
      row.push_back(stats::significant_cell(c.b->iqr, 5));
      row.push_back(stats::significant_cell(c.a->iqr - c.b->iqr, 4));
      const SampleComparison& s = c.comparison;
      for (const TestOutcome* o :
           {&s.raw.location, &s.raw.welch, &s.raw.f_test, &s.raw.levene_median}) {
        row.push_back(p_value_cell(*o));
      }
      row.push_back(s.box_cox.applicable ? stats::significant_cell(s.box_cox.lambda, 3)
                                         : stats::text_cell("n/a"));
      for (const TestOutcome* o : {&s.transformed.location, &s.transformed.welch,
                                   &s.transformed.f_test, &s.transformed.levene_median}) {
        row.push_back(p_value_cell(*o));
      }
      row.push_back(flag(s.raw.welch));
      row.push_back(flag(s.raw.levene_median));
    } else {
      for (std::size_t i = row.size(); i < t.columns.size(); ++i) row.push_back(none);
    }
    t.rows.push_back(std::move(row));
  }
  t.notes = {
      "Location: Welch t test on raw data (variances not assumed equal); Spread: Levene "
      "test with median centre on raw data; 'differs' when p < alpha.",
      "BC: Box-Cox transformed, lambda by maximum PPCC on both platforms' pooled data "
      "(systematic subsample of at most " +
          std::to_string(options.comparison.box_cox_subsample) +
          " order statistics), shift 1 - min when min <= 0; n/a: not applicable.",
      "With samples of 10^5 even tiny differences are significant: read the differences "
      "of medians and IQRs, in metric units, for their size."};
  return t;
}

}  // namespace ra::analysis
