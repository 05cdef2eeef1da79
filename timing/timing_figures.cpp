// The figures of the rendering-time study (timing_figures.h).
#include "timing/timing_figures.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>

#include "stats/descriptive.h"

namespace ra::timing {
namespace {

// Frame-time histogram (density) of the system task, the paper's Figure 3, in ms; the range is
// [min, q_0.999]: the few slowest renderings would squash the picture (they are counted in the note).
plots::Figure density_figure(const PlatformMeasurements& m, const PlatformAnalysis& a) {
  std::vector<double> ms;
  for (double v : m.system_cpu_us) ms.push_back(v / 1000.0);
  std::sort(ms.begin(), ms.end());
  const double lo = ms.front();
  const double hi = std::max(stats::quantile_sorted(ms, 0.999), lo + 1e-6);
  const double iqr = stats::quantile_sorted(ms, 0.75) - stats::quantile_sorted(ms, 0.25);
  // Freedman-Diaconis bin width, at most 200 bins
  double width = iqr > 0 ? 2 * iqr / std::cbrt(double(ms.size())) : (hi - lo) / 50;
  int bins = int(std::ceil((hi - lo) / width));
  bins = std::clamp(bins, 10, 200);
  width = (hi - lo) / bins;
  plots::HistogramSeries s;
  s.name = m.renderer.platform;
  for (int b = 0; b <= bins; ++b) s.edges.push_back(lo + width * b);
  s.counts.assign(std::size_t(bins), 0);
  std::size_t beyond = 0;
  for (double v : ms) {
    if (v > hi) {
      ++beyond;
      continue;
    }
    s.counts[std::size_t(std::min(bins - 1, int((v - lo) / width)))]++;
  }
  for (std::size_t c : s.counts) s.heights.push_back(double(c) / (double(ms.size()) * width));
  s.n = ms.size();
  plots::Figure f;
  f.id = "system_task_density_" + m.renderer.platform;
  f.title = m.renderer.platform + ": frame time of one viewpoint rendered " +
            std::to_string(ms.size()) + " times (" + m.system_scene + ", frame " +
            std::to_string(m.system_frame) + ")";
  f.x_label = "frame time (ms)";
  f.y_label = "empirical density (1/ms)";
  char note[256];
  std::snprintf(note, sizeof note,
                "min %.4g ms, median %.4g ms, q0.99 %.4g ms: c = q0.99 - min = %.4g ms. %zu "
                "rendering(s) above q0.999 (%.4g ms) not shown.",
                a.system.min_us / 1000, a.system.median_us / 1000, a.system.q99_us / 1000,
                a.system.c_us / 1000, beyond, hi);
  f.note = note;
  f.caption = "Empirical density of the frame time of one viewpoint (Wimmer & Wonka 2003, Fig. 3).";
  f.section = "timing";
  plots::HistogramContent c;
  c.density = true;
  c.series.push_back(std::move(s));
  f.content = std::move(c);
  return f;
}

std::string id_part(const std::string& s) {
  std::string o;
  for (char c : s) {
    const char l = char(std::tolower(static_cast<unsigned char>(c)));
    o += (std::isalnum(static_cast<unsigned char>(l)) || l == '-' || l == '.') ? l : '_';
  }
  return o;
}

// Measured and predicted frame time along the path: one step line per series over frame numbers.
plots::Figure path_figure(const std::string& platform, const std::string& scene,
                          const std::vector<FramePrediction>& preds, const std::string& method,
                          double error_ms2) {
  plots::Figure f;
  f.id = "path_" + id_part(platform) + "_" + id_part(scene) + "_" + id_part(method == "pos" ? method : method);
  for (char& c : f.id)
    if (c == '+') c = 'b';
  f.title = platform + ", " + scene + ": measured vs predicted (" + method + ") frame time";
  f.x_label = "frame of the camera path";
  f.y_label = "frame time (ms)";
  char note[160];
  std::snprintf(note, sizeof note, "Average squared error (Table 6): %.4g ms^2 over %zu frames.",
                error_ms2, preds.size());
  f.note = note;
  f.caption = "Frame time along the camera path: measured (median of the repetitions) and "
              "predicted by " + method + ".";
  f.section = "timing";
  plots::HistogramContent c;
  c.density = false;
  plots::HistogramSeries meas, pred;
  meas.name = "measured";
  pred.name = "predicted " + method;
  // Each measured frame is a step from its frame number to the next measured one.
  for (std::size_t i = 0; i < preds.size(); ++i) {
    const double x0 = preds[i].frame;
    const double x1 = i + 1 < preds.size() ? preds[i + 1].frame : x0 + (i ? x0 - preds[i - 1].frame : 1);
    if (i == 0) meas.edges.push_back(x0), pred.edges.push_back(x0);
    meas.edges.push_back(x1);
    pred.edges.push_back(x1);
    meas.heights.push_back(preds[i].measured_us / 1000.0);
    pred.heights.push_back(preds[i].predicted_us.at(method) / 1000.0);
    meas.counts.push_back(1);
    pred.counts.push_back(1);
  }
  meas.n = pred.n = preds.size();
  c.series = {meas, pred};
  f.content = std::move(c);
  return f;
}

}  // namespace

std::vector<plots::Figure> timing_figures(const StudyResults& r) {
  std::vector<plots::Figure> out;
  for (std::size_t i = 0; i < r.measured.size() && i < r.analysed.size(); ++i) {
    const PlatformMeasurements& m = r.measured[i];
    const PlatformAnalysis& a = r.analysed[i];
    if (!m.error.empty()) continue;
    if (!m.system_cpu_us.empty()) out.push_back(density_figure(m, a));
    for (const SceneMeasurements& s : m.scenes) {
      if (!a.frames.count(s.name) || a.frames.at(s.name).empty()) continue;
      for (const std::string& method : a.methods) {
        if (method.find("+b") != std::string::npos) continue;  // the paper's forms and pos
        out.push_back(path_figure(m.renderer.platform, s.name, a.frames.at(s.name), method,
                                  a.table6_ms2.at(s.name).at(method)));
      }
    }
  }
  return out;
}

}  // namespace ra::timing
