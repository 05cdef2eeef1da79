// End-to-end tests of `renderaudit history`: the table of recent audits, the trend figures (PNG,
// PDF, CSV) and the error for a missing database.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "audit/history_db.h"
#include "plots/figure_renderer.h"
#include "tests/cli_harness.h"

namespace fs = std::filesystem;
using namespace ra::testing_cli;

namespace {

// Audit k: two platforms x view groups A, B of triangles, te_u and te_s; te_u's median grows.
ra::audit::AuditSummary audit(int k) {
  ra::audit::AuditSummary s;
  s.date_utc = "2026-11-1" + std::to_string(k) + "T03:00:00Z";
  s.experiment = "nightly";
  s.experiment_hash = "feedface";
  s.seed = 2008;
  s.baseline_run = "/srv/runs/nightly-" + std::to_string(k - 1);
  s.current_run = "/srv/runs/nightly-" + std::to_string(k) + "/";
  s.current_drivers = {{"osmesa-llvmpipe", "llvmpipe (LLVM 15.0.6, 256 bits)",
                        k < 3 ? "4.5 Mesa 22.3.6" : "4.5 Mesa 23.0.0"}};
  s.baseline_drivers = {{"osmesa-llvmpipe", "llvmpipe (LLVM 15.0.6, 256 bits)",
                         k < 4 ? "4.5 Mesa 22.3.6" : "4.5 Mesa 23.0.0"}};
  s.verdict = k == 3 ? ra::audit::Verdict::kChanged : ra::audit::Verdict::kUnchanged;
  s.changed_primitives = k == 3 ? 17 : 0;
  s.flaky_primitives = k == 2 ? 2 : 0;
  s.failed_primitives = 0;
  s.significant_tests = k == 3 ? 1 : 0;
  for (const char* p : {"osmesa-llvmpipe", "osmesa-softpipe"})
    for (int g = 1; g <= 2; ++g) {
      s.metrics.push_back({p, "triangle", "te_u", g, 900, 0.4 + 0.1 * k + 0.05 * g, 0.2});
      s.metrics.push_back({p, "triangle", "te_s", g, 900, -0.01 * k, 0.1});
    }
  return s;
}

std::string file_start(const std::string& path, std::size_t n) {
  std::ifstream in(path, std::ios::binary);
  std::string s(n, '\0');
  in.read(&s[0], std::streamsize(n));
  s.resize(std::size_t(in.gcount()));
  return s;
}

std::size_t lines_in(const std::string& path) {
  std::ifstream in(path);
  std::size_t n = 0;
  for (std::string line; std::getline(in, line);) ++n;
  return n;
}

// The line of the table for audit `id`, white space squeezed.
std::string table_row(const std::string& output, const std::string& id) {
  std::istringstream in(output);
  for (std::string line; std::getline(in, line);)
    if (line.rfind(id + "  ", 0) == 0 || line.rfind(" " + id + "  ", 0) == 0)
      return squeeze(line.substr(line.find('#')));
  return "";
}

TEST(HistoryCommand, PrintsTheRecentAuditsAndDrawsATrendPerMetric) {
  const std::string dir = fresh_dir("history_cmd");
  const std::string db = dir + "/outputs/history.sqlite";
  for (int k = 1; k <= 3; ++k) ra::audit::append_history(db, audit(k));

  const Outcome o = run_renderaudit("history --db " + db + " --metric te_u");
  ASSERT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(o.output.find(db + ": 3 audits, the last 3:"), std::string::npos) << o.output;
  const std::size_t header = o.output.find("id  date");
  ASSERT_NE(header, std::string::npos) << o.output;
  EXPECT_EQ(squeeze(o.output.substr(header, o.output.find('\n', header) - header)),
            "id date (UTC) verdict changed flaky failed tests compares current run baseline run");
  EXPECT_EQ(table_row(o.output, "#1"),
            "#1 2026-11-11T03:00:00Z unchanged 0 0 0 0 two runs nightly-1 nightly-0");
  EXPECT_EQ(table_row(o.output, "#2"),
            "#2 2026-11-12T03:00:00Z unchanged 0 2 0 0 two runs nightly-2 nightly-1");
  EXPECT_EQ(table_row(o.output, "#3"),
            "#3 2026-11-13T03:00:00Z changed 17 0 0 1 two runs nightly-3 nightly-2");
  // Drivers: the current ones, and the baseline's where they differ (audit 3: new Mesa).
  EXPECT_NE(o.output.find("  #3  osmesa-llvmpipe: llvmpipe (LLVM 15.0.6, 256 bits), 4.5 Mesa "
                          "23.0.0\n      baseline: osmesa-llvmpipe: llvmpipe (LLVM 15.0.6, 256 "
                          "bits), 4.5 Mesa 22.3.6\n"),
            std::string::npos)
      << o.output;

  // Default figure directory: beside the database.
  const std::string stem = dir + "/outputs/history/trend_te_u";
  EXPECT_NE(o.output.find(stem + ".png"), std::string::npos) << o.output;
  EXPECT_FALSE(fs::exists(dir + "/outputs/history/trend_te_s.png")) << "only the metric asked for";
  const ra::plots::RgbImage png = ra::plots::read_png(stem + ".png");
  EXPECT_EQ(png.width, 1123);
  EXPECT_EQ(png.height, 794);
  // The first series' colour outlines its IQR bands: many pixels of exactly that colour.
  unsigned char blue[3];
  ra::plots::series_color(0, blue);
  std::size_t coloured = 0;
  for (int y = 0; y < png.height; ++y)
    for (int x = 0; x < png.width; ++x)
      coloured +=
          png.at(x, y)[0] == blue[0] && png.at(x, y)[1] == blue[1] && png.at(x, y)[2] == blue[2];
  EXPECT_GT(coloured, 100u);
  EXPECT_EQ(file_start(stem + ".pdf", 5), "%PDF-");
  EXPECT_GT(fs::file_size(stem + ".pdf"), 2000u);
  // CSV: the trend's numbers in record units, 3 audits x 4 series.
  EXPECT_EQ(lines_in(stem + ".csv"), 1u + 3 * 4);
  char first_row[200];  // audit 1, llvmpipe, group A: median as audit() computes it
  std::snprintf(first_row, sizeof first_row, "%.17g,%.17g\n", 0.4 + 0.1 * 1 + 0.05 * 1, 0.2);
  const std::string csv_start =
      "audit,date_utc,series,n,median,iqr\n#1,2026-11-11T03:00:00Z,"
      "osmesa-llvmpipe triangle A,900," +
      std::string(first_row);
  EXPECT_EQ(file_start(stem + ".csv", csv_start.size()), csv_start);

  // --last 2 and --out.
  const Outcome last = run_renderaudit("history --db " + db + " --last 2 --out " + dir + "/figs");
  ASSERT_EQ(last.exit_code, 0) << last.output;
  EXPECT_NE(last.output.find(db + ": 3 audits, the last 2:"), std::string::npos) << last.output;
  EXPECT_EQ(table_row(last.output, "#1"), "");
  EXPECT_NE(table_row(last.output, "#2"), "");
  EXPECT_EQ(lines_in(dir + "/figs/trend_te_u.csv"), 1u + 2 * 4);
  EXPECT_TRUE(fs::exists(dir + "/figs/trend_te_s.pdf")) << "every metric by default";
}

// A night of `renderaudit watch` audits two platforms of one run, nights/<UTC>/run: the current
// run is named with its night, and the baseline side is said to be that same run (the platforms
// are in the compares column), not "run" twice. Two runs both called "run" are named by the
// folders that tell them apart.
TEST(HistoryCommand, CurrentAndBaselineRunsAreToldApart) {
  const std::string dir = fresh_dir("history_run_labels");
  const std::string db = dir + "/history.sqlite";
  ra::audit::AuditSummary night = audit(1);
  night.current_run = night.baseline_run = "/state/nights/2026-11-12T03-00-00Z/run";
  night.baseline_drivers = {{"egl-llvmpipe@last", "llvmpipe", "4.5 Mesa 25.1.0-devel"}};
  night.current_drivers = {{"egl-llvmpipe@tonight", "llvmpipe", "4.5 Mesa 25.1.0-devel"}};
  ra::audit::append_history(db, night);
  ra::audit::AuditSummary runs = audit(2);
  runs.baseline_run = "/state/nights/2026-11-11T03-00-00Z/run";
  runs.current_run = "/state/nights/2026-11-12T03-00-00Z/run/";
  ra::audit::append_history(db, runs);
  const Outcome o = run_renderaudit("history --db " + db + " --metric te_u --out " + dir + "/h");
  ASSERT_EQ(o.exit_code, 0) << o.output;
  EXPECT_EQ(table_row(o.output, "#1"),
            "#1 2026-11-11T03:00:00Z unchanged 0 0 0 0 egl-llvmpipe@last vs egl-llvmpipe@tonight "
            "2026-11-12T03-00-00Z/run same run")
      << o.output;
  EXPECT_EQ(table_row(o.output, "#2"),
            "#2 2026-11-12T03:00:00Z unchanged 0 2 0 0 two runs 2026-11-12T03-00-00Z/run "
            "2026-11-11T03-00-00Z/run")
      << o.output;
}

TEST(HistoryCommand, AMissingDatabaseOrMetricIsAClearError) {
  const std::string dir = fresh_dir("history_cmd_errors");
  const Outcome missing = run_renderaudit("history --db " + dir + "/none.sqlite");
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.output.find("renderaudit: no history database at " + dir +
                                "/none.sqlite (`renderaudit audit` creates it; --db FILE "
                                "chooses another)"),
            std::string::npos)
      << missing.output;
  EXPECT_FALSE(fs::exists(dir + "/none.sqlite")) << "reading never creates the database";

