// missing_steps (report.h): the stages the report needs before it can read a run, with the reason.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "analysis/records_testing.h"
#include "analysis/run_analysis.h"
#include "report/report.h"

namespace ra::report {
namespace {

namespace an = ra::analysis;
namespace fs = std::filesystem;

// Why: the report reads its counts from analysis/tally.json; when an analysis has none (written by
// a version before it) or another version of it, the report must run analyze (and plot after it)
// again, as for a missing or stale analysis.
TEST(MissingSteps, AnalysisOfAnotherSchemaVersionIsRunAgain) {
  const an::testing::ScopedTempDir scoped("missing_steps");
  const std::string dir = scoped.path.string();
  an::testing::write_nine_point_run(scoped.path);
  ASSERT_EQ(missing_steps(dir).size(), 2u);  // nothing analysed, nothing drawn
  EXPECT_EQ(missing_steps(dir)[0].reason, dir + "/analysis/figures.json is missing");

  an::AnalyzeOptions o;
  o.run_dir = dir;
  an::analyze_run(o);
  fs::create_directories(scoped.path / "figures");
  std::ofstream(scoped.path / "figures" / "index.json") << "{}";
  EXPECT_TRUE(missing_steps(dir).empty());

  const fs::path tally = scoped.path / "analysis" / "tally.json";
  fs::remove(tally);
  std::vector<Step> steps = missing_steps(dir);
  ASSERT_EQ(steps.size(), 2u);
  EXPECT_EQ(steps[0].command, "renderaudit analyze " + dir);
  EXPECT_EQ(steps[0].reason, tally.string() + " is missing");
  EXPECT_EQ(steps[1].command, "renderaudit plot " + dir);

  std::ofstream(tally) << R"({"schema": "renderaudit-tally", "schema_version": 2})";
  steps = missing_steps(dir);
  ASSERT_EQ(steps.size(), 2u);
  EXPECT_EQ(steps[0].reason, tally.string() + ": expected schema renderaudit-tally version 1");
  EXPECT_EQ(steps[1].command, "renderaudit plot " + dir);
}

}  // namespace
}  // namespace ra::report
