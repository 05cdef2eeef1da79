// Figure data for the plots stage; see figure_data.h.
#include "analysis/figure_data.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>

#include "stats/distribution_plots.h"
#include "stats/hypothesis_tests.h"
#include "analysis/view_equivalence.h"
#include "metrics/headline_metric.h"
#include "rundir/manifest.h"

namespace ra::analysis {
namespace {

using nlohmann::json;

// A finite number for JSON (the statistics never return anything else; if they did, that is a bug
// to report, not a NaN to write).
double finite(double v) {
  if (!std::isfinite(v)) throw std::logic_error("figure_data: a non-finite number");
  return v;
}

double round_significant(double v, int digits) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.*g", digits, finite(v));
  return std::strtod(buf, nullptr);
}

json rounded(const std::vector<double>& v, int digits) {
  json a = json::array();
  for (double x : v) a.push_back(round_significant(x, digits));
  return a;
}

// One side of a comparison.
struct Side {
  std::size_t platform = 0;
  const ViewGroup* group = nullptr;
  const ViewData* view = nullptr;  // a single view, or nullptr: the whole group pooled
  std::vector<double> values(std::size_t metric) const {
    return view ? view->values[metric] : group->pooled(metric);
  }
  json describe(const RunRecords& run) const {
    json views = json::array();
    if (view) {
      views.push_back(view->meta.view);
    } else {
      for (int v : group->view_numbers()) views.push_back(v);
    }
    return json{
        {"platform", run.platforms[platform]}, {"view_group", group->label}, {"views", views}};
  }
};

struct Comparison {
  std::string what;
  std::string figure;
  geometry::Kind kind;
  std::size_t metric;
  Side a, b;
  json result;  // filled in parallel; null when a side has no data
};

json qq_json(std::vector<double> a, std::vector<double> b, const FigureOptions& o) {
  stats::sort_ascending(a);
  stats::sort_ascending(b);
  const std::size_t m = std::min(a.size(), b.size());
  json j{{"n_a", a.size()},
         {"n_b", b.size()},
         {"min_a", finite(a.front())},
         {"max_a", finite(a.back())},
         {"min_b", finite(b.front())},
         {"max_b", finite(b.back())}};
  stats::QQPlotData qq;
  if (m <= o.qq_points_max) {
    qq = stats::qq_plot(std::move(a), std::move(b));
    j["subsampled"] = false;
  } else {
    const std::size_t k = o.qq_points_max;
    for (std::size_t i = 1; i <= k; ++i) {
      const double p = static_cast<double>(i) / static_cast<double>(k + 1);
      qq.p.push_back(p);
      qq.x.push_back(stats::quantile_sorted(a, p, stats::QuantileDefinition::kHyndmanFan6));
      qq.y.push_back(stats::quantile_sorted(b, p, stats::QuantileDefinition::kHyndmanFan6));
    }
    j["subsampled"] = true;
  }
  j["p"] = rounded(qq.p, o.significant_digits);
  j["x"] = rounded(qq.x, o.significant_digits);
  j["y"] = rounded(qq.y, o.significant_digits);
  return j;
}

// The pair's location and spread tests (see the header, "Test").
json test_json(const std::vector<double>& a, const std::vector<double>& b, bool pooled,
               double alpha) {
  json j{{"location", pooled ? "t_pooled" : "t_welch"}, {"alpha", alpha}};
  bool differ = false;
  try {
    const double p = (pooled ? stats::t_test_pooled(a, b) : stats::t_test_welch(a, b)).p_value;
    j["location_p"] = p;
    differ = differ || p < alpha;
  } catch (const std::invalid_argument&) {
    j["location_p"] = nullptr;
  }
  try {
    const double p = stats::levene_test({a, b}, stats::LeveneCenter::kMedian).p_value;
    j["levene_median_p"] = p;
    differ = differ || p < alpha;
  } catch (const std::invalid_argument&) {
    j["levene_median_p"] = nullptr;
  }
  j["differ"] = differ;
  return j;
}

json bihistogram_json(const std::vector<double>& a, const std::vector<double>& b,
                      const FigureOptions& o) {
  const std::vector<double> pooled = merge_sorted({&a, &b});  // a and b are ascending
  const double tail = (1 - o.bihistogram_central_fraction) / 2;
  const double lo = stats::quantile_sorted(pooled, tail, stats::QuantileDefinition::kHyndmanFan6);
  const double hi =
      stats::quantile_sorted(pooled, 1 - tail, stats::QuantileDefinition::kHyndmanFan6);
  const auto central = [&](const std::vector<double>& v) {
    std::vector<double> c;
    for (double x : v) {
      if (lo <= x && x <= hi) c.push_back(x);
    }
    return c;
  };
  std::vector<double> ca = central(a), cb = central(b);
  if (ca.empty() || cb.empty()) {
    ca = a;
    cb = b;
  }
  stats::BihistogramOptions bo;
  bo.max_bins = o.bihistogram_bins_max;
  const stats::BihistogramData h = stats::relative_bihistogram(ca, cb, bo);
  const int d = o.significant_digits;
  return json{{"edges", rounded(h.edges, d)},
              {"count_a", h.count1},
              {"count_b", h.count2},
              {"height_a", rounded(h.height1, d)},
              {"height_b", rounded(h.height2, d)},
              {"bin_width", finite(h.bin_width)},
              {"n_a", h.n1},
              {"n_b", h.n2},
              {"outside_a", a.size() - ca.size()},
              {"outside_b", b.size() - cb.size()}};
}

json box_json(const stats::SampleBoxPlot& s) {
  const stats::BoxPlotData& b = s.box;
  json outliers = json::array();
  for (double x : b.outliers) outliers.push_back(finite(x));
  return json{{"n", b.n},
              {"relative_width", finite(s.relative_width)},
              {"q1", finite(b.q1)},
              {"median", finite(b.median)},
              {"q3", finite(b.q3)},
              {"lower_whisker", finite(b.lower_whisker)},
              {"upper_whisker", finite(b.upper_whisker)},
              {"lower_fence", finite(b.lower_fence)},
              {"upper_fence", finite(b.upper_fence)},
              {"n_outliers_low", b.n_outliers_low},
              {"n_outliers_high", b.n_outliers_high},
              {"outliers", outliers},
              {"outliers_truncated", b.outliers_truncated}};
}

// Two groups of one kind differ only in field of view.
bool differ_only_in_fov(const ViewGroup& a, const ViewGroup& b) {
  const ViewMeta &x = a.meta(), &y = b.meta();
  return x.fov_deg != y.fov_deg && x.width == y.width && x.height == y.height && x.near == y.near &&
         x.far == y.far;
}

std::vector<Comparison> plan_comparisons(const RunRecords& run) {
  std::vector<Comparison> plan;
  const std::size_t platforms = run.platforms.size();
  for (geometry::Kind kind : run.kinds()) {
    const std::size_t headline = std::min<std::size_t>(2, kind_metrics(kind).size());
    for (std::size_t m = 0; m < headline; ++m) {
      for (std::size_t p = 0; p < platforms; ++p) {
        for (const ViewGroup* g : run.groups_of(p, kind)) {
          if (g->views.size() < 2) continue;
          plan.push_back({"orientations",
                          "Fig. 4",
                          kind,
                          m,
                          {p, g, g->views[0]},
                          {p, g, g->views[1]},
                          nullptr});
        }
      }
      for (int gn : run.view_groups(kind)) {
        for (std::size_t a = 0; a < platforms; ++a) {
          for (std::size_t b = a + 1; b < platforms; ++b) {
            const ViewGroup* ga = run.find_group(a, kind, gn);
            const ViewGroup* gb = run.find_group(b, kind, gn);
            if (ga && gb) {
              plan.push_back({"platforms",
                              "Figs. 7, 9, 13",
                              kind,
                              m,
                              {a, ga, nullptr},
                              {b, gb, nullptr},
                              nullptr});
            }
          }
        }
      }
      for (std::size_t p = 0; p < platforms; ++p) {
        const auto groups = run.groups_of(p, kind);
        for (std::size_t i = 0; i < groups.size(); ++i) {
          for (std::size_t j = i + 1; j < groups.size(); ++j) {
            if (differ_only_in_fov(*groups[i], *groups[j])) {
              plan.push_back({"view_groups",
                              "Fig. 11",
                              kind,
                              m,
                              {p, groups[i], nullptr},
                              {p, groups[j], nullptr},
                              nullptr});
            }
          }
        }
      }
      const auto first = run.groups_of(0, kind);
      const auto last = run.groups_of(platforms - 1, kind);
      if (!first.empty() && !last.empty() && first.front() != last.back()) {
        plan.push_back({"first_last",
                        "Fig. 5",
                        kind,
                        m,
                        {0, first.front(), nullptr},
                        {platforms - 1, last.back(), nullptr},
                        nullptr});
      }
    }
  }
  return plan;
}

std::string comparison_id(const RunRecords& run, const Comparison& c) {
  const auto side = [&](const Side& s) {
    std::string id = run.platforms[s.platform] + "." + s.group->label;
    if (s.view) id += ".v" + std::to_string(s.view->meta.view);
    return id;
  };
  return std::string(kind_name(c.kind)) + "." + kind_metrics(c.kind)[c.metric].column + "." +
         c.what + "." + side(c.a) + "-" + side(c.b);
}

// Median and quartiles of an ascending sample under the run's quantile definition, as
// {"median"SUFFIX, "q1"SUFFIX, "q3"SUFFIX} (nulls when the sample is empty: nothing to describe).
void quartiles_json(json& j, const std::vector<double>& ascending, const std::string& suffix,
                    stats::QuantileDefinition q) {
  if (ascending.empty()) {
    j["median" + suffix] = nullptr;
    j["q1" + suffix] = nullptr;
    j["q3" + suffix] = nullptr;
    return;
  }
  const stats::Description d = describe_sorted(ascending, q);
  j["median" + suffix] = finite(d.median);
  j["q1" + suffix] = finite(d.q1);
  j["q3" + suffix] = finite(d.q3);
}

// One kind's speed-against-error points: per platform and view group, the render time of every
// `ok` record with a time (speed_table's data) beside the normalised unsigned error.
json speed_error_json(const RunRecords& run, geometry::Kind kind, const FigureOptions& o) {
  const char* column = speed_error_metric(kind);
  const std::size_t metric = metric_index(kind, column);
  const MetricSpec& spec = kind_metrics(kind)[metric];
  json points = json::array();
  for (std::size_t p = 0; p < run.platforms.size(); ++p) {
    for (const ViewGroup* g : run.groups_of(p, kind)) {
      std::vector<const std::vector<double>*> time, error;
      for (const ViewData* view : g->views) {
        time.push_back(&view->render_us_visible);
        time.push_back(&view->render_us_other);
        error.push_back(&view->values[metric]);
      }
      const std::vector<double> t = merge_sorted(time), e = merge_sorted(error);
      if (t.empty() && e.empty()) continue;
      json pt{{"platform", run.platforms[p]},
              {"view_group", g->label},
              {"views", g->view_numbers()},
              {"fov_deg", g->meta().fov_deg},
              {"width", g->meta().width},
              {"height", g->meta().height},
              {"n_time", t.size()}};
      quartiles_json(pt, t, "_us", o.quantiles);
      pt["n_error"] = e.size();
      pt["metric"] = column;
      quartiles_json(pt, e, "_error", o.quantiles);
      points.push_back(std::move(pt));
    }
  }
  return json{{"kind", kind_name(kind)},
              {"metric", column},
              {"symbol", spec.symbol},
              {"units", unit_name(spec.unit)},
              {"time_units", "us"},
              {"points", std::move(points)}};
}

}  // namespace

