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

void plan_tally_figures(FigurePlanner& planner, geometry::Kind kind);
// The bars of a conformance_classes figure: per view group (label, its verdict counts) the shares
// of snapped, within-spec and violation, named as docs/conformance.md names them and each in
// conformance_class_color(); the exact share in the group's category ("A (exact 98.4%)").
BarChartContent conformance_class_bars(
    const std::vector<std::pair<std::string, an::ConformanceCounts>>& groups);
// One platform's agreement with the reference rasterizer per view group (nullptr: no records).
struct PlatformAgreement {
  std::string platform;
  std::vector<const an::ReferenceAgreement*> groups;
};
// The bars of a conformance figure (conformance.KIND): per view group (`categories`) the share of
// compared cases whose pixels differ from the reference's, over all cases and over those where
// either rasterizer lit a pixel, for each platform that compared any. Each share has its hue
// (differs_share_color) and each platform a shade of it (platform_shade); the bars go share by
// share, platform by platform, so one share reads as one family. Labels: percent_text in one
// format for the figure, "n/a" where nothing was compared.
BarChartContent conformance_bars(const std::vector<std::string>& categories,
                                 const std::vector<PlatformAgreement>& platforms);
// One number format for the percentages of a figure (above its bars, in its category names): the
// decimals its smallest share needs, 2 when a share is below 10 %, else 1, for every number alike
// ("0.21" beside "38.00", never beside "38.0").
int percent_decimals(const std::vector<double>& shares);
// A percentage in that format: "0" for none at all, "<0.01" for a share too small to show,
// ">99.99" for one that would round to 100 without being all of them.
std::string percent_text(double v, int decimals);
// Every kind and view group in one bar chart (conformance.overview): the report's first page.
void plan_conformance_overview(FigurePlanner& planner);
void plan_distribution_figures(FigurePlanner& planner, geometry::Kind kind);
void plan_comparison_figures(FigurePlanner& planner, geometry::Kind kind);
void plan_speed_error_figures(FigurePlanner& planner, geometry::Kind kind);

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
const char* section_of(geometry::Kind kind);

}  // namespace ra::plots
