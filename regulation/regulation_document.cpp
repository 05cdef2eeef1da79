// The regulation study's document (regulation_document.h): regulation.md from regulation.json.
#include "regulation/regulation_document.h"

#include <algorithm>
#include <sstream>
#include <vector>

#include "rundir/study_dir.h"
#include "stats/table_writer.h"
#include "util/atomic_file.h"
#include "util/errors.h"
#include "util/number_text.h"
#include "util/json_number.h"
#include "util/json_file.h"

namespace ra::regulation {

using nlohmann::json;

json read_regulation_json(const std::string& dir) {
  const auto info = rundir::read_study_info(dir);
  if (!info || info->kind != rundir::StudyKind::kRegulation)
    throw util::UserError(dir +
                          " is not a complete regulation study (no study.json of kind regulation: "
                          "run `renderaudit run` on a regulation experiment first)");
  try {
    return util::parse_json_document(util::read_file(dir + "/regulation.json"), dir + "/regulation.json");
  } catch (const std::exception& e) {
    throw util::UserError(dir + "/regulation.json cannot be read: " + e.what());
  }
}

namespace {

std::string regulation_markdown(const json& j) {
  std::ostringstream md;
  const json& sc = j["scene"];
  const json& cm = j["cost_model"];
  const json& rnd = j["random"];
  const json& rq = rnd["value_ratio"];
  md << "# Decision-theoretic regulation\n\n"
     << "Horvitz & Lengyel, Perception, Attention, and Resources: A Decision-Theoretic Approach to "
        "Graphics Rendering (UAI 1997), sections 5-7, with levels of detail in place of Talisman's "
        "sprites: experiment `" << j["experiment"].value("file", "") << "`, scene `"
     << sc.value("name", "") << "` (" << sc.value("kind", "") << ", " << sc.value("objects", 0)
     << " objects, " << sc.value("path_frames", 0) << " path frames, planned every "
     << sc.value("frame_stride", 1) << " frames), computed " << j.value("created_utc", "") << ".\n\n";
  md << "### Method\n\n"
     << "- **Levels of detail**: meshoptimizer's `meshopt_simplify` per texture group at the target "
        "triangle ratios below, restripified; the error of a level is the simplifier's, in metres.\n"
     << "- **Time** (the timing study's H4): " << util::json_number_text(cm["intercept_us"]) << " us + "
     << util::json_number_text(cm["c1_us_per_tv"]) << " us x #tv + " << util::json_number_text(cm["c2_us_per_pixel"]) << " us x #pix ("
     << cm.value("source", "") << "); #pix " << cm.value("pixels", "") << "; knapsack costs rounded up to "
     << util::json_number_text(cm["cost_unit_us"]) << " us.\n"
     << "- **Perceptual cost** (section 7.2): screen-area fraction x (projected geometric error in "
        "pixels)^" << util::json_number_text(j["attention"]["error_exponent"]) << ", 0 at full detail.\n"
     << "- **Attention** (equations 4 and 6, alpha = " << util::json_number_text(j["attention"]["alpha"])
     << "): each object is weighted by q + (1 - q) alpha, q = p(A_S | A_O) p(A_O).\n"
     << "- **Policies**: `greedy` = increments of each object's convex-hull upgrade chain in "
        "decreasing Phi = gain / cost, compared with the best single-object upgrade (the better "
        "of the two); `greedy_ratio_only` = without that check; `optimal` = dynamic programme over "
        "the integer budget; `uniform` = the finest single level for all objects that fits; "
        "`distance` = levels by distance bands scaled until the plan fits.\n\n";

  md << "### Attention categories\n\n"
     << stats::markdown_header({"Category", "p(attend)", "Seeded share", "Weight", "Objects"}, 1);
  for (const auto& [name, c] : j["attention"]["categories"].items())
    md << stats::markdown_row({name, util::json_number_text(c["probability"], "%.2f"), util::json_number_text(c["share"], "%.2f"), util::json_number_text(c["weight"], "%.3f"),
               std::to_string(c.value("objects", 0))});
  md << "\n### Levels of detail (all objects)\n\n"
     << stats::markdown_header({"Level", "Target ratio", "Objects with it", "Triangles", "#tv", "Median error m", "Max error m"}, 1);
  for (const json& l : j["lod"])
    md << stats::markdown_row({std::to_string(l.value("level", 0)), util::json_number_text(l["target_ratio"], "%.4g"),
               std::to_string(l.value("objects_with_level", 0)), std::to_string(l.value("triangles", 0)),
               std::to_string(l.value("transformed", 0)), util::json_number_text(l["error_median_m"], "%.3g"),
               util::json_number_text(l["error_max_m"], "%.3g")});
  md << "\nAn object whose simplifier could not reduce further keeps fewer levels (counted at its last "
        "level in the sums).\n\n";

  md << "### Greedy against the optimum on random instances\n\n"
     << "The factor-two guarantee holds for the **value**, the expected perceptual cost saved over "
        "the all-coarsest plan: value(OPT) <= 2 value(greedy). The ratio of the expected costs "
        "themselves has no bound.\n\n"
     << stats::markdown_header({"Quantity", "n", "Median", "q90", "q99", "Max", "Above 2"}, 1);
  auto qrow = [&](const std::string& name, const json& q, const json& above) {
    md << stats::markdown_row({name, std::to_string(q.value("n", 0)), util::json_number_text(q.value("q50", json())), util::json_number_text(q.value("q90", json())),
               util::json_number_text(q.value("q99", json())), util::json_number_text(q.value("max", json())),
               above.is_number() ? std::to_string(above.get<int>()) : "-"});
  };
  qrow("value(OPT) / value(greedy)", rq, rnd["value_ratio_above_2"]);
  qrow("value(OPT) / value(greedy, ratio only)", rnd["value_ratio_ratio_only"], rnd["value_ratio_ratio_only_above_2"]);
  qrow("cost(greedy) / cost(OPT), expected perceptual cost", rnd["loss_ratio"], json());
  md << "\n" << rnd.value("instances", 0) << " instances (" << rnd.value("adversarial", 0)
     << " adversarial: the trap of the single-item check and its tight case), "
     << rnd["objects"][0].get<int>() << "-" << rnd["objects"][1].get<int>() << " objects of "
     << rnd["levels"][0].get<int>() << "-" << rnd["levels"][1].get<int>() << " levels; the DP was checked "
        "against brute force on " << rnd.value("brute_forced", 0) << " of them ("
     << rnd.value("dp_mismatches", 0) << " differences); plans over budget: " << rnd.value("over_budget", 0)
     << ".\n\n";

  const json& render = j["render"];
  md << "### Expected perceptual cost against the frame budget (camera path)\n\n"
     << "Mean over the planned frames; the objects may spend the budget minus the empty frame ("
     << util::json_number_text(json(render.value("base_us", 0.0) / 1000.0), "%.3f") << " ms measured).\n\n";
  std::vector<std::string> budgets;
  std::vector<std::string> policies;
  for (const json& r : j["sweep"]) {
    const std::string b = util::json_number_text(r["budget_ms"], "%g");
    if (std::find(budgets.begin(), budgets.end(), b) == budgets.end()) budgets.push_back(b);
    const std::string p = r.value("policy", "");
    if (std::find(policies.begin(), policies.end(), p) == policies.end()) policies.push_back(p);
  }
  std::vector<std::string> cols = {"Policy"};
  for (const auto& b : budgets) cols.push_back(b + " ms");
  md << stats::markdown_header(cols, 1);
  for (const auto& p : policies) {
    std::vector<std::string> cells = {p};
    for (const auto& b : budgets) {
      std::string c = "-";
      for (const json& r : j["sweep"])
        if (r.value("policy", "") == p && util::json_number_text(r["budget_ms"], "%g") == b) c = util::json_number_text(r["mean_expected_cost"]);
      cells.push_back(c);
    }
    md << stats::markdown_row(cells);
  }
  if (render.value("enabled", false) && render["error"].is_null()) {
    md << "\n### Rendered plans: frame skips on " << j.value("platform", "") << "\n\n"
       << render.value("renderer", "") << ", " << render.value("repetitions", 0)
       << " timed repetitions per plan (clear + chosen levels + glFinish); a frame is skipped when "
          "its median measured time exceeds the budget. Relative error = (measured - predicted) / "
          "predicted, median over frames; |error| = |predicted - measured| / measured, median over "
          "frames, with the #pix used and (last column) with the estimated #pix for the same plans.\n\n"
       << stats::markdown_header({"Policy", "Budget ms", "Frames", "Skips", "Skip rate", "Mean predicted ms",
                  "Median measured ms", "Median relative error", "Median abs error",
                  "Median abs error, estimated #pix"}, 1);
    for (const json& r : j["sweep"])
      md << stats::markdown_row({r.value("policy", ""), util::json_number_text(r["budget_ms"], "%g"), std::to_string(r.value("rendered", 0)),
                 std::to_string(r.value("skips", 0)), util::json_number_text(r["skip_fraction"], "%.2f"),
                 util::json_number_text(r["mean_predicted_ms"], "%.2f"), util::json_number_text(r["median_measured_ms"], "%.2f"),
                 util::json_number_text(r["median_relative_error"], "%+.2f"), util::json_number_text(r["median_abs_relative_error"], "%.2f"),
                 util::json_number_text(r["median_abs_relative_error_estimated_pixels"], "%.2f")});
    const json& ae = render["abs_relative_error"];
    const json& ee = render["abs_relative_error_estimated_pixels"];
    md << "\nOver all " << ae.value("n", 0) << " rendered plans, median |predicted - measured| / measured: "
       << util::json_number_text(ae.value("q50", json()), "%.3f") << " (q90 " << util::json_number_text(ae.value("q90", json()), "%.3f")
       << "); with the estimated #pix for the same plans " << util::json_number_text(ee.value("q50", json()), "%.3f")
       << " (q90 " << util::json_number_text(ee.value("q90", json()), "%.3f") << ").\n";
    if (cm.contains("measured_over_estimated_pixels")) {
      const json& q = cm["measured_over_estimated_pixels"];
      md << "Measured #pix of the finest level / estimated #pix per (frame, visible object): median "
         << util::json_number_text(q.value("q50", json()), "%.3f") << ", min " << util::json_number_text(q.value("min", json()), "%.3g")
         << ", max " << util::json_number_text(q.value("max", json()), "%.3g") << " (n = " << q.value("n", 0) << "; pixels.csv).\n";
    }
  } else if (!render["error"].is_null()) {
    md << "\nRendering failed: " << render["error"].get<std::string>() << "\n";
  }
  md << "\n### Findings\n\n";
  md << "- value(OPT) / value(greedy) on " << rnd.value("instances", 0) << " random instances: max "
     << util::json_number_text(rq.value("max", json())) << ", median " << util::json_number_text(rq.value("q50", json()))
     << " (never above 2: " << (rnd.value("value_ratio_above_2", 1) == 0 ? "yes" : "NO") << "); "
     << "without the single-item check the max is " << util::json_number_text(rnd["value_ratio_ratio_only"].value("max", json()))
     << ".\n";
  for (const json& f : j["findings"]) md << "- **Check failed**: " << f.get<std::string>() << "\n";
  md << "\n";
  return md.str();
}

}  // namespace

void analyze_regulation_study(const std::string& dir) {
  const json j = read_regulation_json(dir);
  util::write_file_atomic(dir + "/regulation.md", regulation_markdown(j));
  rundir::StudyInfo info = *rundir::read_study_info(dir);
  info.document = "regulation.md";
  info.analysed = true;
  rundir::write_study_info(dir, info);
}

}  // namespace ra::regulation
