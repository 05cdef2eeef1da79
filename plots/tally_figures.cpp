// The tallies of a primitive kind: visibility classes, conformance with the reference rasterizer, conformance classes, per platform and view group (figure_planner.h).
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

namespace ra::plots {
namespace {

using nlohmann::json;

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
        all.values.push_back(100 * cf.rate());
        all.labels.push_back(fmt(100 * cf.rate(), "%.2f"));
        drawn.values.push_back(100 * cf.drawn_rate());
        drawn.labels.push_back(cf.drawn ? fmt(100 * cf.drawn_rate(), "%.2f") : "n/a");
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
    c.y_max = 100;
    Figure f;
    f.id = "conformance." + kname;
    f.title = "Conformance with the reference rasterizer, " + section + ": " +
              join(run.platforms, ", ") + ", view groups " + groups_text(labels);
    f.x_label = "view group (field of view, window)";
    f.y_label = "pixel set identical to the reference (%)";
    f.note = "Share of records (status ok) whose lit pixels equal the reference rasterizer's "
             "(ref_diff = 0), per platform: over all compared cases, and over the cases where "
             "either rasterizer lit a pixel. Numbers above the bars: percent.";
    f.caption = "Driver versus reference conformance for " + section +
                ": the share of cases whose pixel set is identical to the project's exact "
                "rasterizer's, per view group and platform.";
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
      for (int g : groups) {
        c.categories.push_back(an::view_group_label(g));
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
        for (int k = 1; k < 5; ++k) {
          const double share = judged ? 100.0 * double(classes[k]) / double(judged) : 0;
          series[k].values.push_back(share);
          series[k].labels.push_back(judged ? fmt(share, "%.2f") : "n/a");
        }
      }
      if (!has) continue;  // the reference platform, or records without verdicts
      for (int k = 1; k < 5; ++k) c.series.push_back(std::move(series[k]));
      c.y_max = 100;
      Figure f;
      f.id = "conformance_classes." + kname + "." + p;
      f.title = "GL conformance classes, " + section + ", " + p + ": view groups " +
                groups_text(c.categories);
      f.x_label = "view group";
      f.y_label = "share of records (%)";
      f.note = "exact: the reference rasterizer's pixels; snapped: the reference's on the "
               "platform's effective subpixel grid; within-spec: other pixels GL allows; "
               "violation: a pixel GL forbids (analysis/violations.md lists them). Numbers above "
               "the bars: percent.";
      f.caption = "Does " + p + " rasterize " + section + " as GL allows? The verdict classes "
                  "per view group.";
      f.section = section;
      f.content = std::move(c);
      add(std::move(f));
    }
  }
};

}  // namespace

void plan_tally_figures(FigurePlanner& planner, an::PrimitiveKind kind) {
  TallyFigures f{planner};
  f.visibility(kind);
  f.conformance(kind);
  f.conformance_classes(kind);
}

}  // namespace ra::plots
