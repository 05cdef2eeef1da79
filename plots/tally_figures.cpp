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

// A percentage above a bar, with the digits a small share needs: "0", "<0.01", "0.25", "12.5".
std::string percent_label(double v) {
  if (v == 0) return "0";
  if (v < 0.01) return "<0.01";
  return util::format_double(v < 10 ? "%.2f" : "%.1f", v);
}

struct TallyFigures : FigurePlanner {
  void visibility(an::PrimitiveKind kind) {
    const std::string section = section_of(kind);
    for (std::size_t p = 0; p < run.platforms.size(); ++p) {
      const auto groups = run.groups_of(p, kind);
      if (groups.empty()) continue;
      BarChartContent c;
      for (int v = 0; v < 5; ++v) {
        if (kind != an::PrimitiveKind::kPoint && v == int(metrics::Visibility::kMultipleVisible))
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
          if (kind != an::PrimitiveKind::kPoint && v == int(metrics::Visibility::kMultipleVisible))
            continue;
          const auto n = counts.by_class[std::size_t(v)];
          s.values.push_back(ok ? 100.0 * double(n) / double(ok) : 0);
          s.labels.push_back(std::to_string(n));
        }
        c.series.push_back(std::move(s));
        labels.push_back(g->label);
      }
      c.y_max = 100;
      Figure f;
      f.id = "visibility." + std::string(an::kind_name(kind)) + "." + run.platforms[p];
      f.title = "Visibility classes of " + section + ": " + run.platforms[p] + ", view groups " +
                groups_text(labels);
      f.x_label = "visibility class (paper, section 3.4)";
      f.y_label = "share of the group's cases (%)";
      f.note = "Numbers above the bars: counts of cases (status ok). Classes: " +
               std::string("true-visible = inside the frustum and drawn; false-visible = drawn "
                           "although outside; false-invisible = not drawn although inside") +
               (kind == an::PrimitiveKind::kPoint ? "; multiple-visible = more than one pixel."
                                                  : ".");
      f.caption = "Visibility classes of " + section + " on " + run.platforms[p] +
                  " per view group, as shares of the group's cases with counts above the bars "
                  "(the paper's Table " +
                  (kind == an::PrimitiveKind::kPoint ? "2" : kind == an::PrimitiveKind::kLine ? "5" : "8") +
                  " as a picture).";
      f.section = section;
      f.content = std::move(c);
      add(std::move(f));
    }
  }

  void conformance(an::PrimitiveKind kind) {
    const std::string section = section_of(kind);
    const std::string kname = an::kind_name(kind);
    std::vector<int> groups = run.view_groups(kind);
    BarChartContent c;
    std::vector<std::string> labels;
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
      c.categories.push_back(label);
    }
    bool any = false;
    for (const auto& p : run.platforms) {
      BarSeries all, drawn;
      all.name = p + ", all cases";
      drawn.name = p + ", cases with lit pixels";
      bool has = false;
      for (int g : groups) {
        const auto it = tally.reference.find({p, kname, g});
        if (it == tally.reference.end() || it->second.compared == 0) {
          all.values.push_back(0), all.labels.push_back("n/a");
          drawn.values.push_back(0), drawn.labels.push_back("n/a");
          continue;
        }
        has = true;
        const an::ReferenceAgreement& cf = it->second;
        // the part that is not exact: where the finding is (99.99 % beside 98.96 % on a 0-100
        // axis look alike; 0.01 % beside 1.04 % do not)
        const double differs = 100 * (1 - cf.rate());
        all.values.push_back(differs);
        all.labels.push_back(percent_label(differs));
        const double drawn_differs = cf.drawn ? 100 * (1 - cf.drawn_rate()) : 0;
        drawn.values.push_back(drawn_differs);
        drawn.labels.push_back(cf.drawn ? percent_label(drawn_differs) : "n/a");
      }
      if (!has) continue;
      any = true;
      c.series.push_back(std::move(all));
      c.series.push_back(std::move(drawn));
    }
    if (!any) {
      skip(section, "conformance with the reference rasterizer",
           "no " + section + " record has a reference comparison (ref_diff)");
      return;
    }
    Figure f;
    f.id = "conformance." + kname;
    f.title = "Pixel sets that differ from the reference rasterizer, " + section + ": " +
              join(run.platforms, ", ") + ", view groups " + groups_text(labels);
    f.x_label = "view group (field of view, window)";
    f.y_label = "pixel set differs from the reference (%)";
    f.note = "Share of records (status ok) whose lit pixels differ from the reference "
             "rasterizer's (ref_diff > 0), per platform: over all compared cases, and over the "
             "cases where either rasterizer lit a pixel; the rest are identical. Numbers above "
             "the bars: percent. The axis starts at 0 and ends above the largest share.";
    f.caption = "Driver versus reference conformance for " + section +
                ": the share of cases whose pixel set differs from the project's exact "
                "rasterizer's, per view group and platform (the rest are identical).";
    f.section = section;
    f.content = std::move(c);
    add(std::move(f));
  }

  // The GL verdicts per view group, one figure per platform that has them.
  void conformance_classes(an::PrimitiveKind kind) {
    const std::string section = section_of(kind);
    const std::string kname = an::kind_name(kind);
    const std::vector<int> groups = run.view_groups(kind);
    for (const auto& p : run.platforms) {
      BarChartContent c;
      const char* names[] = {"", "exact", "snapped", "within-spec", "violation"};
      std::vector<BarSeries> series(5);
      for (int k = 1; k < 5; ++k) series[k].name = names[k];
      bool has = false;
      std::vector<std::string> labels;
      for (int g : groups) {
        labels.push_back(an::view_group_label(g));
        const auto it = tally.verdicts.find({p, kname, g});
        std::uint64_t classes[5] = {};  // indexed by ra::Conformance
        if (it != tally.verdicts.end()) {
          classes[int(metrics::Conformance::kExact)] = it->second.exact;
          classes[int(metrics::Conformance::kSnapped)] = it->second.snapped;
          classes[int(metrics::Conformance::kWithinSpec)] = it->second.within_spec;
          classes[int(metrics::Conformance::kViolation)] = it->second.violation;
        }
        const std::uint64_t judged = classes[1] + classes[2] + classes[3] + classes[4];
        has = has || judged > 0;
        // exact in the category's name, the other classes as bars on an axis of their own size
        c.categories.push_back(
            labels.back() +
            (judged ? " (exact " + percent_label(100.0 * double(classes[1]) / double(judged)) + "%)"
                    : ""));
        for (int k = 2; k < 5; ++k) {
          const double share = judged ? 100.0 * double(classes[k]) / double(judged) : 0;
          series[k].values.push_back(share);
          series[k].labels.push_back(judged ? percent_label(share) : "n/a");
        }
      }
      if (!has) continue;  // the reference platform, or records without verdicts
      for (int k = 2; k < 5; ++k) c.series.push_back(std::move(series[k]));
      Figure f;
      f.id = "conformance_classes." + kname + "." + p;
      f.title = "GL conformance classes other than exact, " + section + ", " + p +
                ": view groups " + groups_text(labels);
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

void plan_conformance_overview(FigurePlanner& p) {
  BarChartContent c;
  std::vector<std::string> platforms;
  for (const auto& name : p.run.platforms) {
    BarSeries s;
    s.name = name;
    bool has = false;
    for (an::PrimitiveKind kind : p.run.kinds())
      for (int g : p.run.view_groups(kind)) {
        const auto it = p.tally.reference.find({name, an::kind_name(kind), g});
        const bool compared = it != p.tally.reference.end() && it->second.compared > 0;
        has = has || compared;
        const double differs = compared ? 100 * (1 - it->second.rate()) : 0;
        s.values.push_back(differs);
        s.labels.push_back(compared ? percent_label(differs) : "n/a");
      }
    if (!has) continue;  // the reference platform
    platforms.push_back(name);
    c.series.push_back(std::move(s));
  }
  if (c.series.empty()) return;
  // short labels ("T C": triangles of view group C): twelve of them share one short figure
  for (an::PrimitiveKind kind : p.run.kinds())
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

void plan_tally_figures(FigurePlanner& planner, an::PrimitiveKind kind) {
  TallyFigures f{planner};
  f.visibility(kind);
  f.conformance(kind);
  f.conformance_classes(kind);
}

}  // namespace ra::plots
