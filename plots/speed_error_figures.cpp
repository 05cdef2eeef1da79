// Rendering time against geometric error for a primitive kind, one point per platform and view group (figure_planner.h).
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
#include "util/shell_quote.h"

namespace ra::plots {
namespace {

using nlohmann::json;

struct SpeedErrorFigures : FigurePlanner {
  // Speed against error: one point per platform x view group, x = median render time
  // per primitive, y = median of the kind's normalised unsigned error, IQR bars on both, log axes.
  void speed_error(geometry::Kind kind) {
    const std::string section = section_of(kind);
    const std::string kname = an::kind_name(kind);
    const json* entry = nullptr;  // into doc (not into a copy of its array)
    const auto list = doc.find("speed_error");
    if (list != doc.end() && list->is_array())
      for (const json& e : *list)
        if (e.value("kind", "") == kname) entry = &e;
    const std::string what = "render time against error";
    if (!entry) {
      skip(section, what,
           "figures.json has no speed_error data for " + section + " (run `renderaudit analyze " +
               util::shell_quote(run_dir) + "` again)");
      return;
    }
    const std::string column = entry->value("metric", ""), symbol = entry->value("symbol", column),
                      units = entry->value("units", "");
    // The paper tables' x 10^k, as every other figure of the metric (a shift on a log axis).
    int e = table_exponent(column);
    if (e < 0) e = 0;
    const double scale = std::pow(10.0, e);
    ScatterContent c;
    c.x_log10 = c.y_log10 = true;
    std::map<std::string, std::string> group_text;  // "A" -> "A: 30 deg, 128x128"
    std::vector<std::string> no_time, no_error;
    const auto number = [](const json& p, const char* key) {
      const auto it = p.find(key);
      return it == p.end() || it->is_null() ? NAN : it->get<double>();
    };
    for (const std::string& platform : doc.value("platforms", std::vector<std::string>{})) {
      ScatterSeries se;
      se.name = platform;
      for (const json& p : entry->at("points")) {
        if (p.value("platform", "") != platform) continue;
        const std::string g = p.value("view_group", "?");
        if (p.value("n_time", 0) == 0) {
          no_time.push_back(g + " " + platform);
          continue;
        }
        if (p.value("n_error", 0) == 0) {
          no_error.push_back(g + " " + platform);
          continue;
        }
        group_text.emplace(g, g + ": " + util::significant(p.value("fov_deg", 0.0), 6) + " deg, " +
                                  std::to_string(p.value("width", 0)) + "x" +
                                  std::to_string(p.value("height", 0)));
        se.labels.push_back(g);
        se.x.push_back(number(p, "median_us"));
        se.x_lo.push_back(number(p, "q1_us"));
        se.x_hi.push_back(number(p, "q3_us"));
        se.y.push_back(number(p, "median_error") * scale);
        se.y_lo.push_back(number(p, "q1_error") * scale);
        se.y_hi.push_back(number(p, "q3_error") * scale);
      }
      if (!se.x.empty()) c.series.push_back(std::move(se));
    }
    if (c.series.empty()) {
      skip(section, what + " (" + symbol + ")",
           "no view group has both a render time and a true-visible " + symbol + " value");
      return;
    }
    std::vector<std::string> platforms, groups, legend;
    for (const ScatterSeries& se : c.series) platforms.push_back(se.name);
    for (const auto& [g, text] : group_text) groups.push_back(g), legend.push_back(text);
    Figure f;
    f.id = "speed_error." + kname;
    f.title = "Render time against error, " + section + ": " + symbol + " vs time per primitive, " +
              join(platforms, ", ") + ", " + groups_phrase(groups);
    f.x_label = "render time per primitive, median (us, log scale)";
    f.y_label = axis_label(symbol, units, e) + ", median, log scale";
    f.note = "Letters: view groups (" + join(legend, "; ") +
             "). Bars: interquartile ranges of time and error. Times depend on the machine and "
             "its load; the errors do not.";
    if (!no_time.empty()) f.note += "\nNot drawn, no render time: " + join(no_time, ", ") + ".";
    if (!no_error.empty())
      f.note += "\nNot drawn, no true-visible " + symbol + " value: " + join(no_error, ", ") + ".";
    f.caption =
        "Render time against rendering error for " + section + ": each point is one platform and "
        "view group (the letter beside it), at the median render_us (CPU microseconds of draw + "
        "glFinish, over the group's records with a time) and the median " + symbol + " (" +
        units + ", over its true-visible records: the normalised unsigned error, so that view "
        "groups with different windows share the axis), with interquartile-range bars (quartiles " +
        doc.value("quantile_definition", std::string("hyndman_fan_6")) +
        "); both axes log10. Small primitives are drawn in batches under one glFinish and each is "
        "given an equal share of its batch's time (records column batch_size), so render_us is a "
        "per-primitive average over the batch, not the latency of one draw. " +
        std::string(analysis::kDeviceClockNote) + " Times depend on the machine and its load.";
    f.section = section;
    f.content = std::move(c);
    add(std::move(f));
  }
};

}  // namespace

void plan_speed_error_figures(FigurePlanner& planner, geometry::Kind kind) {
  SpeedErrorFigures f{planner};
  f.speed_error(kind);
}

}  // namespace ra::plots