  ra::audit::append_history(dir + "/h.sqlite", audit(1));
  const Outcome metric = run_renderaudit("history --db " + dir + "/h.sqlite --metric pe");
  EXPECT_EQ(metric.exit_code, 2);
  EXPECT_NE(metric.output.find("renderaudit: no metric 'pe' in the last 1 audits of " + dir +
                               "/h.sqlite (present: te_u, te_s)"),
            std::string::npos)
      << metric.output;
}

}  // namespace

namespace {

// Sixteen nights of `audit --speed`: triangles of group D drew at 300 us, from night 9 on at
// 230 us (a faster driver), with 2% of noise; lines of group C stayed at 40 us.
TEST(HistoryCommand, DrawingTimeNamesTheNightItStepped) {
  const std::string dir = fresh_dir("history_speed");
  const std::string db = dir + "/history.sqlite";
  const double noise[16] = {1.01, 0.99, 1.02, 0.98, 1.0,  1.01, 0.99, 1.02,
                            0.98, 1.0,  1.01, 0.99, 1.02, 0.98, 1.0,  1.01};
  for (int k = 1; k <= 16; ++k) {
    ra::audit::AuditSummary s = audit(1);
    s.date_utc = "2026-12-" + std::string(k < 10 ? "0" : "") + std::to_string(k) + "T03:00:00Z";
    const double tri = (k < 9 ? 300.0 : 230.0) * noise[k - 1];
    s.speed = {{"osmesa-llvmpipe", "osmesa-llvmpipe", "triangle", 4, 100, 1, 0.97, 1.03, tri, tri,
                "same"},
               {"osmesa-llvmpipe", "osmesa-llvmpipe", "line", 3, 100, 1, 0.97, 1.03, 40,
                40 * noise[(k + 5) % 16], "same"}};
    ra::audit::append_history(db, s);
  }
  const Outcome o = run_renderaudit("history --db " + db + " --last 16 --out " + dir + "/h");
  ASSERT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(o.output.find("osmesa-llvmpipe triangle D: 16 audits"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("step at #9 (2026-12-09T03:00:00Z)"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("osmesa-llvmpipe line C: 16 audits, 40.4 us last; no change point"),
            std::string::npos)
      << o.output;
  EXPECT_TRUE(fs::exists(dir + "/h/trend_render_us.png"));
  EXPECT_EQ(lines_in(dir + "/h/trend_render_us.csv"), 1u + 2 * 16);  // header, 2 series x 16
}

}  // namespace
