// The error metrics' tables (paper_tables.h): median and IQR by view group and platform
// (Tables 3, 4, 6, 7, 9, 10 and the supplements), their bootstrap uncertainty, and the medians in
// physical units (Table 11).
#include "analysis/paper_tables.h"

#include <algorithm>
#include <cctype>
#include <cmath>

#include "analysis/paper_table_parts.h"
#include "util/number_text.h"

namespace ra::analysis {

using namespace table_parts;
using stats::Description;
using stats::QuantileDefinition;

stats::Table uncertainty_table(const RunRecords& run, const GroupSummaries& summaries,
                        const TableOptions& options) {
  stats::Table t;
  t.file_stem = "uncertainty";
  t.title =
      "Uncertainty of Tables 3, 4, 6, 7, 9, 10: bootstrap standard error (SE) and 95% "
      "percentile interval of each median and IQR, in the units and scale of its table";
  stats::add_columns(t, {"Table", "Metric", "View", "Platform"}, stats::Align::kLeft);
  stats::add_columns(
      t, {"n", "Median", "SE", "95% low", "95% high", "IQR", "SE", "95% low", "95% high"},
      stats::Align::kRight);
  for (const MetricTableSpec& spec : metric_table_specs()) {
    if (!std::isdigit(static_cast<unsigned char>(spec.number.back()))) continue;  // supplements
    const std::size_t metric = metric_index(spec.kind, spec.column);
    const MetricSpec& m = kind_metrics(spec.kind)[metric];
    const double scale = std::pow(10.0, spec.scale_exponent);
    const int decimals = spec.decimals + 1;  // one more than the table: the SE's first digit
    for (int g : run.view_groups(spec.kind)) {
      for (std::size_t p = 0; p < run.platforms.size(); ++p) {
        const Description* d = summaries.find(p, spec.kind, metric, g);
        const stats::MedianIqrBootstrap* b = summaries.bootstrap(p, spec.kind, metric, g);
        if (!d || !b) continue;
        std::vector<stats::TableCell> row = {
            stats::text_cell(spec.number),
            stats::text_cell(std::string(m.symbol) + " " + scale_text(spec.scale_exponent)),
            stats::text_cell(view_group_label(g)), stats::text_cell(run.platforms[p]),
            stats::text_cell(std::to_string(d->n))};
        for (const auto& [value, e] :
             {std::pair{d->median, b->median}, std::pair{d->iqr, b->iqr}}) {
          row.push_back(stats::number_cell(value * scale, decimals));
          row.push_back(stats::number_cell(e.se * scale, decimals));
          row.push_back(stats::number_cell(e.lo95 * scale, decimals));
          row.push_back(stats::number_cell(e.hi95 * scale, decimals));
        }
        t.rows.push_back(std::move(row));
      }
    }
  }
  t.notes.push_back("Bootstrap: " + std::to_string(options.bootstrap.resamples) +
                    " resamples of each pooled view-group sample, seed " +
                    std::to_string(options.bootstrap.seed) +
                    " (reproducible); each resample's median and quartiles by " +
                    quantile_label(options.quantiles) +
                    "; SE = standard deviation of the resampled statistic; interval = its 2.5% "
                    "and 97.5% percentiles (stats/bootstrap.h).");
  t.notes.push_back(
      "A difference between two cells (two platforms, or ours and the paper's) "
      "larger than 3 x sqrt(SE_a^2 + SE_b^2) is unlikely to be sampling noise.");
  return t;
}

stats::Table metric_table(const RunRecords& run, const GroupSummaries& summaries,
                   const MetricTableSpec& spec, QuantileDefinition quantiles) {
  const std::size_t metric = metric_index(spec.kind, spec.column);
  const MetricSpec& m = kind_metrics(spec.kind)[metric];
  const bool supplement = !std::isdigit(static_cast<unsigned char>(spec.number.back()));
  const std::string paper_number =
      spec.number.substr(0, spec.number.find_first_not_of("0123456789"));
  stats::Table t;
  t.file_stem = spec.file_stem;
  const std::string head = "Table " + spec.number + " (" +
                           (supplement ? "supplement to" : "mirrors") + " the paper's Table " +
                           paper_number + "): " + spec.paper_title + " " + m.symbol + ", " +
                           unit_name(m.unit) + ", values ";
  const std::string tail =
      "; median and IQR by view group and platform; quartiles " + quantile_label(quantiles);
  t.title = head + scale_text(spec.scale_exponent) + tail;  // LaTeX typesets x10^k (table_writer)

  const bool planes = planes_vary(run);
  add_view_columns(t, planes);
  for (const std::string& p : run.platforms) {
    t.groups.push_back({p, 2});
    t.columns.push_back({"Median", stats::Align::kRight});
    t.columns.push_back({"IQR", stats::Align::kRight});
  }
  t.groups.insert(t.groups.begin(), stats::ColumnGroup{"", planes ? 5u : 3u});

  const double scale = std::pow(10.0, spec.scale_exponent);
  bool no_data = false;
  for (int g : run.view_groups(spec.kind)) {
    std::vector<stats::TableCell> row;
    add_view_cells(row, *any_group(run, spec.kind, g), planes);
    for (std::size_t p = 0; p < run.platforms.size(); ++p) {
      if (const Description* d = summaries.find(p, spec.kind, metric, g)) {
        row.push_back(stats::number_cell(d->median * scale, spec.decimals));
        row.push_back(stats::number_cell(d->iqr * scale, spec.decimals));
      } else {
        row.push_back(stats::text_cell("no data"));
        row.push_back(stats::text_cell("no data"));
        no_data = true;
      }
    }
    t.rows.push_back(std::move(row));
  }

  t.notes.push_back(std::string("Units: ") + unit_long(m.unit) +
                    (spec.scale_exponent
                         ? "; shown x10^" + std::to_string(spec.scale_exponent) +
                               " (1.000 means 1e-" + std::to_string(spec.scale_exponent) + ")"
                         : "") +
                    ".");
  t.notes.push_back(std::string("Sample: true-visible ") + kind_label_plural(spec.kind) +
                    " with status ok and a value of " + spec.column + ".");
  t.notes.push_back(group_note(run, spec.kind));
  std::uint64_t missing = 0;
  for (const auto& [key, data] : run.views) {
    if (key.kind == spec.kind) missing += data.missing[metric];
  }
  if (missing > 0) {
    t.notes.push_back(std::to_string(missing) + " true-visible records have no value of " +
                      spec.column + " (not measured by the runner that wrote them).");
  }
  if (no_data) {
    t.notes.push_back(
        "no data: no true-visible record of this view group and platform has a "
        "value.");
  }
  if (spec.number == "6") {
    t.notes.push_back(
        "Scale x10^6: the exponent is lost in the paper's extracted text; x10^6 makes its "
        "Platform II medians 0.041-0.046 px in all four views (344.89e-6 x 128 px, 45.39e-6 x 907 "
        "px), below the median LSEu of 0.25 px as abs(mean signed offset) <= mean abs(offset) "
        "requires; "
        "x10^5 would give 0.44 px, above LSEu.");
  }
  if (spec.number == "9") {
    t.notes.push_back(
        "Scale x10^6, as the paper's values imply (IQRs of 1-4.5 px^2 at 128 px, "
        "below the median TEu of 26 px^2).");
  }
  return t;
}

stats::Table physical_units_table(const RunRecords& run, const GroupSummaries& summaries,
                           const TableOptions& options) {
  struct Column {
    geometry::Kind kind;
    const char* metric;
    const char* name;
    int power;  // 1: length, 2: area
    int decimals;
  };
  std::vector<Column> columns;
  const std::vector<geometry::Kind> kinds = run.kinds();
  const auto has = [&](geometry::Kind k) {
    return std::find(kinds.begin(), kinds.end(), k) != kinds.end();
  };
  if (has(geometry::Kind::kPoint))
    columns.push_back({geometry::Kind::kPoint, "pe", "PE (mm)", 1, 3});
  if (has(geometry::Kind::kLine)) {
    columns.push_back({geometry::Kind::kLine, "lse_u", "LSEu (mm)", 1, 3});
  }
  if (has(geometry::Kind::kTriangle)) {
    columns.push_back({geometry::Kind::kTriangle, "te_u", "TEu (mm^2)", 2, 2});
  }

  stats::Table t;
  t.file_stem = "table11_physical_units";
  t.title =
      "Table 11 (mirrors the paper's Table 11): median rendering errors converted to "
      "physical units for pixel pitches of ";
  for (std::size_t i = 0; i < options.pixel_pitches_mm.size(); ++i) {
    t.title += (i ? ", " : "") + util::significant(options.pixel_pitches_mm[i], 6);
  }
  t.title += " mm: PE and LSEu in mm, TEu in mm^2, unscaled; medians, quartiles " +
             quantile_label(options.quantiles);
  t.columns = {{"Pitch (mm)", stats::Align::kRight},
               {"View", stats::Align::kLeft},
               {"FOV", stats::Align::kRight},
               {"Win Size", stats::Align::kRight}};
  t.groups.push_back({"", 4});
  for (const std::string& p : run.platforms) {
    t.groups.push_back({p, columns.size()});
    for (const Column& c : columns) t.columns.push_back({c.name, stats::Align::kRight});
  }

  // all view groups pooled, per platform and column (the paper's overall 0.396 px)
  std::vector<std::vector<std::optional<Description>>> all(
      run.platforms.size(), std::vector<std::optional<Description>>(columns.size()));
  util::run_in_parallel(run.platforms.size() * columns.size(), options.jobs, [&](std::size_t i) {
    const std::size_t p = i / columns.size();
    const Column& c = columns[i % columns.size()];
    all[p][i % columns.size()] = describe_if_any(
        pooled_all(run, p, c.kind, metric_index(c.kind, c.metric)), options.quantiles);
  });

  // view groups of any kind, by number
  std::vector<int> groups;
  for (const ViewGroup& g : run.groups) groups.push_back(g.view_group);
  std::sort(groups.begin(), groups.end());
  groups.erase(std::unique(groups.begin(), groups.end()), groups.end());

  bool no_data = false;
  for (double pitch : options.pixel_pitches_mm) {
    t.rules_before.push_back(t.rows.size());
    for (std::size_t gi = 0; gi <= groups.size(); ++gi) {
      const bool pooled = gi == groups.size();
      std::vector<stats::TableCell> row = {stats::text_cell(util::significant(pitch, 6))};
      if (pooled) {
        row.push_back(stats::text_cell("all"));
        row.push_back(stats::text_cell(""));
        row.push_back(stats::text_cell(""));
      } else {
        const ViewGroup* any = nullptr;
        for (geometry::Kind k : kinds) {
          if (!any) any = any_group(run, k, groups[gi]);
        }
        row.push_back(stats::text_cell(any->label));
        row.push_back(stats::text_cell(util::significant(any->meta().fov_deg, 6)));
        row.push_back(stats::text_cell(window_text(any->meta())));
      }
      for (std::size_t p = 0; p < run.platforms.size(); ++p) {
        for (std::size_t c = 0; c < columns.size(); ++c) {
          const Column& col = columns[c];
          const Description* d =
              pooled ? (all[p][c] ? &*all[p][c] : nullptr)
                     : summaries.find(p, col.kind, metric_index(col.kind, col.metric), groups[gi]);
          if (d) {
            row.push_back(stats::number_cell(d->median * std::pow(pitch, col.power), col.decimals));
          } else {
            row.push_back(stats::text_cell("no data"));
            no_data = true;
          }
        }
      }
      t.rows.push_back(std::move(row));
    }
  }
  t.notes = {
      "mm = median in px x pitch; mm^2 = median in px^2 x pitch^2 (paper section 4: 0.396 px "
      "x 0.255 mm = 0.101 mm). The medians in pixels are in Tables 3, 7s and 10s.",
      "all: every view group of the platform pooled (different windows mixed, as the "
      "paper's overall PE of 0.396 px)."};
  if (no_data) t.notes.push_back("no data: no true-visible record with a value.");
  return t;
}

}  // namespace ra::analysis
