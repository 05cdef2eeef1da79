// The distributions of a primitive kind's metrics: box plots and histograms per platform and view group (figure_planner.h).
#include "plots/figure_planner.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <sstream>

#include "analysis/paper_tables.h"
#include "plots/figure_builders.h"
#include "metrics/records.h"
#include "util/number_text.h"

namespace ra::plots {
namespace {

using nlohmann::json;

struct DistributionFigures : FigurePlanner {
  // A group's box plots need an axis of their own when the view groups' whisker spans differ by
  // more than this factor: on a shared axis the smaller groups are flat lines (TEs-norm in the
  // 907 x 907 groups against the 128 x 128 ones).
  static constexpr double kSharedAxisSpanRatio = 10;

  void box_plots(geometry::Kind kind) {
    const std::string section = section_of(kind);
    for (const json& bp : doc.value("box_plots", json::array())) {
      if (bp.value("kind", "") != an::kind_name(kind)) continue;
      const std::string column = bp.value("metric", ""), symbol = bp.value("symbol", column);
      const json& boxes = bp.at("boxes");
      if (boxes.empty()) {
        skip(section, "box plot of " + symbol, "no true-visible " + section + " with a value");
        continue;
      }
      // the whisker span of each view group, in record units
      std::map<std::string, double> span;
      for (const json& b : boxes) {
        double& g = span[b.value("view_group", "?")];
        g = std::max(g, b.at("upper_whisker").get<double>() - b.at("lower_whisker").get<double>());
      }
      double smallest = 0, largest = 0;
      for (const auto& [g, w] : span)
        if (w > 0) smallest = smallest > 0 ? std::min(smallest, w) : w, largest = std::max(largest, w);
      const bool split = span.size() > 1 && smallest > 0 && largest > kSharedAxisSpanRatio * smallest;
      if (!split) {
        std::vector<const json*> all;
        for (const json& b : boxes) all.push_back(&b);
        add(box_plot(kind, bp, all, ""));
        continue;
      }
      for (const auto& [g, w] : span) {
        std::vector<const json*> of_group;
        for (const json& b : boxes)
          if (b.value("view_group", "?") == g) of_group.push_back(&b);
        Figure f = box_plot(kind, bp, of_group, g);
        f.caption += " One figure per view group: their whisker spans differ by a factor of " +
                     util::fixed(largest / smallest, 0) + ", so a shared axis would flatten the "
                     "smaller ones.";
        add(std::move(f));
      }
    }
  }

