// The paper's tables from a run's records (see paper_tables.h): the table specifications, the
// per-group summaries they share, and paper_tables, which assembles them in the report's order.
// Each family of tables has its file: visibility_tables, metric_tables, paper_comparison_tables,
// speed_table, platform_comparison_table.
#include "analysis/paper_tables.h"

#include <algorithm>
#include <cctype>

#include "analysis/paper_table_parts.h"

namespace ra::analysis {

using namespace table_parts;
using stats::Description;
using stats::QuantileDefinition;

std::string quantile_label(QuantileDefinition q) {
  return q == QuantileDefinition::kHyndmanFan6 ? "Hyndman-Fan 6 (NIST e-Handbook, Dataplot)"
                                               : "Hyndman-Fan 7 (R, NumPy default)";
}

const std::vector<MetricTableSpec>& metric_table_specs() {
  using K = geometry::Kind;
  static const std::vector<MetricTableSpec> specs = {
      {"3", K::kPoint, "pe", 0, 5, "Summary of non-normalized point rendering errors",
       "table03_pe"},
      {"4", K::kPoint, "pe_norm", 3, 3, "Summary of normalized point rendering errors",
       "table04_pe_norm"},
      {"6", K::kLine, "lse_s_norm", 6, 2,
       "Summary of normalized signed line segment rendering errors", "table06_lse_s_norm"},
      {"7", K::kLine, "lse_u_norm", 3, 3,
       "Summary of normalized unsigned line segment rendering errors", "table07_lse_u_norm"},
      {"9", K::kTriangle, "te_s_norm", 6, 2,
       "Summary of normalized signed triangle rendering errors", "table09_te_s_norm"},
      {"10", K::kTriangle, "te_u_norm", 3, 3,
       "Summary of normalized unsigned triangle rendering errors", "table10_te_u_norm"},
      {"6s", K::kLine, "lse_s", 0, 4, "Summary of non-normalized signed line segment errors",
       "table06s_lse_s"},
      {"7s", K::kLine, "lse_u", 0, 4, "Summary of non-normalized unsigned line segment errors",
       "table07s_lse_u"},
      {"9s", K::kTriangle, "te_s", 0, 3, "Summary of non-normalized signed triangle errors",
       "table09s_te_s"},
      {"10s", K::kTriangle, "te_u", 0, 3, "Summary of non-normalized unsigned triangle errors",
       "table10s_te_u"},
      {"10e", K::kTriangle, "te_u_edge_norm", 0, 4,
       "Summary of unsigned triangle errors per pixel of visible edge", "table10e_te_u_edge_norm"},
  };
  return specs;
}

GroupSummaries::GroupSummaries(const RunRecords& run, QuantileDefinition quantiles, unsigned jobs,
                               stats::BootstrapOptions bootstrap) {
  bootstrap.definition = quantiles;
  struct Task {
    const ViewGroup* group;
    std::size_t metric;
  };
  std::vector<Task> tasks;
  for (const ViewGroup& g : run.groups) {
    for (std::size_t m = 0; m < kind_metrics(g.kind).size(); ++m) tasks.push_back({&g, m});
  }
  std::vector<std::optional<Description>> out(tasks.size());
  std::vector<std::optional<stats::MedianIqrBootstrap>> boot(tasks.size());
  util::run_in_parallel(tasks.size(), jobs, [&](std::size_t i) {
    const std::vector<double> sample = tasks[i].group->pooled(tasks[i].metric);  // ascending
    out[i] = describe_if_any(sample, quantiles);
    if (out[i] && bootstrap.resamples > 0) boot[i] = stats::bootstrap_median_iqr(sample, bootstrap);
  });
  for (std::size_t i = 0; i < tasks.size(); ++i) {
    if (!out[i]) continue;
    const ViewGroup& g = *tasks[i].group;
    const auto key =
        std::make_tuple(g.platform, static_cast<int>(g.kind), tasks[i].metric, g.view_group);
    d_.emplace(key, *out[i]);
    if (boot[i]) b_.emplace(key, *boot[i]);
  }
}

const Description* GroupSummaries::find(std::size_t platform, geometry::Kind kind,
                                        std::size_t metric, int view_group) const {
  const auto it = d_.find(std::make_tuple(platform, static_cast<int>(kind), metric, view_group));
  return it == d_.end() ? nullptr : &it->second;
}

const stats::MedianIqrBootstrap* GroupSummaries::bootstrap(std::size_t platform,
                                                           geometry::Kind kind, std::size_t metric,
                                                           int view_group) const {
  const auto it = b_.find(std::make_tuple(platform, static_cast<int>(kind), metric, view_group));
  return it == b_.end() ? nullptr : &it->second;
}

std::vector<stats::Table> paper_tables(const RunRecords& run, const TableOptions& options) {
  const GroupSummaries summaries(run, options.quantiles, options.jobs, options.bootstrap);
  const std::vector<geometry::Kind> kinds = run.kinds();
  const auto has = [&](geometry::Kind k) {
    return std::find(kinds.begin(), kinds.end(), k) != kinds.end();
  };
  std::vector<stats::Table> tables;
  const auto metric_tables = [&](geometry::Kind kind, bool supplements) {
    for (const MetricTableSpec& spec : metric_table_specs()) {
      const bool is_supplement = !std::isdigit(static_cast<unsigned char>(spec.number.back()));
      if (spec.kind == kind && is_supplement == supplements) {
        tables.push_back(metric_table(run, summaries, spec, options.quantiles));
        if (!is_supplement && options.bootstrap.resamples > 0)
          tables.back().notes.push_back(
              "The bootstrap standard error and 95% interval of every "
              "cell: uncertainty.md.");
      }
    }
  };
  for (geometry::Kind kind : kAllKinds) {
    if (!has(kind)) continue;
    tables.push_back(visibility_table(run, kind));
    tables.push_back(visibility_share_table(run, kind));
    metric_tables(kind, false);
  }
  for (geometry::Kind kind : kAllKinds) {
    if (has(kind)) metric_tables(kind, true);
  }
  if (!kinds.empty() && options.bootstrap.resamples > 0)
    tables.push_back(uncertainty_table(run, summaries, options));
  if (!kinds.empty() && options.bootstrap.resamples > 0 && !options.paper.empty()) {
    stats::Table comparison = paper_comparison_table(run, summaries, options);
    if (!comparison.rows.empty()) {
      tables.push_back(std::move(comparison));
      tables.push_back(paper_differences_table(run, summaries, options));
    }
  }
  if (!kinds.empty()) tables.push_back(physical_units_table(run, summaries, options));
  if (!kinds.empty()) tables.push_back(speed_table(run, options));
  if (run.platforms.size() > 1) {
    tables.push_back(
        cross_platform_table(run, compare_platforms(run, summaries, options), options));
  }
  return tables;
}

}  // namespace ra::analysis
