// What the figure families of plan_figures (plot_run.h) share: the run's records, the analysis'
// figures.json, its tally.json (analysis/run_tally.h) and the plan being built, with the helpers that word their
// titles and axes. Each family adds the figures of one primitive kind to the plan, in the order
// plan_figures calls them: tallies (visibility, conformance, conformance classes), distributions
// (box plots, histograms), comparisons of views and platforms, speed against error.
#pragma once

#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "analysis/run_records.h"
#include "analysis/run_tally.h"
#include "plots/figure.h"
#include "plots/plot_run.h"

namespace ra::plots {

namespace an = ra::analysis;

struct FigurePlanner {
  const std::string& run_dir;
  const nlohmann::json& doc;  // DIR/analysis/figures.json
  const an::RunRecords& run;
  const an::RunTally& tally;  // DIR/analysis/tally.json
  FigurePlan& plan;
  std::set<std::string>& ids;  // of the figures planned: a repeated id gets "_2", "_3", ...

  void add(Figure f);
  void skip(const std::string& section, const std::string& what, const std::string& reason);
  std::string group_label(const an::ViewGroup& g) const;  // "A: 30 deg, 128x128"
};

void plan_tally_figures(FigurePlanner& planner, an::PrimitiveKind kind);
// The bars of a conformance_classes figure: per view group (label, its verdict counts) the shares
// of snapped, within-spec and violation, named as docs/conformance.md names them and each in
// conformance_class_color(); the exact share in the group's category ("A (exact 98.4%)").
BarChartContent conformance_class_bars(
    const std::vector<std::pair<std::string, an::ConformanceCounts>>& groups);
// Every kind and view group in one bar chart (conformance.overview): the report's first page.
void plan_conformance_overview(FigurePlanner& planner);
void plan_distribution_figures(FigurePlanner& planner, an::PrimitiveKind kind);
void plan_comparison_figures(FigurePlanner& planner, an::PrimitiveKind kind);
void plan_speed_error_figures(FigurePlanner& planner, an::PrimitiveKind kind);

// Wording helpers of the families.
// What a box plot shows, named by what varies in it: "Box plot of TEu" (one box), "Box plots of
// TEu by view group" (one platform), "... by platform" (one view group), "... by view group and
// platform".
std::string box_plot_title(const std::string& symbol, const BoxPlotContent& content);
std::string sanitize_id(const std::string& s);  // [a-z0-9._-], others '_'
// The x 10^k the paper's tables use for a metric column; -1 when no table shows it.
int table_exponent(const std::string& column);
// "PEnorm x 10^3 (sqrt(W*H) units)": the numbers on the axis are the metric times 10^k.
std::string axis_label(const std::string& symbol, const std::string& units, int exponent);
std::string views_text(const nlohmann::json& views);
std::string join(const std::vector<std::string>& v, const std::string& sep);
std::string groups_text(const std::vector<std::string>& labels);  // "A-D" or "A" or "A, C"
// "view group A" for one, "view groups A-D" (groups_text) for more.
std::string groups_phrase(const std::vector<std::string>& labels);
const char* section_of(an::PrimitiveKind kind);

}  // namespace ra::plots
