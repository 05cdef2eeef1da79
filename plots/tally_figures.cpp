// The tallies of a primitive kind: visibility classes, conformance with the reference rasterizer, conformance classes, per platform and view group (figure_planner.h).
#include "plots/figure_planner.h"

#include <algorithm>
#include <cctype>
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

struct TallyFigures : FigurePlanner {
  void visibility(geometry::Kind kind) {
    const std::string section = section_of(kind);
    for (std::size_t p = 0; p < run.platforms.size(); ++p) {
      const auto groups = run.groups_of(p, kind);
      if (groups.empty()) continue;
      BarChartContent c;
      for (int v = 0; v < 5; ++v) {
        if (kind != geometry::Kind::kPoint && v == int(metrics::Visibility::kMultipleVisible))
          continue;
        c.categories.push_back(metrics::visibility_name(metrics::Visibility(v)));
      }
      std::vector<std::string> labels;
      for (const an::ViewGroup* g : groups) {
        const an::VisibilityCounts counts = g->counts();
        std::uint64_t ok = 0;
        for (auto n : counts.by_class) ok += n;
        BarSeries s;
        s.name = group_label(*g);
        for (int v = 0; v < 5; ++v) {
          if (kind != geometry::Kind::kPoint && v == int(metrics::Visibility::kMultipleVisible))
            continue;
          const auto n = counts.by_class[std::size_t(v)];
          s.values.push_back(ok ? 100.0 * double(n) / double(ok) : 0);
          s.labels.push_back(std::to_string(n));
        }
        c.series.push_back(std::move(s));
        labels.push_back(g->label);
      }
      // a log axis: 2 false-invisible cases in 10,000 beside 99.9 % true-visible still have a bar
      c.y_max = 100;
      c.y_log10 = true;
      Figure f;
      f.id = "visibility." + std::string(an::kind_name(kind)) + "." + run.platforms[p];
      f.title = "Visibility classes of " + section + ": " + run.platforms[p] + ", " + groups_phrase(labels);
      f.x_label = "visibility class (paper, section 3.4)";
      f.y_label = "share of the group's cases (%, log scale)";
      f.note =
          "Numbers above the bars: counts of cases (status ok); the axis is logarithmic, "
          "so that a rare class has a bar of visible height (bars rise from " +
          util::significant(bar_chart_log_floor(c), 3) +
          " %; a count of 0 has none). "
          "Classes: " +
          std::string(
              "true-visible = inside the frustum and drawn; false-visible = drawn "
              "although outside; false-invisible = not drawn although inside") +
          (kind == geometry::Kind::kPoint ? "; multiple-visible = more than one pixel." : ".");
      f.caption = "Visibility classes of " + section + " on " + run.platforms[p] +
                  " per view group, as shares of the group's cases with counts above the bars "
                  "(the paper's Table " +
                  (kind == geometry::Kind::kPoint  ? "2"
                   : kind == geometry::Kind::kLine ? "5"
                                                   : "8") +
                  " as a picture).";
      f.section = section;
      f.content = std::move(c);
      add(std::move(f));
    }
  }

  void conformance(geometry::Kind kind) {
    const std::string section = section_of(kind);
    const std::string kname = an::kind_name(kind);
    std::vector<int> groups = run.view_groups(kind);
    std::vector<std::string> categories, labels;
    for (int g : groups) {
      std::string label = an::view_group_label(g);
      labels.push_back(label);
      for (const auto& p : run.platforms) {
        auto it = tally.group_labels.find({p, kname, g});
        if (it != tally.group_labels.end()) {
          label += ": " + it->second;
          break;
        }
      }
      categories.push_back(label);
    }
    std::vector<PlatformAgreement> platforms;
    for (const auto& p : run.platforms) {
      PlatformAgreement a{p, {}};
      for (int g : groups) {
        const auto it = tally.reference.find({p, kname, g});
        a.groups.push_back(it == tally.reference.end() ? nullptr : &it->second);
      }
      platforms.push_back(std::move(a));
    }
    BarChartContent c = conformance_bars(categories, platforms);
    if (c.series.empty()) {
      skip(section, "conformance with the reference rasterizer",
           "no " + section + " record has a reference comparison (ref_diff)");
      return;
    }
    Figure f;
    f.id = "conformance." + kname;
    f.title = "Pixel sets that differ from the reference rasterizer, " + section + ": " +
              join(run.platforms, ", ") + ", " + groups_phrase(labels);
    f.x_label = "view group (field of view, window)";
    f.y_label = "pixel set differs from the reference (%)";
    f.note =
        "Share of records (status ok) whose lit pixels differ from the reference "
        "rasterizer's (ref_diff > 0), per platform: over all compared cases, and over the "
        "cases where either rasterizer lit a pixel; the rest are identical. " +
        std::string(c.series.size() > 2 ? "Each share in its colour, each platform in a "
                                          "shade of it. "
                                        : "") +
        "Numbers above the bars: percent. The axis starts at 0 and ends above the largest "
        "share.";
    f.caption = "Driver versus reference conformance for " + section +
                ": the share of cases whose pixel set differs from the project's exact "
                "rasterizer's, per view group and platform (the rest are identical).";
    f.section = section;
    f.content = std::move(c);
    add(std::move(f));
  }

