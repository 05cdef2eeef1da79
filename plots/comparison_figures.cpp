// The comparisons of figures.json for a primitive kind: Q-Q plots and bihistograms of two views or platforms, with the test that compared them (figure_planner.h).
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

struct ComparisonFigures : FigurePlanner {
  std::string side_text(const json& s, bool with_views) const {
    std::string t = s.value("platform", "") + ", view group " + s.value("view_group", "");
    if (with_views) {
      const json views = s.value("views", json::array());
      t += (views.size() == 1 ? ", view " : ", views ") + views_text(views);
    }
    return t;
  }

  // What the pair's tests concluded (figures.json "test"), one sentence for the figure's note.
  static std::string test_sentence(const json& c) {
    if (!c.contains("test") || !c["test"].is_object()) return "";
    const json& t = c["test"];
    auto p = [](const json& v) {
      if (!v.is_number()) return std::string("undefined");
      const double x = v.get<double>();
      return x < 0.001 ? std::string("p < 0.001") : "p = " + util::fixed(x, 3);
    };
    const json lp = t.value("location_p", json()), sp = t.value("levene_median_p", json());
    const bool orientations = c.value("what", "") == "orientations";
    std::string verdict;
    if (!lp.is_number() && !sp.is_number())
      verdict = "no test is defined (constant samples)";
    else if (orientations)
      verdict = t.value("differ", false) ? "NOT equivalent (pooled into the group anyway, as the "
                                           "paper did)"
                                         : "equivalent: pooled into the view group";
    else
      verdict = t.value("differ", false) ? "the two differ significantly"
                                         : "no significant difference";
    return "Tests at alpha " + util::significant(t.value("alpha", 0.05), 6) + ": " +
           (t.value("location", "") == "t_pooled" ? "pooled t " : "Welch t ") + p(lp) +
           ", Levene (median) " + p(sp) + ": " + verdict + ".";
  }

