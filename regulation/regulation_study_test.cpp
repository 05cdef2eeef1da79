// End to end: experiments/regulation_smoke.toml through run / analyze / plot into a temporary folder.
#include "regulation/regulation_document.h"
#include "regulation/regulation_figures.h"
#include "regulation/regulation_run.h"

#include <gtest/gtest.h>

#include "plots/figure_testing.h"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "util/atomic_file.h"
#include "util/errors.h"

namespace ra::regulation {
namespace {

TEST(RegulationStudy, SmokeExperimentRunsAnalysesAndPlots) {
  const std::string dir = (std::filesystem::temp_directory_path() / "regulation_smoke_test").string();
  std::filesystem::remove_all(dir);
  EXPECT_THROW(analyze_regulation_study(dir), util::UserError);  // nothing there yet

  rundir::StudyRunOptions o;
  o.experiment = std::string(RA_SOURCE_DIR) + "/experiments/regulation_smoke.toml";
  o.out_dir = dir;
  o.progress = false;
  const rundir::StudyRunResult r = run_regulation_study(o);
  EXPECT_FALSE(r.findings) << r.summary;
  const auto info = rundir::read_study_info(dir);
  ASSERT_TRUE(info);
  EXPECT_EQ(info->kind, rundir::StudyKind::kRegulation);
  EXPECT_FALSE(info->analysed);

  const auto j = nlohmann::json::parse(util::read_file(dir + "/regulation.json"));
  EXPECT_EQ(j["random"]["instances"], 300);
  EXPECT_LE(j["random"]["value_ratio"]["max"].get<double>(), 2.0);
  EXPECT_GE(j["random"]["value_ratio"]["max"].get<double>(), 1.0);
  EXPECT_GT(j["random"]["value_ratio_ratio_only"]["max"].get<double>(), 2.0);  // the traps
  EXPECT_GT(j["random"]["brute_forced"].get<int>(), 100);
  EXPECT_EQ(j["random"]["dp_mismatches"], 0);
  ASSERT_TRUE(j["render"]["error"].is_null()) << j["render"]["error"];
  EXPECT_GT(j["render"]["base_us"].get<double>(), 0.0);
  // 4 frames (8, stride 2) x 4 budgets x 5 policies, every one rendered twice
  int rendered = 0;
  for (const auto& row : j["sweep"]) rendered += row["rendered"].get<int>();
  EXPECT_EQ(rendered, 4 * 4 * 5);
  // more budget never costs more perception for the optimum: mean expected cost non-increasing
  double prev = 1e300;
  for (const auto& row : j["sweep"])
    if (row["policy"] == "optimal") {
      EXPECT_LE(row["mean_expected_cost"].get<double>(), prev + 1e-12);
      prev = row["mean_expected_cost"].get<double>();
    }
  // the LOD chain: level 0 error 0, coarser levels fewer triangles
  EXPECT_EQ(j["lod"][0]["error_max_m"].get<double>(), 0.0);
  EXPECT_LT(j["lod"][1]["triangles"].get<int64_t>(), j["lod"][0]["triangles"].get<int64_t>());

  std::ifstream frames(dir + "/frames.csv");
  std::string line;
  int lines = 0;
  while (std::getline(frames, line)) ++lines;
  EXPECT_EQ(lines, 1 + 4 * 4 * 5);

  analyze_regulation_study(dir);
  const auto info2 = rundir::read_study_info(dir);
  EXPECT_TRUE(info2->analysed);
  EXPECT_EQ(info2->document, "regulation.md");
  const std::string md = util::read_file(dir + "/regulation.md");
  EXPECT_NE(md.find("value(OPT) / value(greedy)"), std::string::npos);
  EXPECT_NE(md.find("frame skips on osmesa-llvmpipe"), std::string::npos);

  plot_regulation_study(dir);
  const auto index = nlohmann::json::parse(util::read_file(dir + "/figures/index.json"));
  EXPECT_NE(index.dump().find("regulation_ratio_histogram"), std::string::npos);
  plots::testing::expect_drawn_png(dir + "/figures/regulation_cost_vs_budget.png");
  plots::testing::expect_drawn_png(dir + "/figures/regulation_frame_skips.png");
  plots::testing::expect_whole_pdf(dir + "/figures/regulation_cost_vs_budget.pdf");
  std::filesystem::remove_all(dir);
}

// A smoke experiment with nothing rendered and few instances (fast), written to a temporary file.
std::string quick_experiment(const std::string& name) {
  const std::string toml = (std::filesystem::temp_directory_path() / (name + ".toml")).string();
  std::string text =
      util::read_file(std::string(RA_SOURCE_DIR) + "/experiments/regulation_smoke.toml");
  auto replace = [&](const std::string& a, const std::string& b) {
    const auto at = text.find(a);
    if (at == std::string::npos) throw std::runtime_error("regulation_smoke.toml lacks " + a);
    text.replace(at, a.size(), b);
  };
  replace("repetitions = 2", "repetitions = 2\nrender = false");
  replace("instances = 300", "instances = 20");
  std::ofstream(toml) << text;
  return toml;
}

// A re-run removes what analyze and plot derived from the previous run, and plot refuses a run
// that has not been analysed.
TEST(RegulationStudy, RerunRemovesDerivedOutputsAndPlotNeedsAnalysis) {
  const std::string toml = quick_experiment("regulation_rerun_test");
  const std::string dir = (std::filesystem::temp_directory_path() / "regulation_rerun_test").string();
  std::filesystem::remove_all(dir);
  rundir::StudyRunOptions o;
  o.experiment = toml;
  o.out_dir = dir;
  o.progress = false;
  run_regulation_study(o);
  try {
    plot_regulation_study(dir);
    ADD_FAILURE() << "plotted a run that was not analysed";
  } catch (const util::UserError& e) {
    EXPECT_EQ(std::string(e.what()), dir + " has not been analysed: run `renderaudit analyze " + dir + "` first");
  }
  EXPECT_FALSE(std::filesystem::exists(dir + "/figures"));
  analyze_regulation_study(dir);
  plot_regulation_study(dir);
  ASSERT_TRUE(std::filesystem::exists(dir + "/regulation.md"));
  ASSERT_TRUE(std::filesystem::exists(dir + "/figures/index.json"));
  run_regulation_study(o);
  EXPECT_FALSE(std::filesystem::exists(dir + "/regulation.md"));
  EXPECT_FALSE(std::filesystem::exists(dir + "/figures"));
  EXPECT_FALSE(rundir::read_study_info(dir)->analysed);
  EXPECT_TRUE(std::filesystem::exists(dir + "/regulation.json"));
  EXPECT_THROW(plot_regulation_study(dir), util::UserError);
  std::filesystem::remove_all(dir);
  std::filesystem::remove(toml);
}

// --platform is checked directly (no TOML text made from it): a name with a quote is an unknown
// platform, and the error names the allowed ones.
TEST(RegulationStudy, PlatformOverrideIsValidatedDirectly) {
  const std::string toml = quick_experiment("regulation_platform_test");
  const std::string dir = (std::filesystem::temp_directory_path() / "regulation_platform_test").string();
  for (const std::string bad : {"osmesa\"llvmpipe", "reference", "osmesa-llvmpipe\"\nrender = true"}) {
    rundir::StudyRunOptions o;
    o.experiment = toml;
    o.out_dir = dir;
    o.progress = false;
    o.platforms = {bad};
    try {
      run_regulation_study(o);
      ADD_FAILURE() << "accepted --platform " << bad;
    } catch (const util::UserError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("--platform"), std::string::npos) << what;
      EXPECT_NE(what.find("allowed: osmesa-llvmpipe, osmesa-softpipe"), std::string::npos) << what;
      EXPECT_EQ(what.find("TOML"), std::string::npos) << what;
    }
  }
  std::filesystem::remove_all(dir);
  std::filesystem::remove(toml);
}

std::vector<std::string> split_csv_line(const std::string& line) {
  std::vector<std::string> cells;
  std::string cell;
  std::istringstream in(line);
  while (std::getline(in, cell, ',')) cells.push_back(cell);
  return cells;
}

// The pixel query of the rendering process against the bounding-sphere disc: for an object far
// enough (distance > 3 radii) that its disc lies wholly inside the window, the finest level's
// measured #pix is positive and within a factor of the disc (a tree's cone and trunk fill part of
// the disc; the depth test is off, so front and back faces both count). The ground, whose sphere
// holds the eye (estimate: the whole window), covers well under the window.
TEST(RegulationStudy, MeasuredPixelsAgainstTheEstimatedDisc) {
  const std::string dir = (std::filesystem::temp_directory_path() / "regulation_smoke_pixels").string();
  std::filesystem::remove_all(dir);
  rundir::StudyRunOptions o;
  o.experiment = std::string(RA_SOURCE_DIR) + "/experiments/regulation_smoke.toml";
  o.out_dir = dir;
  o.progress = false;
  const rundir::StudyRunResult r = run_regulation_study(o);
  EXPECT_FALSE(r.findings) << r.summary;
  const auto j = nlohmann::json::parse(util::read_file(dir + "/regulation.json"));
  ASSERT_TRUE(j["cost_model"]["pixels_measured"].get<bool>());
  const double window = 160.0 * 120.0;  // regulation_smoke.toml
  const double focal = 60.0 / std::tan(M_PI / 6);  // (height / 2) / tan(30 deg), fov 60
  std::istringstream in(util::read_file(dir + "/pixels.csv"));
  std::string line;
  std::getline(in, line);
  ASSERT_EQ(line, "frame,object,name,distance_m,radius_m,estimated_pixels,level,measured_pixels");
  int far = 0, ground = 0, rows = 0;
  while (std::getline(in, line)) {
    const auto c = split_csv_line(line);
    ASSERT_EQ(c.size(), 8u) << line;
    ++rows;
    const double d = std::stod(c[3]), radius = std::stod(c[4]), est = std::stod(c[5]),
                 meas = std::stod(c[7]);
    EXPECT_GE(meas, 0.0);
    EXPECT_LE(meas, 4 * window) << line;  // a fragment per covering triangle: a few layers at most
    if (c[6] != "0") continue;
    if (c[2] == "ground") {
      ++ground;
      EXPECT_EQ(est, window) << line;
      EXPECT_GT(meas, 0.2 * window) << line;
      EXPECT_LT(meas, 0.7 * window) << line;
      continue;
    }
    const double r_px = focal * radius / std::sqrt(d * d - radius * radius);
    const bool whole_disc = d > 3 * radius && std::abs(est - M_PI * r_px * r_px) < 1e-6 * est;
    if (!whole_disc) continue;
    ++far;
    EXPECT_GT(meas, 0.3 * est) << line;
    EXPECT_LT(meas, 1.5 * est) << line;
  }
  EXPECT_EQ(ground, 4);  // every planned frame sees the ground
  EXPECT_GE(far, 2);
  EXPECT_GT(rows, 4 * 4 * 3);  // 4 frames, several visible objects of 4 levels
  std::filesystem::remove_all(dir);
}

// Measured #pix predict the rendered frames better than the estimate: median |predicted -
// measured| / measured of the smoke study with measured pixels (2.1 when this test was written)
// is below the same study's with estimated pixels (6.3), and below the estimate's prediction of
// the same plans.
TEST(RegulationStudy, MeasuredPixelsPredictFrameTimesBetter) {
  const auto tmp = std::filesystem::temp_directory_path();
  const std::string toml = (tmp / "regulation_smoke_estimated.toml").string();
  std::ofstream(toml) << util::read_file(std::string(RA_SOURCE_DIR) +
                                         "/experiments/regulation_smoke.toml")
                      << "\n[regulation.cost_model]\npixels = \"estimated\"\n";
  double median[2];
  for (int measured = 0; measured < 2; ++measured) {
    const std::string dir = (tmp / ("regulation_smoke_px" + std::to_string(measured))).string();
    std::filesystem::remove_all(dir);
    rundir::StudyRunOptions o;
    o.experiment = measured ? std::string(RA_SOURCE_DIR) + "/experiments/regulation_smoke.toml" : toml;
    o.out_dir = dir;
    o.progress = false;
    const rundir::StudyRunResult r = run_regulation_study(o);
    EXPECT_FALSE(r.findings) << r.summary;
    const auto j = nlohmann::json::parse(util::read_file(dir + "/regulation.json"));
    EXPECT_EQ(j["cost_model"]["pixels_measured"].get<bool>(), measured == 1);
    EXPECT_EQ(std::filesystem::exists(dir + "/pixels.csv"), measured == 1);
    const auto& e = j["render"]["abs_relative_error"];
    ASSERT_EQ(e["n"].get<int>(), 4 * 4 * 5);
    median[measured] = e["q50"].get<double>();
    const double same_plans_estimated = j["render"]["abs_relative_error_estimated_pixels"]["q50"].get<double>();
    if (measured)
      EXPECT_LT(median[1], same_plans_estimated);
    else
      EXPECT_DOUBLE_EQ(median[0], same_plans_estimated);  // the estimate is what was used
    std::filesystem::remove_all(dir);
  }
  EXPECT_LT(median[1], median[0]);
  EXPECT_GT(median[0], 1.0);  // the estimate's error this test was written against (> 100 %)
  std::filesystem::remove(toml);
}

// The default experiment (experiments/regulation.toml; RA_REGULATION_EXPERIMENT another) end to
// end, minutes; not part of the suite:
//   RA_REGULATION_OUT=DIR regulation_tests --gtest_also_run_disabled_tests
//       --gtest_filter=*DISABLED_DefaultExperiment*
TEST(RegulationStudy, DISABLED_DefaultExperiment) {
  const char* out = std::getenv("RA_REGULATION_OUT");
  const char* experiment = std::getenv("RA_REGULATION_EXPERIMENT");
  rundir::StudyRunOptions o;
  o.experiment = experiment ? experiment : std::string(RA_SOURCE_DIR) + "/experiments/regulation.toml";
  o.out_dir = out ? out : ::testing::TempDir() + "regulation_default";
  o.progress = true;
  const rundir::StudyRunResult r = run_regulation_study(o);
  std::cerr << r.summary << "\n";
  EXPECT_FALSE(r.findings);
  analyze_regulation_study(o.out_dir);
  plot_regulation_study(o.out_dir);
}

}  // namespace
}  // namespace ra::regulation
