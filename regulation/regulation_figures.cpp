// The regulation study's figures (regulation_figures.h).
#include "regulation/regulation_figures.h"

#include <algorithm>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "plots/figure.h"
#include "plots/figure_set.h"
#include "regulation/regulation_document.h"
#include "rundir/study_dir.h"
#include "util/errors.h"
#include "util/json_number.h"

namespace ra::regulation {

using nlohmann::json;

void plot_regulation_study(const std::string& dir) {
  const json j = read_regulation_json(dir);
  if (!rundir::read_study_info(dir)->analysed)
    throw util::UserError(dir + " has not been analysed: run `renderaudit analyze " + dir +
                          "` first");
  plots::StudyFigures figs("regulation");
  // 1. distribution of value(OPT) / value(greedy)
  {
    std::vector<double> r;
    for (const json& v : j["random"]["ratios"]) if (v.is_number()) r.push_back(v.get<double>());
    plots::HistogramSeries hs;
    hs.name = "greedy with the single-item check";
    const int bins = 40;
    for (int i = 0; i <= bins; ++i) hs.edges.push_back(1.0 + double(i) / bins);
    hs.counts.assign(bins, 0);
    for (double v : r) hs.counts[std::min(bins - 1, std::max(0, int((v - 1.0) * bins)))] += 1;
    for (auto c : hs.counts) hs.heights.push_back(double(c));
    hs.n = r.size();
    plots::HistogramContent hc;
    hc.density = false;
    hc.series.push_back(hs);
    figs.add("regulation_ratio_histogram", "value(OPT) / value(greedy) on random instances",
             "value(OPT) / value(greedy)", "instances",
             "Distribution of the ratio of the optimal to the greedy value (perceptual cost saved "
             "over the all-coarsest plan) on " +
                 std::to_string(r.size()) +
                 " random knapsack instances; the theorem bounds it by 2.",
             hc);
  }
  // y against x of `rows` on log axes, one series per policy in the order they first appear; a
  // row without a number for y is left out (its policy keeps its place).
  auto by_policy = [](const json& rows, const char* x, const char* y) {
    plots::SeriesInOrder by;
    for (const json& r : rows) {
      plots::ScatterSeries& s = by[r.value("policy", "")];
      if (!r[y].is_number()) continue;
      s.x.push_back(r[x].get<double>());
      s.y.push_back(r[y].get<double>());
    }
    plots::ScatterContent sc;
    sc.series = by.series();
    sc.x_log10 = sc.y_log10 = true;
    return sc;
  };
  // 2. expected perceptual cost against budget, one series per policy
  {
    const plots::ScatterContent sc = by_policy(j["sweep"], "budget_ms", "mean_expected_cost");
    figs.add("regulation_cost_vs_budget", "Expected perceptual cost against frame budget",
             "frame budget (ms)", "mean expected perceptual cost",
             "Mean expected perceptual cost of the plans along the camera path, per policy and "
             "budget.",
             sc)
        .note = plots::scatter_omitted_note(sc);
  }
  // 3. skip rate per budget and policy; 4. measured against predicted
  if (j["render"].value("enabled", false) && j["render"]["error"].is_null()) {
    plots::BarChartContent bc;
    std::map<std::string, std::size_t> series_index;
    for (const json& r : j["sweep"]) {
      const std::string b = util::json_number_text(r["budget_ms"], "%g") + " ms";
      if (std::find(bc.categories.begin(), bc.categories.end(), b) == bc.categories.end())
        bc.categories.push_back(b);
    }
    for (const json& r : j["sweep"]) {
      const std::string p = r.value("policy", "");
      if (!series_index.count(p)) {
        series_index[p] = bc.series.size();
        bc.series.push_back({p, std::vector<double>(bc.categories.size(), 0.0), {}, std::nullopt});
      }
      const std::string b = util::json_number_text(r["budget_ms"], "%g") + " ms";
      const auto at = std::find(bc.categories.begin(), bc.categories.end(), b) - bc.categories.begin();
      bc.series[series_index[p]].values[std::size_t(at)] =
          100.0 * (r["skip_fraction"].is_number() ? r["skip_fraction"].get<double>() : 0.0);
    }
    bc.y_max = 100;
    figs.add("regulation_frame_skips", "Frame skips per budget and policy", "frame budget",
             "frames over budget (%)",
             "Share of the planned frames whose median measured time exceeded the budget.", bc);

    const plots::ScatterContent sc = by_policy(j["render"]["points"], "predicted_ms", "measured_ms");
    figs.add("regulation_measured_vs_predicted", "Measured against predicted frame time",
             "predicted frame time (ms)", "measured median frame time (ms)",
             "Each rendered plan: the H4 prediction plus the empty frame against the median "
             "measured time.",
             sc)
        .note = plots::scatter_omitted_note(sc);
  }
  figs.write(dir);
}

}  // namespace ra::regulation