const char* speed_error_metric(geometry::Kind kind) { return metrics::headline_norm_column(kind); }

json figure_data(const RunRecords& run, const FigureOptions& options) {
  json doc = rundir::document_header("figures", kFiguresSchemaVersion, false);
  doc["run_dir"] = run.run_dir;
  doc["platforms"] = run.platforms;
  doc["quantile_definition"] = stats::quantile_definition_name(options.quantiles);
  doc["limits"] = {{"qq_points_max", options.qq_points_max},
                   {"box_plot_outliers_max", options.box_plot_outliers_max},
                   {"bihistogram_bins_max", options.bihistogram_bins_max},
                   {"bihistogram_central_fraction", options.bihistogram_central_fraction},
                   {"significant_digits", options.significant_digits}};

  // box plots: one figure per kind and metric
  struct BoxFigure {
    geometry::Kind kind;
    std::size_t metric;
    json result;
  };
  std::vector<BoxFigure> boxes;
  for (geometry::Kind kind : run.kinds()) {
    for (std::size_t m = 0; m < kind_metrics(kind).size(); ++m) boxes.push_back({kind, m, nullptr});
  }
  std::vector<Comparison> plan = plan_comparisons(run);

  util::run_in_parallel(boxes.size() + plan.size(), options.jobs, [&](std::size_t i) {
    if (i < boxes.size()) {
      BoxFigure& f = boxes[i];
      const MetricSpec& spec = kind_metrics(f.kind)[f.metric];
      std::vector<const ViewGroup*> groups;
      std::vector<std::vector<double>> samples;
      for (const ViewGroup& g : run.groups) {
        if (g.kind != f.kind || g.count(f.metric) == 0) continue;
        groups.push_back(&g);
        samples.push_back(g.pooled(f.metric));
      }
      json list = json::array();
      if (!samples.empty()) {
        const auto plots =
            stats::box_plots(samples, options.quantiles, options.box_plot_outliers_max);
        for (std::size_t s = 0; s < plots.size(); ++s) {
          const ViewGroup& g = *groups[s];
          json box{{"platform", run.platforms[g.platform]},
                   {"view_group", g.label},
                   {"views", g.view_numbers()},
                   {"fov_deg", g.meta().fov_deg},
                   {"width", g.meta().width},
                   {"height", g.meta().height}};
          box.update(box_json(plots[s]));
          list.push_back(std::move(box));
        }
      }
      f.result = json{{"kind", kind_name(f.kind)},
                      {"metric", spec.column},
                      {"symbol", spec.symbol},
                      {"units", unit_name(spec.unit)},
                      {"boxes", list}};
      return;
    }
    Comparison& c = plan[i - boxes.size()];
    const std::vector<double> a = c.a.values(c.metric), b = c.b.values(c.metric);
    if (a.empty() || b.empty()) return;  // no data: omitted
    const MetricSpec& spec = kind_metrics(c.kind)[c.metric];
    c.result = json{{"id", comparison_id(run, c)},
                    {"figure", c.figure},
                    {"what", c.what},
                    {"kind", kind_name(c.kind)},
                    {"metric", spec.column},
                    {"symbol", spec.symbol},
                    {"units", unit_name(spec.unit)},
                    {"a", c.a.describe(run)},
                    {"b", c.b.describe(run)},
                    {"qq", qq_json(a, b, options)},
                    {"bihistogram", bihistogram_json(a, b, options)},
                    {"test", test_json(a, b, c.what == "orientations", options.alpha)}};
  });

  json box_list = json::array();
  for (BoxFigure& f : boxes) box_list.push_back(std::move(f.result));
  json comparisons = json::array();
  for (Comparison& c : plan) {
    if (!c.result.is_null()) comparisons.push_back(std::move(c.result));
  }
  doc["box_plots"] = std::move(box_list);
  doc["comparisons"] = std::move(comparisons);
  json speed = json::array();
  for (geometry::Kind kind : run.kinds()) speed.push_back(speed_error_json(run, kind, options));
  doc["speed_error"] = std::move(speed);
  return doc;
}

}  // namespace ra::analysis
