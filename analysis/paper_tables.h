// The tables of the paper's section 4, built from a run's records: visibility counts (Tables 2, 5,
// 8), median and IQR of each error metric by view group and platform (Tables 3, 4, 6, 7, 9, 10,
// plus supplements for the non-normalized metrics), medians in physical units (Table 11), render
// time beside error, and the comparison of platforms per view group and metric.
//
// Layout follows the paper: one row per view group (A, B, C, D: the orientation views pooled, see
// view_equivalence.h) with its field of view and window, one column block (Median, IQR) per
// platform; platforms in name order. Near and far columns appear when the groups differ in them.
//
// Samples: true-visible primitives with status `ok` whose metric cell is not empty. A cell with no
// such value says "no data"; nothing is ever NaN. Quartiles by the chosen Hyndman-Fan definition
// (default 6, the NIST e-Handbook's and Dataplot's, which the paper's authors used).
//
// Scales (values shown = metric x 10^k, as the paper prints them):
//   Table 3  PE          px                 x1      5 decimals
//   Table 4  PEnorm      sqrt(W*H) units    x10^3   3 decimals
//   Table 6  LSEs-norm   sqrt(W*H) units    x10^6   2 decimals  (see below)
//   Table 7  LSEu-norm   sqrt(W*H) units    x10^3   3 decimals
//   Table 9  TEs-norm    W*H units          x10^6   2 decimals
//   Table 10 TEu-norm    W*H units          x10^3   3 decimals
// Table 6's exponent is lost in the paper's extracted text. x10^6 is the one its numbers allow:
// Platform II's medians are then 0.041-0.046 px in all four views (344.89e-6 x 128 px = 0.044 px,
// 45.39e-6 x 907 px = 0.041 px), a bias independent of the window, as sub-pixel snapping of the end
// points would give, and below that platform's median LSEu of 0.25 px (Table 7), as they must be
// (|mean signed offset| <= mean |offset|). At x10^5 they would be 0.44 px, above LSEu. Table 9's
// x10^6 likewise keeps its IQRs (1-4.5 px^2 at 128 px) below the median TEu (26 px^2, Table 10).
#pragma once

#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "stats/bootstrap.h"
#include "stats/descriptive.h"
#include "analysis/paper_values.h"
#include "analysis/run_records.h"
#include "stats/table_writer.h"
#include "analysis/view_equivalence.h"

namespace ra::analysis {

// One of the paper's metric tables (or a supplement in the same layout).
struct MetricTableSpec {
  std::string number;  // "3", "6", "6s" (supplement): names the paper table it mirrors
  geometry::Kind kind;
  const char* column;       // records column
  int scale_exponent;       // values shown = metric x 10^scale_exponent
  int decimals;             // decimals shown (Markdown, LaTeX)
  std::string paper_title;  // the paper's caption, or the supplement's
  std::string file_stem;    // "table03_pe"
};

// Tables 3, 4, 6, 7, 9, 10 and the supplements 6s (LSEs, px), 7s (LSEu, px), 9s (TEs, px^2),
// 10s (TEu, px^2), 10e (TEu-edge-norm, px), in that order.
const std::vector<MetricTableSpec>& metric_table_specs();

struct TableOptions {
  stats::QuantileDefinition quantiles = stats::QuantileDefinition::kHyndmanFan6;
  std::vector<double> pixel_pitches_mm = {0.255};  // Table 11; the paper's LCD: 0.255 mm
  double alpha = 0.05;                             // cross-platform "differs" columns
  ComparisonOptions comparison;                    // Box-Cox subsample
  unsigned jobs = 0;                               // threads; 0: the number of cores
  // Bootstrap standard errors and intervals of every median and IQR (the uncertainty table);
  // resamples 0: none computed. Its quantile definition follows `quantiles`.
  stats::BootstrapOptions bootstrap;
  // The paper's published values (paper_values.h); empty: no comparison with the paper.
  std::vector<PaperTableValues> paper;
  std::vector<PaperDifference> paper_differences;  // established reasons, paper_differences_table
  double paper_primitives_per_group = 0;  // behind each paper cell; 0: z uses our SE alone
};

// Description (n, median, quartiles, ...) of every pooled view-group sample of the run, computed
// once (in parallel) and shared by the tables. Absent: the sample is empty.
class GroupSummaries {
 public:
  // bootstrap.resamples > 0: also the bootstrap of each sample's median and IQR.
  GroupSummaries(const RunRecords& run, stats::QuantileDefinition quantiles, unsigned jobs,
                 stats::BootstrapOptions bootstrap = {0});
  const stats::Description* find(std::size_t platform, geometry::Kind kind, std::size_t metric,
                                 int view_group) const;
  const stats::MedianIqrBootstrap* bootstrap(std::size_t platform, geometry::Kind kind,
                                             std::size_t metric, int view_group) const;