  // The box plot of `chosen` boxes of one metric (all view groups, or the one named `group`).
  Figure box_plot(geometry::Kind kind, const json& bp, const std::vector<const json*>& chosen,
                  const std::string& group) {
    const std::string column = bp.value("metric", ""), symbol = bp.value("symbol", column),
                      units = bp.value("units", "");
    BoxPlotContent c;
    double max_abs = 0;
    for (const json* b : chosen)
      max_abs = std::max({max_abs, std::fabs(b->at("q1").get<double>()),
                          std::fabs(b->at("q3").get<double>())});
    // a shared axis keeps the tables' exponent; a group of its own gets the one its values need
    int e = group.empty() ? table_exponent(column) : -1;
    if (e < 0) e = display_exponent(max_abs);
    const double scale = std::pow(10.0, e);
    std::vector<std::string> group_labels;
    for (const std::string& p : doc.value("platforms", std::vector<std::string>{}))
      for (const json* b : chosen)
        if (b->value("platform", "") == p &&
            std::find(c.series.begin(), c.series.end(), p) == c.series.end())
          c.series.push_back(p);
    std::map<std::string, std::string> category_of;
    for (const json* b : chosen) {
      const std::string g = b->value("view_group", "?");
      if (!category_of.count(g))
        category_of[g] = g + ": " + util::significant(b->value("fov_deg", 0.0), 6) + " deg, " +
                         std::to_string(b->value("width", 0)) + "x" +
                         std::to_string(b->value("height", 0));
    }
    for (const auto& [g, label] : category_of) {
      c.categories.push_back(label);
      group_labels.push_back(g);
    }
    for (const json* b : chosen) {
      Box x;
      x.category = category_of[b->value("view_group", "?")];
      x.series = b->value("platform", "");
      x.n = b->value("n", std::size_t(0));
      x.q1 = b->at("q1").get<double>() * scale;
      x.median = b->at("median").get<double>() * scale;
      x.q3 = b->at("q3").get<double>() * scale;
      x.lower_whisker = b->at("lower_whisker").get<double>() * scale;
      x.upper_whisker = b->at("upper_whisker").get<double>() * scale;
      x.min = x.lower_whisker, x.max = x.upper_whisker;
      for (const json& o : b->value("outliers", json::array())) {
        x.min = std::min(x.min, o.get<double>() * scale);
        x.max = std::max(x.max, o.get<double>() * scale);
      }
      x.n_outliers_low = b->value("n_outliers_low", std::size_t(0));
      x.n_outliers_high = b->value("n_outliers_high", std::size_t(0));
      c.boxes.push_back(x);
    }
    Figure f;
    f.id = "boxplot." + std::string(an::kind_name(kind)) + "." + column +
           (group.empty() ? "" : "." + group);
    f.title = box_plot_title(symbol, c) + ": " + join(c.series, ", ") + ", " +
              groups_phrase(group.empty() ? group_labels : std::vector<std::string>{group});
    f.x_label = "view group (field of view, window)";
    f.y_label = axis_label(symbol, units, e);
    const bool one = c.boxes.size() == 1;
    f.caption = (one ? "Box plot of " + symbol + " for view group " + group_labels.front() +
                           " on " + c.series.front()
                     : "Box plots of " + symbol + " for " +
                           (group.empty() ? "each view group" : "view group " + group) +
                           (c.series.size() > 1 ? " and platform" : " on " + c.series.front())) +
                " (quartiles " + doc.value("quantile_definition", std::string("hyndman_fan_6")) +
                "; whiskers to the most extreme values within 1.5 IQR); " +
                (one ? "" : "box widths proportional to the number of measurements; ") +
                "the y range is restricted to the " + (one ? "box's body" : "box bodies") +
                " as in the paper's Figs. 6, 8, 10 and 12.";
    f.section = section_of(kind);
    f.content = std::move(c);
    return f;
  }

  void histograms(geometry::Kind kind) {
    const std::string section = section_of(kind);
    const auto& metrics = an::kind_metrics(kind);
    for (std::size_t p = 0; p < run.platforms.size(); ++p) {
      const auto groups = run.groups_of(p, kind);
      if (groups.empty()) continue;
      for (std::size_t m = 0; m < metrics.size(); ++m) {
        std::vector<NamedSample> samples;
        std::vector<std::string> labels;
        double max_abs = 0;
        for (const an::ViewGroup* g : groups) {
          NamedSample s{group_label(*g), g->pooled(m)};
          if (s.values.empty()) continue;
          for (double v : s.values) max_abs = std::max(max_abs, std::fabs(v));
          labels.push_back(g->label);
          samples.push_back(std::move(s));
        }
        const std::string what = "histogram of " + std::string(metrics[m].symbol) + " on " +
                                 run.platforms[p];
        if (samples.empty()) {
          skip(section, what, "no true-visible " + section + " with a value");
          continue;
        }
        int e = table_exponent(metrics[m].column);
        if (e < 0) e = display_exponent(max_abs);
        Figure f = histogram_figure(
            "histogram." + std::string(an::kind_name(kind)) + "." + metrics[m].column + "." +
                run.platforms[p],
            "Histogram of " + std::string(metrics[m].symbol) + ": " + run.platforms[p] +
                ", " + groups_phrase(labels),
            axis_label(metrics[m].symbol, an::unit_name(metrics[m].unit), e), samples,
            std::pow(10.0, e));
        f.caption = "Histogram of " + std::string(metrics[m].symbol) + " (" +
                    metrics[m].description + ") on " + run.platforms[p] +
                    (samples.size() > 1 ? ", one panel per view group," : "") +
                    " normalised to area 1, on bins of the group's own spread "
                    "(Freedman-Diaconis over its central 99 %).";
        f.section = section;
        add(std::move(f));
      }
    }
  }
};

}  // namespace

void plan_distribution_figures(FigurePlanner& planner, geometry::Kind kind) {
  DistributionFigures f{planner};
  f.box_plots(kind);
  f.histograms(kind);
}

}  // namespace ra::plots