  void comparisons(geometry::Kind kind) {
    const std::string section = section_of(kind);
    for (const json& c : doc.value("comparisons", json::array())) {
      if (c.value("kind", "") != an::kind_name(kind)) continue;
      const std::string what = c.value("what", ""), column = c.value("metric", ""),
                        symbol = c.value("symbol", column), units = c.value("units", "");
      const json& a = c.at("a");
      const json& b = c.at("b");
      int e = table_exponent(column);
      if (what == "orientations") {
        if (!c.contains("qq") || c["qq"].is_null() || c["qq"].value("x", json::array()).empty()) {
          skip(section, "Q-Q plot " + c.value("id", ""), "no values in one of the samples");
          continue;
        }
        const json& q = c["qq"];
        ra::stats::QQPlotData d;
        d.x = q.at("x").get<std::vector<double>>();
        d.y = q.at("y").get<std::vector<double>>();
        d.p = q.value("p", std::vector<double>{});
        double max_abs = 0;
        for (double v : d.x) max_abs = std::max(max_abs, std::fabs(v));
        if (e < 0) e = display_exponent(max_abs);
        const std::string va = "view " + views_text(a.value("views", json::array()));
        const std::string vb = "view " + views_text(b.value("views", json::array()));
        Figure f = qq_figure("qq." + c.value("id", ""),
                             "Q-Q plot of " + symbol + ": " + a.value("platform", "") +
                                 ", view group " + a.value("view_group", "") + ", " + va + " vs " +
                                 vb,
                             axis_label(symbol, units, e), va, vb, d,
                             q.value("n_a", std::size_t(0)), q.value("n_b", std::size_t(0)),
                             std::pow(10.0, e), 100000);
        if (q.value("subsampled", false))
          f.note = "Quantiles of both samples at p = i / 2001, i = 1..2000 (Hyndman-Fan 6); "
                   "extremes: " + va + " " + util::significant(q.value("min_a", 0.0) * std::pow(10.0, e), 4) +
                   " to " + util::significant(q.value("max_a", 0.0) * std::pow(10.0, e), 4) + ", " + vb +
                   " " + util::significant(q.value("min_b", 0.0) * std::pow(10.0, e), 4) + " to " +
                   util::significant(q.value("max_b", 0.0) * std::pow(10.0, e), 4) + ".";
        f.caption = "Quantile-quantile plot of " + symbol + " for two views of " +
                    a.value("platform", "") + " that differ only in camera orientation (view "
                    "group " + a.value("view_group", "") + "; the paper's Fig. 4): points on the "
                    "line y = x mean equal distributions.";
        if (const std::string t = test_sentence(c); !t.empty()) {
          f.caption += " " + t;
          f.note = t + (f.note.empty() ? "" : "\n" + f.note);
        }
        f.section = section;
        add(std::move(f));
        continue;
      }
      if (!c.contains("bihistogram") || c["bihistogram"].is_null()) {
        skip(section, "bihistogram " + c.value("id", ""), "no values in one of the samples");
        continue;
      }
      const json& h = c["bihistogram"];
      ra::stats::BihistogramData d;
      d.edges = h.at("edges").get<std::vector<double>>();
      d.count1 = h.at("count_a").get<std::vector<std::size_t>>();
      d.count2 = h.at("count_b").get<std::vector<std::size_t>>();
      std::size_t in_a = 0, in_b = 0;
      for (auto n : d.count1) in_a += n;
      for (auto n : d.count2) in_b += n;
      d.n1 = in_a;  // heights: each side's binned values have area 1
      d.n2 = in_b;
      double max_abs = 0;
      for (double v : d.edges) max_abs = std::max(max_abs, std::fabs(v));
      if (e < 0) e = display_exponent(max_abs);
      const bool views = false;
      const std::string sa = side_text(a, views), sb = side_text(b, views);
      std::string title = "Relative bihistogram of " + symbol + ": ";
      if (what == "platforms")
        title += "view group " + a.value("view_group", "") + ", " + a.value("platform", "") +
                 " (above) vs " + b.value("platform", "") + " (below)";
      else if (what == "view_groups" && a.value("platform", "") == b.value("platform", ""))
        title += a.value("platform", "") + ", view group " + a.value("view_group", "") +
                 " (above) vs " + b.value("view_group", "") + " (below)";
      else
        title += sa + " (above) vs " + sb + " (below)";
      Figure f = bihistogram_figure("bihistogram." + c.value("id", ""), title,
                                    axis_label(symbol, units, e), sa, sb, d, std::pow(10.0, e));
      auto& content = std::get<BihistogramContent>(f.content);
      const auto out_a = h.value("outside_a", std::size_t(0)), out_b = h.value("outside_b", std::size_t(0));
      content.n_upper = in_a + out_a;  // the legend gives each sample's size
      content.n_lower = in_b + out_b;
      if (out_a || out_b)
        f.note = "Bins cover the central 99 % of the pooled data; outside them: " +
                 std::to_string(out_a) + " of the upper sample's values, " + std::to_string(out_b) +
                 " of the lower's (each side has area 1 over its binned values).";
      const std::string paper = c.value("figure", "");
      f.caption = "Relative bihistogram of " + symbol + ": " + sa + " above the axis, " + sb +
                  " below, on common bins, each side normalised to area 1" +
                  (paper.empty() ? "" : " (like the paper's " + paper + ")") + ".";
      if (const std::string t = test_sentence(c); !t.empty()) {
        f.caption += " " + t;
        f.note = t + (f.note.empty() ? "" : "\n" + f.note);
      }
      f.section = section;
      add(std::move(f));
    }
  }
};

}  // namespace

void plan_comparison_figures(FigurePlanner& planner, geometry::Kind kind) {
  ComparisonFigures f{planner};
  f.comparisons(kind);
}

}  // namespace ra::plots
