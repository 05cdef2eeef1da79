// Tests of `renderaudit analyze`: the whole analysis in process on synthetic runs (files written,
// no NaN anywhere, empty and constant samples, options), located errors for bad input, and end to
// end through the binary on a directory written by `renderaudit run`.
#include "analysis/run_analysis.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <regex>

#include "analysis/records_testing.h"
#include "stats/csv_table.h"
#include "util/errors.h"
#include "tests/cli_harness.h"

namespace ra::analysis {
namespace {

namespace fs = std::filesystem;
using testing::point;
using testing::read_text;
using testing::write_records;

const std::regex& not_a_number() {
  static const std::regex r(R"(\b-?(nan|inf|infinity)\b)", std::regex::icase);
  return r;
}

// Every file of DIR/analysis: no NaN or infinity in any of them.
void expect_no_nan(const fs::path& out) {
  for (const auto& e : fs::directory_iterator(out)) {
    const std::string text = read_text(e.path());
    EXPECT_FALSE(std::regex_search(text, not_a_number())) << e.path();
  }
}

template <typename F>
std::string user_error(F f) {
  try {
    f();
  } catch (const util::UserError& e) {
    return e.what();
  }
  return "";
}

// Points in views 1-4 (group A normal-ish, group B constant) and lines with no metric values.
std::vector<metrics::Record> small_run() {
  std::vector<metrics::Record> rs;
  stats::testing::Generator g(5);
  std::uint64_t i = 0;
  for (int view = 1; view <= 2; ++view) {
    for (int k = 0; k < 300; ++k) {
      rs.push_back(point("ref", view, i++, std::hypot(g.uniform() - 0.5, g.uniform() - 0.5)));
    }
  }
  for (int view = 3; view <= 4; ++view) {
    for (int k = 0; k < 5; ++k) rs.push_back(point("ref", view, i++, 0.25));
  }
  for (int view = 1; view <= 4; ++view) rs.push_back(testing::unmeasured_line("ref", view, 0));
  return rs;
}

TEST(AnalyzeCommand, WritesEveryFileWithoutNaN) {
  const testing::ScopedTempDir scoped("analyze_files");
  const std::filesystem::path& dir = scoped.path;
  write_records(dir, small_run());
  AnalyzeOptions o;
  o.run_dir = dir.string();
  o.pixel_pitches_mm = {0.255, 0.294, 1.5};
  const AnalyzeResult r = analyze_run(o);
  EXPECT_EQ(r.out_dir, (dir / "analysis").string());
  EXPECT_EQ(r.records, 614u);
  for (const char* name :
       {"README.md", "report.md", "figures.json", "tally.json", "view_equivalence.csv",
        "view_equivalence.md", "table02_point_visibility.csv", "table02_point_visibility.md",
        "table02_point_visibility.tex", "table03_pe.csv", "table04_pe_norm.tex",
        "table05_line_visibility.md", "table06_lse_s_norm.md", "table07_lse_u_norm.csv",
        "table06s_lse_s.md", "table11_physical_units.md", "speed.md"}) {
    EXPECT_TRUE(fs::exists(dir / "analysis" / name)) << name;
  }
  EXPECT_FALSE(fs::exists(dir / "analysis" / "table08_triangle_visibility.md"));  // no triangles
  EXPECT_FALSE(fs::exists(dir / "analysis" / "cross_platform.md"));               // one platform
  expect_no_nan(dir / "analysis");

  // README lists every file written, one line each
  const std::string readme = read_text(dir / "analysis" / "README.md");
  for (const std::string& f : r.files)
    EXPECT_NE(readme.find("| " + f + " |"), std::string::npos) << f;
  // lines without values: "no data" in Table 6
  EXPECT_NE(read_text(dir / "analysis" / "table06_lse_s_norm.md")
                .find("| A | 30 | 128 | no data | no data |"),
            std::string::npos);
  // the constant group B: a median, IQR 0, equivalence by constants
  EXPECT_NE(
      read_text(dir / "analysis" / "table03_pe.md").find("| B | 150 | 128 | 0.25000 | 0.00000 |"),
      std::string::npos);
  EXPECT_NE(
      read_text(dir / "analysis" / "view_equivalence.csv").find("equivalent,t (pooled),undefined"),
      std::string::npos);
  EXPECT_NE(read_text(dir / "analysis" / "view_equivalence.csv")
                .find("every view is the same constant 0.25"),
            std::string::npos);
  // Table 11 with three pitches
  const std::string t11 = read_text(dir / "analysis" / "table11_physical_units.csv");
  EXPECT_NE(t11.find("\n1.5,B,150,128,0.375,no data\n"), std::string::npos) << t11;
  // the summary printed holds the main tables, not the supplements
  EXPECT_NE(r.summary.find("### Table 3 (mirrors the paper's Table 3)"), std::string::npos);
  EXPECT_EQ(r.summary.find("### Table 6s"), std::string::npos);
  // the stages in order; equivalence, tables and figures run at once, within `statistics`
  ASSERT_EQ(r.timings.size(), 6u);
  const char* const stages[] = {"load", "equivalence", "tables", "figures", "statistics", "write"};
  for (std::size_t i = 0; i < r.timings.size(); ++i) EXPECT_EQ(r.timings[i].stage, stages[i]);
  for (std::size_t i = 1; i <= 3; ++i)
    EXPECT_LE(r.timings[i].seconds, r.timings[4].seconds) << r.timings[i].stage;

  // figures.json: schema, box plots with widths proportional to n, Q-Q of the orientation views
  const nlohmann::json fig = nlohmann::json::parse(read_text(dir / "analysis" / "figures.json"));
  EXPECT_EQ(fig["schema"], "renderaudit-figures");
  EXPECT_EQ(fig["schema_version"], 1);
  const auto& pe_boxes = fig["box_plots"][0];
  EXPECT_EQ(pe_boxes["metric"], "pe");
  ASSERT_EQ(pe_boxes["boxes"].size(), 2u);
  EXPECT_EQ(pe_boxes["boxes"][0]["n"], 600);
  EXPECT_DOUBLE_EQ(pe_boxes["boxes"][0]["relative_width"].get<double>(), 1.0);
  EXPECT_DOUBLE_EQ(pe_boxes["boxes"][1]["relative_width"].get<double>(), 10.0 / 600);
  bool orientation_qq = false;
  for (const auto& c : fig["comparisons"]) {
    if (c["what"] == "orientations" && c["metric"] == "pe" && c["a"]["view_group"] == "A") {
      orientation_qq = true;
      EXPECT_EQ(c["figure"], "Fig. 4");
      EXPECT_EQ(c["qq"]["x"].size(), 300u);
      EXPECT_EQ(c["qq"]["subsampled"], false);
      EXPECT_EQ(c["a"]["views"], nlohmann::json::array({1}));
      // The figure's test is the view-equivalence analysis' test of the same pair: same p-values,
      // same verdict (the Q-Q page states it)
      const stats::CsvTable eq = stats::CsvTable::read_file((dir / "analysis" / "view_equivalence.csv").string());
      bool found = false;
      for (std::size_t r = 0; r < eq.row_count(); ++r) {
        if (eq.cell(r, eq.column("platform")) != c["a"]["platform"].get<std::string>() ||
            eq.cell(r, eq.column("metric")) != "pe" || eq.cell(r, eq.column("view_group")) != "A")
          continue;
        found = true;
        EXPECT_EQ(c["test"]["location"], "t_pooled");
        EXPECT_NEAR(c["test"]["location_p"].get<double>(),
                    *eq.number(r, eq.column("raw_location_p")), 1e-8);
        EXPECT_NEAR(c["test"]["levene_median_p"].get<double>(),
                    *eq.number(r, eq.column("raw_levene_median_p")), 1e-8);
        EXPECT_EQ(c["test"]["differ"].get<bool>(),
                  eq.cell(r, eq.column("verdict")) != "equivalent");
      }
      EXPECT_TRUE(found);
    }
  }
  EXPECT_TRUE(orientation_qq);
}

TEST(AnalyzeCommand, RemovesStaleFilesOfAnEarlierAnalysis) {
  const testing::ScopedTempDir scoped("analyze_stale");
  const std::filesystem::path& dir = scoped.path;
  write_records(dir, small_run());
  fs::create_directories(dir / "analysis");
  std::ofstream(dir / "analysis" / "cross_platform.csv") << "old";
  std::ofstream(dir / "analysis" / "my_notes.txt") << "mine";
  AnalyzeOptions o;
  o.run_dir = dir.string();
  analyze_run(o);
  EXPECT_FALSE(fs::exists(dir / "analysis" / "cross_platform.csv"));
  EXPECT_TRUE(fs::exists(dir / "analysis" / "my_notes.txt"));
}

TEST(AnalyzeCommand, QQPointsAreCappedForLargeSamples) {
  const testing::ScopedTempDir scoped("analyze_qq");
  const std::filesystem::path& dir = scoped.path;
  std::vector<metrics::Record> rs;
  stats::testing::Generator g(9);
  for (int view = 1; view <= 2; ++view) {
    for (std::uint64_t k = 0; k < 2500; ++k) rs.push_back(point("ref", view, k, g.uniform()));
  }
  write_records(dir, rs);
  AnalyzeOptions o;
  o.run_dir = dir.string();
  analyze_run(o);
  const nlohmann::json fig = nlohmann::json::parse(read_text(dir / "analysis" / "figures.json"));
  for (const auto& c : fig["comparisons"]) {
    EXPECT_LE(c["qq"]["x"].size(), 2000u);
    EXPECT_EQ(c["qq"]["subsampled"], true);
  }
}

TEST(AnalyzeCommand, BadOptionsAndInputAreUserErrors) {
  const testing::ScopedTempDir scoped("analyze_bad");
  const std::filesystem::path& dir = scoped.path;
  AnalyzeOptions o;
  o.run_dir = (dir / "missing").string();
  EXPECT_NE(user_error([&] { analyze_run(o); }).find(o.run_dir + ": no such directory"),
            std::string::npos);
  o.run_dir = dir.string();
  fs::create_directories(dir / "records");
  EXPECT_NE(user_error([&] { analyze_run(o); }).find("no records files"), std::string::npos);
  const std::string path = write_records(dir, {point("p", 1, 0, 0.3)});
  std::ofstream(path, std::ios::app) << "p,1,0,1,30,128,128,0.01,10,point,1,ok\n";
  EXPECT_NE(user_error([&] { analyze_run(o); }).find(path + ":3: expected 39 fields, found 12"),
            std::string::npos);
  o.alpha = 1.5;
  EXPECT_NE(user_error([&] { analyze_run(o); }).find("--alpha 1.5"), std::string::npos);
  o.alpha = 0.05;
  o.pixel_pitches_mm = {0.255, -1};
  EXPECT_NE(user_error([&] { analyze_run(o); }).find("--pixel-pitch-mm"), std::string::npos);
}

TEST(AnalyzeCommand, EndToEndOnARunOfTheReferencePlatform) {
  using namespace ra::testing_cli;
  const std::string dir = fresh_dir("analyze_e2e");
  write_text(dir + "/e.toml",
             "seed = 7\nplatforms = [\"reference\"]\n[views]\norientations = 2\n"
             "fov_deg = [30, 150]\nwindows = [64]\nnear = 0.01\nfar = 10.0\n[primitives]\n"
             "points = 2000\nlines = 0\ntriangles = 0\n[run]\nshard_size = 1000\n");
  const Outcome run = run_renderaudit("run " + dir + "/e.toml --out " + dir + "/run --jobs 2");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const Outcome a = run_renderaudit("analyze " + dir + "/run --pixel-pitch-mm 0.255,0.294");
  ASSERT_EQ(a.exit_code, 0) << a.output;
  EXPECT_NE(a.output.find("Wrote "), std::string::npos);
  EXPECT_NE(a.output.find(dir + "/run/analysis"), std::string::npos) << a.output;
  EXPECT_NE(a.output.find("## View equivalence"), std::string::npos) << a.output;
  const fs::path out = fs::path(dir) / "run" / "analysis";
  const std::vector<std::pair<std::string, std::string>> titles = {
      {"table02_point_visibility.md", "### Table 2 (mirrors the paper's Table 2)"},
      {"table03_pe.md", "### Table 3 (mirrors the paper's Table 3)"},
      {"table04_pe_norm.md", "### Table 4 (mirrors the paper's Table 4)"},
      {"table11_physical_units.md", "### Table 11 (mirrors the paper's Table 11)"},
      {"table03_pe.csv", "# Table 3 (mirrors the paper's Table 3)"},
      {"table03_pe.tex", "\\caption{Table 3 (mirrors the paper's Table 3)"},
      {"view_equivalence.md", "# View equivalence"},
      {"speed.md", "### Render time beside error"},
      {"README.md", "| figures.json |"},
  };
  for (const auto& [file, title] : titles) {
    ASSERT_TRUE(fs::exists(out / file)) << file;
    EXPECT_NE(read_text(out / file).find(title), std::string::npos) << file;
  }
  // two view groups of one window: A (FOV 30) and B (FOV 150), 2000 points per view
  const std::string t2 = read_text(out / "table02_point_visibility.csv");
  EXPECT_NE(t2.find("\nreference,A,"), std::string::npos) << t2;
  EXPECT_NE(t2.find("\nreference,B,"), std::string::npos) << t2;
  expect_no_nan(out);

  const Outcome missing = run_renderaudit("analyze " + dir + "/nothing-here");
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.output.find(dir + "/nothing-here: no such directory"), std::string::npos)
      << missing.output;
  if (!::testing::Test::HasFailure()) fs::remove_all(dir);
}

}  // namespace
}  // namespace ra::analysis