 private:
  std::map<std::tuple<std::size_t, int, std::size_t, int>, stats::Description> d_;
  std::map<std::tuple<std::size_t, int, std::size_t, int>, stats::MedianIqrBootstrap> b_;
};

// "Hyndman-Fan 6 (NIST e-Handbook, Dataplot)" / "Hyndman-Fan 7 (R, NumPy default)".
std::string quantile_label(stats::QuantileDefinition q);

// Table 2 (points), 5 (lines) or 8 (triangles): visibility-class counts by platform and view group.
stats::Table visibility_table(const RunRecords& run, geometry::Kind kind);
// Its supplement (table02s, 05s, 08s): each class as a percentage of the group's ok records with
// its Clopper-Pearson 95% interval.
stats::Table visibility_share_table(const RunRecords& run, geometry::Kind kind);

// A metric table: median and IQR by view group (rows) and platform (column blocks).
stats::Table metric_table(const RunRecords& run, const GroupSummaries& summaries,
                   const MetricTableSpec& spec, stats::QuantileDefinition quantiles);

// The uncertainty of Tables 3, 4, 6, 7, 9 and 10: for each table, view group and platform, n, the
// median and the IQR (scaled as in its table), each with its bootstrap standard error and 95%
// percentile interval (stats/bootstrap.h; resample count and seed in the notes).
stats::Table uncertainty_table(const RunRecords& run, const GroupSummaries& summaries,
                        const TableOptions& options);

// Our tables beside the paper's: for each of its tables, statistic (median, IQR), view group whose
// FOV and window are the paper's, and platform of the run: ours and its bootstrap SE, the paper's
// Platform I and II, and z = (ours - paper) / SE, marked when |z| > 3. Needs the bootstrap.
stats::Table paper_comparison_table(const RunRecords& run, const GroupSummaries& summaries,
                             const TableOptions& options);

// "Where we differ from the paper and why": the cells of paper_comparison_table beyond 3 SE of
// each of the paper's platforms that gives a value, each citing the first of
// options.paper_differences that covers it ("not explained" otherwise); the explanations are the
// notes, numbered in citation order.
stats::Table paper_differences_table(const RunRecords& run, const GroupSummaries& summaries,
                              const TableOptions& options);

// Table 11: medians of PE (mm), LSEu (mm) and TEu (mm^2) for each pixel pitch (mm) and view group
// (and all groups pooled), per platform: mm = px x pitch, mm^2 = px^2 x pitch^2.
stats::Table physical_units_table(const RunRecords& run, const GroupSummaries& summaries,
                           const TableOptions& options);

// Render time beside error: per platform, kind and view group (and all pooled), the median and IQR
// of render_us over all `ok` cases and over the true-visible ones, next to the median and IQR of
// the kind's headline error (PE px, LSEu px, TEu px^2).
stats::Table speed_table(const RunRecords& run, const TableOptions& options);

// Two platforms compared on one kind, metric and view group.
struct PlatformComparison {
  geometry::Kind kind = geometry::Kind::kPoint;
  std::size_t metric = 0;
  int view_group = 0;
  std::string label;
  std::size_t platform_a = 0, platform_b = 0;
  std::optional<stats::Description> a, b;  // absent: no data
  SampleComparison comparison;             // only when both have data
};

// Every pair of platforms (a < b), kind, metric and view group both have; empty with one platform.
std::vector<PlatformComparison> compare_platforms(const RunRecords& run,
                                                  const GroupSummaries& summaries,
                                                  const TableOptions& options);

// The comparisons as one table: medians, IQRs, their differences (a - b, metric units), pooled and
// Welch t, F, Levene (median) p-values on raw and Box-Cox data, and "differs" flags at alpha
// (location: Welch t; spread: Levene median).
stats::Table cross_platform_table(const RunRecords& run, const std::vector<PlatformComparison>& rows,
                           const TableOptions& options);

// Every table above that the run has data for, in paper order: 2, 3, 4, 5, 6, 7, 8, 9, 10 (each
// kind's tables only when the run has records of that kind), the supplements, 11, speed, and the
// cross-platform comparison when there is more than one platform.
std::vector<stats::Table> paper_tables(const RunRecords& run, const TableOptions& options);

}  // namespace ra::analysis