  // The GL verdicts per view group, one figure per platform that has them.
  void conformance_classes(geometry::Kind kind) {
    const std::string section = section_of(kind);
    const std::string kname = an::kind_name(kind);
    const std::vector<int> groups = run.view_groups(kind);
    for (const auto& p : run.platforms) {
      std::vector<std::pair<std::string, an::ConformanceCounts>> counts;
      std::vector<std::string> labels;
      bool has = false;
      for (int g : groups) {
        labels.push_back(an::view_group_label(g));
        const auto it = tally.verdicts.find({p, kname, g});
        const an::ConformanceCounts n =
            it != tally.verdicts.end() ? it->second : an::ConformanceCounts{};
        has = has || n.exact + n.snapped + n.within_spec + n.violation > 0;
        counts.emplace_back(labels.back(), n);
      }
      if (!has) continue;  // the reference platform, or records without verdicts
      BarChartContent c = conformance_class_bars(counts);
      Figure f;
      f.id = "conformance_classes." + kname + "." + p;
      f.title = "GL conformance classes other than exact, " + section + ", " + p +
                ": " + groups_phrase(labels);
      f.x_label = "view group (its exact share)";
      f.y_label = "share of records (%)";
      f.note = "exact (under each group): the reference rasterizer's pixels; snapped: the "
               "reference's on the platform's effective subpixel grid; within-spec: other pixels "
               "GL allows; violation: a pixel GL forbids (analysis/violations.md lists them). "
               "Numbers above the bars: percent; the axis ends above the largest share.";
      f.caption = "Does " + p + " rasterize " + section + " as GL allows? The verdict classes "
                  "per view group.";
      f.section = section;
      f.content = std::move(c);
      add(std::move(f));
    }
  }
};

}  // namespace

int percent_decimals(const std::vector<double>& shares) {
  for (double v : shares)
    if (v > 0 && v < 10) return 2;
  return 1;
}

std::string percent_text(double v, int decimals) {
  if (v == 0) return "0";
  const double unit = std::pow(10.0, -decimals);
  if (v < unit) return "<" + util::fixed(unit, decimals);
  if (v < 100 && v > 100 - 0.5 * unit) return ">" + util::fixed(100 - unit, decimals);
  return util::fixed(v, decimals);
}

BarChartContent conformance_bars(const std::vector<std::string>& categories,
                                 const std::vector<PlatformAgreement>& platforms) {
  BarChartContent c;
  c.categories = categories;
  std::vector<const PlatformAgreement*> shown;
  for (const PlatformAgreement& p : platforms)
    for (const an::ReferenceAgreement* a : p.groups)
      if (a && a->compared > 0) {
        shown.push_back(&p);
        break;
      }
  // share by share, each platform in a shade of the share's colour; values first, labels when
  // the format of the whole figure is known
  std::vector<double> all_values;
  for (const bool lit : {false, true})
    for (std::size_t k = 0; k < shown.size(); ++k) {
      BarSeries s;
      s.name = shown[k]->platform + (lit ? ", cases with lit pixels" : ", all cases");
      s.color = platform_shade(differs_share_color(lit), k, shown.size());
      for (std::size_t g = 0; g < categories.size(); ++g) {
        const an::ReferenceAgreement* a =
            g < shown[k]->groups.size() ? shown[k]->groups[g] : nullptr;
        const bool compared = a && a->compared > 0 && (!lit || a->drawn > 0);
        // the part that is not exact: where the finding is (99.99 % beside 98.96 % on a 0-100
        // axis look alike; 0.01 % beside 1.04 % do not)
        const double differs = !compared ? 0 : 100 * (1 - (lit ? a->drawn_rate() : a->rate()));
        s.values.push_back(differs);
        s.labels.push_back(compared ? "" : "n/a");
        if (compared) all_values.push_back(differs);
      }
      c.series.push_back(std::move(s));
    }
  const int decimals = percent_decimals(all_values);
  for (BarSeries& s : c.series)
    for (std::size_t g = 0; g < s.values.size(); ++g)
      if (s.labels[g].empty()) s.labels[g] = percent_text(s.values[g], decimals);
  return c;
}

