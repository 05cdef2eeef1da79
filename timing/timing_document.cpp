// The rendering-time study's document, timing.md (timing_document.h).
#include "timing/timing_document.h"

#include <cstdio>
#include <sstream>
#include <vector>

#include "stats/table_writer.h"
#include "util/json_number.h"
#include "util/number_text.h"

namespace ra::timing {
namespace {

using nlohmann::json;

// "mean +- sd" of a spread of timing.json's `repeated` block (keys with `unit` appended), scaled.
std::string mean_sd(const json& spread, const std::string& unit = "", double scale = 1) {
  auto v = [&](const char* k) {
    const json x = spread.value(std::string(k) + unit, json());
    return x.is_number() ? json(x.get<double>() * scale) : json();
  };
  return util::json_number_text(v("mean")) + " +- " + util::json_number_text(v("sd"), "%.2g");
}

// "lo - hi" of two numbers of a spread, scaled.
std::string range(const json& spread, const std::string& lo, const std::string& hi,
                  double scale = 1) {
  auto v = [&](const std::string& k) {
    const json x = spread.value(k, json());
    return x.is_number() ? json(x.get<double>() * scale) : json();
  };
  return util::json_number_text(v(lo)) + " - " + util::json_number_text(v(hi));
}

// Table 6 and c over the repeated runs (timing.json's `repeated`, repeated_runs.h).
void repeated_markdown(const json& rep, std::ostringstream& md) {
  const std::string n = std::to_string(rep.value("runs", 0));
  const std::string ci = util::json_number_text(json(100 * rep.value("confidence", 0.95)), "%.0f") + "%";
  md << "## Repeated runs: Table 6 and c over " << n << " independent measurements\n\n"
     << "The study was measured " << n << " times, one run after the other: in each run every "
        "platform was measured afresh (frame base, object measurements, camera paths, per-object "
        "tables, system task) with the same experiment and seed, so the spread below is that of "
        "the measurement on this machine, not of the sampled viewpoints. The tables above are run "
     << rep.value("primary_run", 1)
     << "'s. Spread: SD across runs (n - 1), min - max, and the Student-t " << ci
     << " interval of the mean (wide with few runs: t = 12.7 for 2, 4.3 for 3; a bound below 0, "
        "where no squared error lies, says only that the runs are too few). A method wins a run "
        "when its average squared error is the lowest of the scene's row.\n\n";

  md << "### System task c (99%) over " << n << " runs\n\n"
     << stats::markdown_header({"Platform", "Runs ok", "Failed", "c mean +- SD, ms", "Min - max, ms",
                ci + " interval of the mean, ms"}, 1);
  for (const json& p : rep.value("platforms", json::array())) {
    const json c = p.value("system_task_c", json::object());
    md << stats::markdown_row({p.value("name", ""), std::to_string(p.value("runs", 0)),
               std::to_string(p.value("failed", 0)), mean_sd(c, "_us", 1e-3),
               range(c, "min_us", "max_us", 1e-3), range(c, "ci_low_us", "ci_high_us", 1e-3)});
  }
  md << "\n";

  for (const json& p : rep.value("platforms", json::array())) {
    const std::string name = p.value("name", "");
    const std::vector<std::string> methods = p.value("methods", std::vector<std::string>{});
    const json t6 = p.value("table6_ms2", json::object());
    const json ranking = p.value("ranking", json::object());
    if (t6.empty()) continue;
    std::vector<std::string> cols = {"Scene"};
    cols.insert(cols.end(), methods.begin(), methods.end());
    md << "### Table 6 over " << n << " runs, " << name
       << ": mean +- SD of the average squared error (ms^2)\n\n"
       << stats::markdown_header(cols, 1);
    for (const auto& [scene, by_method] : t6.items()) {
      std::vector<std::string> cells = {scene};
      for (const auto& m : methods) cells.push_back(mean_sd(by_method.value(m, json::object())));
      md << stats::markdown_row(cells);
    }
    md << "\n### Which method was best, " << name << ": runs won out of " << n
       << " (all methods; in brackets among the paper's forms h1-h4 and pos)\n\n"
       << stats::markdown_header(cols, 1);
    for (const auto& [scene, rk] : ranking.items()) {
      std::vector<std::string> cells = {scene};
      const json wins = rk.value("wins", json::object());
      const json paper = rk.value("paper_wins", json::object());
      for (const auto& m : methods)
        cells.push_back(std::to_string(wins.value(m, 0)) +
                        (paper.contains(m) ? " (" + std::to_string(paper.value(m, 0)) + ")" : ""));
      md << stats::markdown_row(cells);
    }
    md << "\n### Table 6 over " << n << " runs, " << name << ", cell by cell (ms^2)\n\n"
       << stats::markdown_header({"Scene", "Method", "Mean", "SD", "Min - max", ci + " interval of the mean",
                  "Wins"}, 2);
    for (const auto& [scene, by_method] : t6.items()) {
      const json wins = ranking.value(scene, json::object()).value("wins", json::object());
      for (const auto& m : methods) {
        const json c = by_method.value(m, json::object());
        md << stats::markdown_row({scene, m, util::json_number_text(c.value("mean", json())), util::json_number_text(c.value("sd", json()), "%.2g"),
                   range(c, "min", "max"), range(c, "ci_low", "ci_high"),
                   std::to_string(wins.value(m, 0))});
      }
    }
    md << "\n### Ranking per run, " << name << " (best first)\n\n"
       << stats::markdown_header({"Scene", "Run", "Methods from the lowest to the highest error"}, 3);
    for (const auto& [scene, rk] : ranking.items()) {
      int k = 0;
      for (const json& order : rk.value("per_run", json::array())) {
        std::string line;
        for (const json& m : order) line += (line.empty() ? "" : " < ") + m.get<std::string>();
        md << stats::markdown_row({scene, std::to_string(++k), line});
      }
    }
    md << "\n";
  }
}
}  // namespace

std::string timing_markdown(const json& j) {
  std::ostringstream md;
  const json host = j.value("host", json::object());
  md << "# Rendering-time study\n\n"
     << "The study of Wimmer & Wonka, Rendering Time Estimation for Real-Time Rendering (EGSR "
        "2003), on this machine: experiment `"
     << j.value("experiment", json::object()).value("file", "") << "`, measured "
     << j.value("created_utc", "") << " on " << host.value("hostname", "") << " ("
     << host.value("cpu", "") << ", " << host.value("cores", 0) << " cores, "
     << host.value("os", "") << "). Times are wall-clock; run the study on an otherwise idle "
        "machine.\n\n";
  if (j.contains("repeated") && j["repeated"].is_object())
    md << "Measured " << j["repeated"].value("runs", 0) << " times (study_runs): the tables are "
       << "run " << j["repeated"].value("primary_run", 1) << "'s; Table 6 and c over every run "
       << "are in the last section.\n\n";

  const json platforms = j.value("platforms", json::array());
  md << "### Platforms and timers\n\n"
     << stats::markdown_header({"Platform", "GL_RENDERER", "Timer query", "Wall s", "Error"}, 3);
  for (const json& p : platforms) {
    const json tq = p.value("timer_query", json::object());
    md << stats::markdown_row({p.value("name", ""), p.value("renderer", json::object()).value("renderer", ""),
               tq.value("supported", false) ? "GL_TIME_ELAPSED, " + std::to_string(tq.value("counter_bits", 0)) + " bits" : "no",
               util::json_number_text(p.value("wall_s", json()), "%.0f"),
               p.value("error", json()).is_string() ? p["error"].get<std::string>() : ""});
  }
  md << "\n";

  md << "### System task: frame times of one viewpoint and the constant c\n\n"
     << stats::markdown_header({"Platform", "Scene", "Renderings", "Min ms", "Median ms", "q99 ms", "c = q99 - min, ms"}, 2);
  for (const json& p : platforms) {
    const json st = p.value("system_task", json());
    if (!st.is_object()) continue;
    auto ms = [&](const char* k) { return st.contains(k) && st[k].is_number() ? util::json_number_text(json(st[k].get<double>() / 1000.0), "%.3f") : "n/a"; };
    md << stats::markdown_row({p.value("name", ""), st.value("scene", ""), std::to_string(st.value("n", 0)),
               ms("min_us"), ms("median_us"), ms("q99_us"), util::json_number_text(st.value("c_ms", json()), "%.3f")});
  }
  md << "\nc is the width of the one-sided interval from the fastest rendering that holds 99% of "
        "them (Hyndman-Fan 6 quantile): a frame budget of min + c is met by 99% of renderings.\n\n";

  md << "### Scenes (the paper's Table 5)\n\n"
     << stats::markdown_header({"Platform", "Scene", "Objects", "Triangles", "#tv", "#tv / tri", "Textures",
                "State switches", "Path frames measured", "Object samples"}, 2);
  for (const json& p : platforms)
    for (const json& s : p.value("scenes", json::array()))
      md << stats::markdown_row({p.value("name", ""), s.value("name", ""), std::to_string(s.value("objects", 0)),
                 std::to_string(s.value("triangles", 0)), std::to_string(s.value("transformed", 0)),
                 util::json_number_text(s.value("tv_per_triangle", json()), "%.2f"), std::to_string(s.value("textures", 0)),
                 std::to_string(s.value("state_switches", 0)),
                 std::to_string(s.value("frames_measured", 0)),
                 std::to_string(s.value("object_samples", 0))});
  md << "\n";

  md << "### Fitted heuristics (least squares, QR; CPU medians of the object measurements)\n\n"
     << stats::markdown_header({"Platform", "Heuristic", "Formula", "Coefficients (value +- standard error)", "n", "R^2", "RMSE us"}, 4);
  for (const json& p : platforms)
    for (const json& f : p.value("fits", json::array())) {
      std::string coef;
      for (const json& c : f.value("parameters", json::array()))
        coef += (coef.empty() ? "" : "; ") + c.value("name", "") + " = " +
                util::json_number_text(c.value("value", json())) + " +- " + util::json_number_text(c.value("standard_error", json()), "%.2g") +
                " " + c.value("unit", "");
      md << stats::markdown_row({p.value("name", ""), f.value("heuristic", "") + (f.value("intercept", false) ? " (+b)" : ""),
                 f.value("formula", ""), coef, std::to_string(f.value("n", 0)),
                 util::json_number_text(f.value("r_squared", json()), "%.3f"), util::json_number_text(f.value("rmse_us", json()), "%.0f")});
    }
  md << "\n";

  for (const json& p : platforms) {
    const json t6 = p.value("table6_ms2", json::object());
    if (t6.empty()) continue;
    std::vector<std::string> methods = p.value("table6_methods", std::vector<std::string>{});
    if (methods.empty())
      for (const auto& [m, v] : t6.begin().value().items()) methods.push_back(m);
    std::vector<std::string> cols = {"Scene"};
    cols.insert(cols.end(), methods.begin(), methods.end());
    md << "### Table 6, " << p.value("name", "")
       << ": average squared error of the predicted frame time along the camera path (ms^2)\n\n"
       << stats::markdown_header(cols, 1);
    for (const auto& [scene, by_method] : t6.items()) {
      std::vector<std::string> cells = {scene};
      for (const auto& m : methods) cells.push_back(util::json_number_text(by_method.value(m, json()), "%.4g"));
      md << stats::markdown_row(cells);
    }
    md << "\nh1-h4: the paper's forms (no intercept); +b: with a per-object intercept; pos: "
          "per-object sampling tables. Predictions add the measured empty frame.\n\n";
  }

  md << "### CPU clock against GL_TIME_ELAPSED\n\n"
     << stats::markdown_header({"Platform", "Draws", "Objects: GPU/CPU median ratio", "Pearson r", "Frames: ratio", "Pearson r"}, 1);
  for (const json& p : platforms) {
    const json c = p.value("cpu_vs_gpu", json());
    if (!c.is_object()) {
      md << stats::markdown_row({p.value("name", ""), "no GPU timer", "", "", "", ""});
      continue;
    }
    const json o = c.value("objects", json::object()), f = c.value("frames", json::object());
    md << stats::markdown_row({p.value("name", ""), std::to_string(o.value("n", 0)), util::json_number_text(o.value("median_ratio", json())),
               util::json_number_text(o.value("pearson_r", json()), "%.3f"), util::json_number_text(f.value("median_ratio", json())),
               util::json_number_text(f.value("pearson_r", json()), "%.3f")});
  }
  md << "\n";
  if (j.contains("repeated") && j["repeated"].is_object()) repeated_markdown(j["repeated"], md);
  return md.str();
}

}  // namespace ra::timing
