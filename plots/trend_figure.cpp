// Trend figures: the history's medians and IQRs as IQR bands per audit (trend_figure.h).
#include "plots/trend_figure.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "analysis/paper_tables.h"
#include "analysis/run_records.h"
#include "plots/figure_builders.h"
#include "plots/headless_display.h"
#include "util/cell_text.h"
#include "util/errors.h"

namespace ra::plots {
namespace {

namespace an = ra::analysis;

// The trend's own numbers, in record units (the box plot's CSV would show the bands as quartiles).
void write_trend_csv(const TrendData& data, const std::string& path) {
  std::ofstream out(path, std::ios::trunc);
  out << "audit,date_utc,series,n,median,iqr\n";
  for (const TrendSeries& s : data.series)
    for (const TrendPoint& p : s.points)
      out << util::csv_escape(data.audits.at(p.audit)) << ','
          << util::csv_escape(p.audit < data.dates.size() ? data.dates[p.audit] : "") << ','
          << util::csv_escape(s.name) << ',' << p.n << ','
          << util::full_precision_if_finite(p.median) << ','
          << util::full_precision_if_finite(p.iqr) << '\n';
  out.close();
  if (!out) throw util::UserError("cannot write " + path);
}

}  // namespace

std::string trend_axis_label(const std::string& metric, double max_abs, int* exponent) {
  int e = -1;
  for (const auto& spec : an::metric_table_specs())
    if (metric == spec.column) e = spec.scale_exponent;
  if (e < 0) e = display_exponent(max_abs);
  *exponent = e;
  std::string symbol = metric, units;
  for (geometry::Kind k : an::kAllKinds)
    for (const an::MetricSpec& m : an::kind_metrics(k))
      if (metric == m.column) symbol = m.symbol, units = an::unit_name(m.unit);
  // Same form as the run figures' axes: the numbers shown are the metric x 10^e.
  std::string label = symbol + (e > 0 ? " x 10^" + std::to_string(e) : "");
  return units.empty() ? label : label + " (" + units + ")";
}

Figure trend_figure(const TrendData& data) {
  double max_abs = 0;
  for (const TrendSeries& s : data.series)
    for (const TrendPoint& p : s.points)
      if (std::isfinite(p.median)) {
        const double half = std::isfinite(p.iqr) ? 0.5 * p.iqr : 0;
        max_abs = std::max({max_abs, std::fabs(p.median - half), std::fabs(p.median + half)});
      }
  int exponent = 0;
  Figure f;
  f.id = data.id;
  f.y_label = trend_axis_label(data.metric, max_abs, &exponent);
  const double scale = std::pow(10.0, exponent);
  const std::string symbol = f.y_label.substr(0, f.y_label.find(' '));
  f.title = symbol + " over the last " + std::to_string(data.audits.size()) +
            (data.audits.size() == 1 ? " audit" : " audits") +
            ": median and IQR per platform, kind and view group";
  f.x_label = "audit (history id, oldest left)";
  f.section = "history";
  f.caption = "Trend of " + symbol +
              " in the audit history: for each audit and each platform, "
              "kind and view group of its current run, the median (black line) and a band as "
              "tall as the IQR centred on it.";
  f.note =
      "Each box is the IQR centred on the median (the history stores medians and IQRs, not "
      "quartiles); no whiskers.";
  if (!data.audits.empty() && data.dates.size() == data.audits.size())
    f.note += " Audits " + data.audits.front() + " (" + data.dates.front() + ") to " +
              data.audits.back() + " (" + data.dates.back() + ").";
  if (!data.note.empty()) f.note += " " + data.note;

  BoxPlotContent c;
  c.categories = data.audits;
  for (const TrendSeries& s : data.series) {
    c.series.push_back(s.name);
    for (const TrendPoint& p : s.points) {
      if (!std::isfinite(p.median)) continue;
      const double half = std::isfinite(p.iqr) ? 0.5 * p.iqr : 0;
      Box b;
      b.category = data.audits.at(p.audit);
      b.series = s.name;
      b.median = p.median * scale;
      b.q1 = b.lower_whisker = b.min = (p.median - half) * scale;
      b.q3 = b.upper_whisker = b.max = (p.median + half) * scale;
      b.n = std::size_t(p.n);
      c.boxes.push_back(b);
    }
  }
  f.content = std::move(c);
  return f;
}

std::vector<RenderedFigure> draw_trend_figures(const std::vector<TrendData>& trends,
                                               const std::string& out_dir) {
  std::error_code ec;
  std::filesystem::create_directories(out_dir, ec);
  if (!std::filesystem::is_directory(out_dir))
    throw util::UserError("cannot create the directory " + out_dir + ": " + ec.message());
  std::vector<RenderedFigure> out;
  if (trends.empty()) return out;
  HeadlessDisplay display;
  {
    FigureRenderer renderer;
    for (const TrendData& t : trends) {
      RenderedFigure r = renderer.render(trend_figure(t), out_dir + "/" + t.id);
      write_trend_csv(t, r.csv);
      out.push_back(std::move(r));
    }
  }
  display.stop();
  return out;
}

}  // namespace ra::plots
