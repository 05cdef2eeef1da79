// The numbers behind the paper's figures, written as DIR/analysis/figures.json for the plots stage
// (which draws them; nothing is drawn here). Box plots (Figs. 6, 8, 10, 12), quantile-quantile
// plots (Fig. 4) and relative bihistograms (Figs. 5, 7, 9, 11, 13) come from
// stats/distribution_plots.h; NIST e-Handbook 1.3.3.7, 1.3.3.24, 1.3.3.2.
//
// figures.json, schema "renderaudit-figures", schema_version 1:
// {
//   "schema": "renderaudit-figures", "schema_version": 1,
//   "run_dir": "...", "platforms": ["..."],            // platforms in name order (I, II, ...)
//   "quantile_definition": "hyndman_fan_6",            // box quartiles (--quantiles); Q-Q: HF6
//   "limits": {"qq_points_max": 2000, "box_plot_outliers_max": 500, "bihistogram_bins_max": 200,
//              "bihistogram_central_fraction": 0.99, "significant_digits": 7},
//   "box_plots": [                      // one figure per kind and metric (every metric)
//     {"kind": "line", "metric": "lse_s_norm", "symbol": "LSEs-norm", "units": "sqrt(W*H) units",
//      "boxes": [                       // per platform, then view group; empty samples omitted
//        {"platform": "...", "view_group": "A", "views": [1, 2], "fov_deg": 30, "width": 128,
//         "height": 128, "n": 20540, "relative_width": 0.16,   // n / largest n in the figure
//         "q1": .., "median": .., "q3": .., "lower_whisker": .., "upper_whisker": ..,
//         "lower_fence": .., "upper_fence": .., "n_outliers_low": 0, "n_outliers_high": 12,
//         "outliers": [..], "outliers_truncated": false}]}],    // at most 500 most extreme
//   "comparisons": [                    // pairs of samples, the paper's headline metrics only
//     {"id": "point.pe.orientations.osmesa-llvmpipe.A",
//      "figure": "Fig. 4",              // the paper figure it is like
//      "what": "orientations",          // "orientations": the first two orientation views of a
//                                       //   group (Fig. 4); "platforms": one group on two
//                                       platforms
//                                       //   (Figs. 7, 9, 13); "view_groups": two groups of one
//                                       //   platform differing only in FOV (Fig. 11);
//                                       //   "first_last": first group of the first platform vs
//                                       last
//                                       //   group of the last platform (Fig. 5)
//      "kind": "point", "metric": "pe", "symbol": "PE", "units": "px",
//      "a": {"platform": "...", "view_group": "A", "views": [1]}, "b": {...},
//      "qq": {"n_a": .., "n_b": .., "subsampled": bool, "p": [..], "x": [..], "y": [..],
//             "min_a": .., "max_a": .., "min_b": .., "max_b": ..},
//      "bihistogram": {"edges": [..], "count_a": [..], "count_b": [..], "height_a": [..],
//                      "height_b": [..], "bin_width": .., "n_a": .., "n_b": ..,
//                      "outside_a": .., "outside_b": ..},
//      "test": {"location": "t_pooled" | "t_welch", "location_p": .., "levene_median_p": ..,
//               "alpha": 0.05, "differ": bool}}],  // p null where a test is undefined
//   "speed_error": [                    // render time against error: one entry per kind
//     {"kind": "line", "metric": "lse_u_norm", "symbol": "LSEu-norm", "units": "sqrt(W*H) units",
//      "time_units": "us",
//      "points": [                      // per platform, then view group (every condition)
//        {"platform": "...", "view_group": "A", "views": [1, 2], "fov_deg": 30, "width": 128,
//         "height": 128,
//         "n_time": 4000,               // status ok records with a render time (any visibility)
//         "median_us": .., "q1_us": .., "q3_us": ..,          // render_us of those; null if none
//         "n_error": 3850,              // true-visible ok records with a value of the metric
//         "metric": "lse_u_norm", "median_error": .., "q1_error": .., "q3_error": ..}]}]
// }
// Q-Q: with m = min(n_a, n_b) <= 2000 the Dataplot convention of distribution_plots.h (x = a, y =
// b); above that, the Hyndman-Fan 6 quantiles of both samples at p_i = i / 2001, i = 1..2000 (the
// same convention on a grid), so a plot has at most 2000 points; min and max are given apart.
// Bihistogram: relative (each side has area 1) over the central 99% of the pooled pair (HF6
// quantiles 0.005 and 0.995; values outside are counted in outside_a / outside_b, so a few extreme
// outliers cannot squeeze the body into one bin; the whole range when that leaves a side empty),
// Freedman-Diaconis bins, at most 200. Arrays of plot coordinates are rounded to 7 significant
// digits; summary numbers (quartiles, fences) are exact. Comparisons cover the paper's headline
// metrics, the first two of each kind in run_records.h (PE, PEnorm; LSEs-norm, LSEu-norm;
// TEs-norm, TEu-norm); box plots cover every metric.
// Test: what each pair's figure is read for, decided as the view-equivalence analysis decides it:
// the samples differ when the location test or Levene's test (median centre) gives p < alpha on
// the raw values. Orientation pairs use the pooled t test (view_equivalence.h: the same verdict
// as its table), other pairs Welch's (their spreads need not be equal).
// Speed against error: the time is render_us (CPU us of draw + glFinish; for primitives drawn in a
// batch, an equal share of the batch's time: records column batch_size) over every `ok` record of
// the group with a time, as speed_table (paper_tables.h) counts its "Cases"; the error is the
// kind's normalised unsigned metric (PEnorm, LSEu-norm, TEu-norm: speed_error_metric()), so that
// groups with different windows share one error axis. Quartiles by `quantiles`, as the box plots;
// numbers exact. A group with neither a time nor an error value is left out; a point lacking one
// of the two has nulls for that side's statistics (median, q1, q3).
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>

#include "stats/descriptive.h"
#include "analysis/run_records.h"

namespace ra::analysis {

constexpr int kFiguresSchemaVersion = 1;

struct FigureOptions {
  stats::QuantileDefinition quantiles = stats::QuantileDefinition::kHyndmanFan6;
  std::size_t qq_points_max = 2000;
  std::size_t box_plot_outliers_max = 500;
  std::size_t bihistogram_bins_max = 200;
  double bihistogram_central_fraction = 0.99;
  int significant_digits = 7;
  unsigned jobs = 0;  // threads; 0: the number of cores
  double alpha = 0.05;  // significance level of each comparison's "test" (analyze --alpha)
};

// The records column of the error the speed-against-error points use for `kind`: its normalised
// unsigned metric, the headline error over the window (metrics/headline_metric.h: "pe_norm", ...).
const char* speed_error_metric(geometry::Kind kind);

// The whole figures.json document for a run.
nlohmann::json figure_data(const RunRecords& run, const FigureOptions& options = {});

}  // namespace ra::analysis
