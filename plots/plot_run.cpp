// plot_run: plans every figure of a run from figures.json and the records, draws them with VTK
// (see the header for the list and the files).
#include "plots/plot_run.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include <unistd.h>

#include "analysis/paper_tables.h"
#include "analysis/run_records.h"
#include "plots/figure_builders.h"
#include "plots/figure_renderer.h"
#include "plots/headless_display.h"
#include "plots/record_scan.h"
#include "util/atomic_file.h"
#include "util/errors.h"
#include "metrics/records.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace ra::plots {
namespace {

namespace an = ra::analysis;

std::string sanitize_id(const std::string& s) {
  std::string out;
  for (char c : s) {
    const char l = char(std::tolower(static_cast<unsigned char>(c)));
    out += (std::isalnum(static_cast<unsigned char>(l)) || l == '.' || l == '-' || l == '_') ? l : '_';
  }
  return out;
}

// The x 10^k the paper's tables use for a metric column; -1 when no table shows it.
int table_exponent(const std::string& column) {
  for (const auto& spec : an::metric_table_specs())
    if (column == spec.column) return spec.scale_exponent;
  return -1;
}

// "PEnorm x 10^3 (sqrt(W*H) units)": the numbers on the axis are the metric times 10^k.
std::string axis_label(const std::string& symbol, const std::string& units, int exponent) {
  std::string s = symbol;
  if (exponent > 0) s += " x 10^" + std::to_string(exponent);
  return s + " (" + units + ")";
}

std::string fmt(double v, const char* f = "%g") {
  char buf[48];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

std::string views_text(const json& views) {
  std::string s;
  for (std::size_t i = 0; i < views.size(); ++i) s += (i ? ", " : "") + views[i].dump();
  return s;
}

std::string join(const std::vector<std::string>& v, const std::string& sep) {
  std::string s;
  for (std::size_t i = 0; i < v.size(); ++i) s += (i ? sep : "") + v[i];
  return s;
}

// "A-D" or "A" or "A, C".
std::string groups_text(const std::vector<std::string>& labels) {
  if (labels.empty()) return "";
  if (labels.size() == 1) return labels[0];
  bool consecutive = true;
  for (std::size_t i = 1; i < labels.size(); ++i)
    consecutive = consecutive && an::view_group_label(int(i)) == labels[i] &&
                  an::view_group_label(0) == labels[0];
  return consecutive ? labels.front() + "-" + labels.back() : join(labels, ", ");
}

const char* section_of(an::PrimitiveKind kind) { return an::kind_label_plural(kind); }

struct Planner {
  const std::string run_dir;
  const json& doc;
  const an::RunRecords& run;
  const RecordScan& scan;
  FigurePlan plan;
  std::set<std::string> ids;

  void add(Figure f) {
    f.id = sanitize_id(f.id);
    std::string id = f.id;
    for (int k = 2; ids.count(id); ++k) id = f.id + "_" + std::to_string(k);
    f.id = id;
    ids.insert(id);
    plan.figures.push_back(std::move(f));
  }
  void skip(const std::string& section, const std::string& what, const std::string& reason) {
    plan.skipped.push_back({section, what, reason});
  }

  std::string group_label(const an::ViewGroup& g) const {
    return g.label + ": " + fmt(g.meta().fov_deg) + " deg, " + std::to_string(g.meta().width) +
           "x" + std::to_string(g.meta().height);
  }

  void visibility(an::PrimitiveKind kind) {
    const std::string section = section_of(kind);
    for (std::size_t p = 0; p < run.platforms.size(); ++p) {
      const auto groups = run.groups_of(p, kind);
      if (groups.empty()) continue;
      BarChartContent c;
      for (int v = 0; v < 5; ++v) {
        if (kind != an::PrimitiveKind::kPoint && v == int(Visibility::kMultipleVisible)) continue;
        c.categories.push_back(visibility_name(Visibility(v)));
      }
      std::vector<std::string> labels;
      for (const an::ViewGroup* g : groups) {
        const an::VisibilityCounts counts = g->counts();
        std::uint64_t ok = 0;
        for (auto n : counts.by_class) ok += n;
        BarSeries s;
        s.name = group_label(*g);
        for (int v = 0; v < 5; ++v) {
          if (kind != an::PrimitiveKind::kPoint && v == int(Visibility::kMultipleVisible)) continue;
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
        auto it = scan.group_labels.find({p, kname, g});
        if (it != scan.group_labels.end()) {
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
        const auto it = scan.conformance.find({p, kname, g});
        if (it == scan.conformance.end() || it->second.compared == 0) {
          all.values.push_back(0), all.labels.push_back("n/a");
          drawn.values.push_back(0), drawn.labels.push_back("n/a");
          continue;
        }
        has = true;
        const Conformance& cf = it->second;
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
        const auto it = scan.conformance.find({p, kname, g});
        std::uint64_t judged = 0;
        if (it != scan.conformance.end())
          for (int k = 1; k < 5; ++k) judged += it->second.classes[k];
        has = has || judged > 0;
        for (int k = 1; k < 5; ++k) {
          const double share = judged ? 100.0 * double(it->second.classes[k]) / double(judged) : 0;
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

  void box_plots(an::PrimitiveKind kind) {
    const std::string section = section_of(kind);
    for (const json& bp : doc.value("box_plots", json::array())) {
      if (bp.value("kind", "") != an::kind_name(kind)) continue;
      const std::string column = bp.value("metric", ""), symbol = bp.value("symbol", column),
                        units = bp.value("units", "");
      const json& boxes = bp.at("boxes");
      if (boxes.empty()) {
        skip(section, "box plot of " + symbol, "no true-visible " + section + " with a value");
        continue;
      }
      BoxPlotContent c;
      double max_abs = 0;
      for (const json& b : boxes) max_abs = std::max({max_abs, std::fabs(b.at("q1").get<double>()),
                                                      std::fabs(b.at("q3").get<double>())});
      int e = table_exponent(column);
      if (e < 0) e = display_exponent(max_abs);
      const double scale = std::pow(10.0, e);
      std::vector<std::string> group_labels;
      for (const std::string& p : doc.value("platforms", std::vector<std::string>{}))
        for (const json& b : boxes)
          if (b.value("platform", "") == p &&
              std::find(c.series.begin(), c.series.end(), p) == c.series.end())
            c.series.push_back(p);
      std::map<std::string, std::string> category_of;
      for (const json& b : boxes) {
        const std::string g = b.value("view_group", "?");
        if (!category_of.count(g))
          category_of[g] = g + ": " + fmt(b.value("fov_deg", 0.0)) + " deg, " +
                           std::to_string(b.value("width", 0)) + "x" +
                           std::to_string(b.value("height", 0));
      }
      for (const auto& [g, label] : category_of) {
        c.categories.push_back(label);
        group_labels.push_back(g);
      }
      for (const json& b : boxes) {
        Box x;
        x.category = category_of[b.value("view_group", "?")];
        x.series = b.value("platform", "");
        x.n = b.value("n", std::size_t(0));
        x.q1 = b.at("q1").get<double>() * scale;
        x.median = b.at("median").get<double>() * scale;
        x.q3 = b.at("q3").get<double>() * scale;
        x.lower_whisker = b.at("lower_whisker").get<double>() * scale;
        x.upper_whisker = b.at("upper_whisker").get<double>() * scale;
        x.min = x.lower_whisker, x.max = x.upper_whisker;
        for (const json& o : b.value("outliers", json::array())) {
          x.min = std::min(x.min, o.get<double>() * scale);
          x.max = std::max(x.max, o.get<double>() * scale);
        }
        x.n_outliers_low = b.value("n_outliers_low", std::size_t(0));
        x.n_outliers_high = b.value("n_outliers_high", std::size_t(0));
        c.boxes.push_back(x);
      }
      Figure f;
      f.id = "boxplot." + std::string(an::kind_name(kind)) + "." + column;
      f.title = "Box plots of " + symbol + " by view group and platform: " + join(c.series, ", ") +
                ", view groups " + groups_text(group_labels);
      f.x_label = "view group (field of view, window)";
      f.y_label = axis_label(symbol, units, e);
      f.caption = "Box plots of " + symbol + " for each view group and platform (quartiles " +
                  doc.value("quantile_definition", std::string("hyndman_fan_6")) +
                  "; whiskers to the most extreme values within 1.5 IQR); box widths proportional "
                  "to the number of measurements; the y range is restricted to the box bodies as "
                  "in the paper's Figs. 6, 8, 10 and 12.";
      f.section = section;
      f.content = std::move(c);
      add(std::move(f));
    }
  }

  void histograms(an::PrimitiveKind kind) {
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
                ", view groups " + groups_text(labels),
            axis_label(metrics[m].symbol, an::unit_name(metrics[m].unit), e), samples,
            std::pow(10.0, e));
        f.caption = "Histogram of " + std::string(metrics[m].symbol) + " (" +
                    metrics[m].description + ") on " + run.platforms[p] +
                    ", each view group normalised to area 1, on common bins.";
        f.section = section;
        add(std::move(f));
      }
    }
  }

  // Speed against error: one point per platform x view group, x = median render time
  // per primitive, y = median of the kind's normalised unsigned error, IQR bars on both, log axes.
  void speed_error(an::PrimitiveKind kind) {
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
               run_dir + "` again)");
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
        group_text.emplace(g, g + ": " + fmt(p.value("fov_deg", 0.0)) + " deg, " +
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
              join(platforms, ", ") + ", view groups " + groups_text(groups);
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
        "per-primitive average over the batch, not the latency of one draw. Times depend on the "
        "machine and its load.";
    f.section = section;
    f.content = std::move(c);
    add(std::move(f));
  }

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
      return x < 0.001 ? std::string("p < 0.001") : "p = " + fmt(x, "%.3f");
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
    return "Tests at alpha " + fmt(t.value("alpha", 0.05), "%g") + ": " +
           (t.value("location", "") == "t_pooled" ? "pooled t " : "Welch t ") + p(lp) +
           ", Levene (median) " + p(sp) + ": " + verdict + ".";
  }

  void comparisons(an::PrimitiveKind kind) {
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
                   "extremes: " + va + " " + fmt(q.value("min_a", 0.0) * std::pow(10.0, e), "%.4g") +
                   " to " + fmt(q.value("max_a", 0.0) * std::pow(10.0, e), "%.4g") + ", " + vb +
                   " " + fmt(q.value("min_b", 0.0) * std::pow(10.0, e), "%.4g") + " to " +
                   fmt(q.value("max_b", 0.0) * std::pow(10.0, e), "%.4g") + ".";
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

json figure_json(const IndexedFigure& f, const FigureLayout* layout) {
  json j{{"id", f.id},           {"kind", f.kind}, {"section", f.section}, {"title", f.title},
         {"caption", f.caption}, {"note", f.note}, {"png", f.png},         {"pdf", f.pdf},
         {"csv", f.csv}};
  if (layout)
    j["layout"] = {{"width", layout->width},         {"height", layout->height},
                   {"plot_left", layout->plot_left}, {"plot_right", layout->plot_right},
                   {"plot_top", layout->plot_top},   {"plot_bottom", layout->plot_bottom},
                   {"x_min", layout->x_min},         {"x_max", layout->x_max},
                   {"y_min", layout->y_min},         {"y_max", layout->y_max},
                   {"x_log10", layout->x_log10},     {"y_log10", layout->y_log10}};
  return j;
}

}  // namespace

FigurePlan plan_figures(const std::string& run_dir, unsigned jobs) {
  const std::string path = run_dir + "/analysis/figures.json";
  if (!fs::exists(path))
    throw UserError(path + " not found: run `renderaudit analyze " + run_dir + "` first");
  json doc;
  try {
    doc = json::parse(read_file(path));
  } catch (const json::exception& e) {
    throw UserError(path + ": not valid JSON: " + e.what());
  }
  if (doc.value("schema", "") != "renderaudit-figures" || doc.value("schema_version", 0) != 1)
    throw UserError(path + ": expected schema renderaudit-figures version 1 (run `renderaudit "
                    "analyze " + run_dir + "` again)");

  an::LoadOptions lo;
  lo.jobs = jobs;
  const an::RunRecords run = an::load_run_records(run_dir, lo);
  const RecordScan scan = scan_records(run_dir, 0, jobs);

  Planner p{run_dir, doc, run, scan, {}, {}};
  try {
    for (an::PrimitiveKind kind : an::kAllKinds) {
      const auto kinds = run.kinds();
      if (std::find(kinds.begin(), kinds.end(), kind) == kinds.end()) {
        p.skip(section_of(kind), "every figure of " + std::string(section_of(kind)),
               std::string("the run has no records of ") + section_of(kind));
        continue;
      }
      p.visibility(kind);
      p.conformance(kind);
      p.conformance_classes(kind);
      p.box_plots(kind);
      p.histograms(kind);
      p.comparisons(kind);
      p.speed_error(kind);
    }
  } catch (const json::exception& e) {
    throw UserError(path + ": unexpected content: " + e.what() + " (run `renderaudit analyze " +
                    run_dir + "` again)");
  }
  return std::move(p.plan);
}

PlotResult plot_run(const PlotOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  if (!fs::is_directory(options.run_dir))
    throw UserError(options.run_dir + ": no such run directory");
  FigurePlan plan = plan_figures(options.run_dir, options.jobs);

  PlotResult result;
  result.figures_dir = (fs::path(options.run_dir) / "figures").string();
  result.index_path = result.figures_dir + "/index.json";
  result.skipped = plan.skipped;

  // Figures of an earlier plot are replaced as a whole: the directory describes the last plot.
  fs::remove_all(result.figures_dir);
  fs::create_directories(result.figures_dir);

  HeadlessDisplay display;
  result.display = display.display();
  result.private_xvfb = display.private_server();
  json figures = json::array();
  {
    FigureRenderer renderer;
    const bool tty = ::isatty(2);
    for (std::size_t i = 0; i < plan.figures.size(); ++i) {
      const Figure& f = plan.figures[i];
      if (options.progress)  // one line rewritten on a terminal, a line per figure in a log
        std::fprintf(stderr, tty ? "\r[%zu/%zu] %s\033[K" : "[%zu/%zu] %s\n", i + 1,
                     plan.figures.size(), f.id.c_str());
      const RenderedFigure r = renderer.render(f, result.figures_dir + "/" + f.id);
      IndexedFigure x{f.id,          figure_kind_name(f), f.section,     f.title,
                      f.caption,     r.note,              f.id + ".png", f.id + ".pdf",
                      f.id + ".csv"};
      figures.push_back(figure_json(x, &r.layout));
      result.figures.push_back(std::move(x));
    }
    if (options.progress && tty) std::fputc('\n', stderr);
  }
  display.stop();

  json skipped = json::array();
  for (const auto& s : result.skipped)
    skipped.push_back({{"section", s.section}, {"what", s.what}, {"reason", s.reason}});
  result.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  json index{{"schema", "renderaudit-figure-index"},
             {"schema_version", 1},
             {"run_dir", options.run_dir},
             {"png_route", "VTK: vtkWindowToImageFilter -> vtkPNGWriter"},
             {"pdf_route", "VTK: vtkPDFExporter (vector)"},
             {"display", result.private_xvfb ? "private Xvfb " + result.display : result.display},
             {"figures", figures},
             {"skipped", skipped},
             {"seconds", result.seconds}};
  write_file_atomic(result.index_path, index.dump(2) + "\n");
  return result;
}

PlotResult read_figure_index(const std::string& run_dir) {
  const std::string path = run_dir + "/figures/index.json";
  if (!fs::exists(path))
    throw UserError(path + " not found: run `renderaudit plot " + run_dir + "` first");
  PlotResult r;
  r.figures_dir = run_dir + "/figures";
  r.index_path = path;
  try {
    const json doc = json::parse(read_file(path));
    if (doc.value("schema", "") != "renderaudit-figure-index")
      throw UserError(path + ": not a figure index (run `renderaudit plot " + run_dir + "` again)");
    for (const json& f : doc.at("figures"))
      r.figures.push_back({f.at("id"), f.at("kind"), f.value("section", ""), f.value("title", ""),
                           f.value("caption", ""), f.value("note", ""), f.at("png"), f.at("pdf"),
                           f.at("csv")});
    for (const json& s : doc.value("skipped", json::array()))
      r.skipped.push_back({s.value("section", ""), s.value("what", ""), s.value("reason", "")});
    r.display = doc.value("display", "");
    r.seconds = doc.value("seconds", 0.0);
  } catch (const json::exception& e) {
    throw UserError(path + ": malformed (" + std::string(e.what()) + "); run `renderaudit plot " +
                    run_dir + "` again");
  }
  return r;
}

}  // namespace ra::plots