BarChartContent conformance_class_bars(
    const std::vector<std::pair<std::string, an::ConformanceCounts>>& groups) {
  BarChartContent c;
  // the names of docs/conformance.md, each class in its one colour (violation red)
  const metrics::Conformance shown[] = {metrics::Conformance::kSnapped,
                                        metrics::Conformance::kWithinSpec,
                                        metrics::Conformance::kViolation};
  for (metrics::Conformance k : shown) {
    BarSeries s;
    s.name = metrics::conformance_name(k);
    s.color = conformance_class_color(k);
    c.series.push_back(std::move(s));
  }
  // every share of the figure, the exact ones under the groups' names too, in one format
  std::vector<double> exact, all;
  for (const auto& [label, n] : groups) {
    const std::uint64_t judged = n.exact + n.snapped + n.within_spec + n.violation;
    exact.push_back(judged ? 100.0 * double(n.exact) / double(judged) : NAN);
    const std::uint64_t count[] = {n.snapped, n.within_spec, n.violation};
    for (std::size_t k = 0; k < 3; ++k) {
      const double share = judged ? 100.0 * double(count[k]) / double(judged) : 0;
      c.series[k].values.push_back(share);
      if (judged) all.push_back(share);
    }
    if (judged) all.push_back(exact.back());
  }
  const int decimals = percent_decimals(all);
  for (std::size_t g = 0; g < groups.size(); ++g) {
    const bool judged = !std::isnan(exact[g]);
    // exact in the category's name, the other classes as bars on an axis of their own size
    c.categories.push_back(groups[g].first +
                           (judged ? " (exact " + percent_text(exact[g], decimals) + "%)" : ""));
    for (BarSeries& s : c.series)
      s.labels.push_back(judged ? percent_text(s.values[g], decimals) : "n/a");
  }
  return c;
}

void plan_conformance_overview(FigurePlanner& p) {
  BarChartContent c;
  std::vector<std::string> platforms;
  std::vector<double> all;
  for (const auto& name : p.run.platforms) {
    BarSeries s;
    s.name = name;
    bool has = false;
    for (geometry::Kind kind : p.run.kinds())
      for (int g : p.run.view_groups(kind)) {
        const auto it = p.tally.reference.find({name, an::kind_name(kind), g});
        const bool compared = it != p.tally.reference.end() && it->second.compared > 0;
        has = has || compared;
        const double differs = compared ? 100 * (1 - it->second.rate()) : 0;
        s.values.push_back(differs);
        s.labels.push_back(compared ? "" : "n/a");
        if (compared) all.push_back(differs);
      }
    if (!has) continue;  // the reference platform
    platforms.push_back(name);
    c.series.push_back(std::move(s));
  }
  if (c.series.empty()) return;
  // the share of all cases, as in each kind's conformance figure: its colour, a shade per platform
  const int decimals = percent_decimals(all);
  for (std::size_t k = 0; k < c.series.size(); ++k) {
    BarSeries& s = c.series[k];
    s.color = platform_shade(differs_share_color(false), k, c.series.size());
    for (std::size_t i = 0; i < s.values.size(); ++i)
      if (s.labels[i].empty()) s.labels[i] = percent_text(s.values[i], decimals);
  }
  // short labels ("T C": triangles of view group C): twelve of them share one short figure
  for (geometry::Kind kind : p.run.kinds())
    for (int g : p.run.view_groups(kind))
      c.categories.push_back(std::string(1, char(std::toupper(an::kind_name(kind)[0]))) + " " +
                             an::view_group_label(g));
  Figure f;
  f.id = "conformance.overview";
  f.title = "Pixel sets that differ from the reference rasterizer: " + join(platforms, ", ") +
            ", every kind and view group";
  f.x_label = "kind (P points, L line segments, T triangles) and view group";
  f.y_label = "differs (%)";
  // no note inside: the figure is short; its caption says what the bars are
  f.caption = "Where each driver draws other pixels than the exact reference rasterizer, per "
              "kind and view group: the share of records (status ok) whose lit pixels differ "
              "(ref_diff > 0), in percent above the bars; the rest are identical (the first "
              "page's picture; per kind, the conformance figures of each section).";
  f.section = "overview";
  f.height = 360;  // wide and short: it fits on the report's first page at a readable size
  f.content = std::move(c);
  p.add(std::move(f));
}

void plan_tally_figures(FigurePlanner& planner, geometry::Kind kind) {
  TallyFigures f{planner};
  f.visibility(kind);
  f.conformance(kind);
  f.conformance_classes(kind);
}

}  // namespace ra::plots
