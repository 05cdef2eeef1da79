// What `plot` does without the analysis it draws from (plot_run.h, app/plot_command.cpp): it
// draws nothing and names the command to run, first or again.
#include "plots/plot_run.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "analysis/records_testing.h"
#include "util/errors.h"

namespace ra::plots {
namespace {

namespace an = ra::analysis;

std::string plan_error(const std::string& dir) {
  try {
    plan_figures(dir);
  } catch (const util::UserError& e) {
    return e.what();
  }
  return "no error";
}

// Why: the figures come from analysis/figures.json and tally.json; a run not analysed, or analysed
// by a version that wrote no tally.json or another version of it, must say what to run.
TEST(PlotRun, WithoutAnAnalysisNamesTheCommandToRun) {
  const an::testing::ScopedTempDir scoped("plot_unanalysed");
  const std::string dir = scoped.path.string();
  an::testing::write_nine_point_run(scoped.path);
  EXPECT_EQ(plan_error(dir),
            dir + "/analysis/figures.json not found: run `renderaudit analyze " + dir + "` first");

  std::filesystem::create_directories(scoped.path / "analysis");
  std::ofstream(scoped.path / "analysis" / "figures.json")
      << R"({"schema": "renderaudit-figures", "schema_version": 1})";
  EXPECT_EQ(plan_error(dir),
            dir + "/analysis/tally.json not found: run `renderaudit analyze " + dir + "` first");
  std::ofstream(scoped.path / "analysis" / "tally.json")
      << R"({"schema": "renderaudit-tally", "schema_version": 0})";
  EXPECT_EQ(plan_error(dir), dir +
                                 "/analysis/tally.json: expected schema renderaudit-tally "
                                 "version 1 (run `renderaudit analyze " +
                                 dir + "` again)");
  std::ofstream(scoped.path / "analysis" / "tally.json")
      << R"({"schema": "renderaudit-tally", "schema_version": 1, "records": 9})";
  EXPECT_NE(plan_error(dir).find(dir + "/analysis/tally.json: unexpected content: "),
            std::string::npos)
      << plan_error(dir);
  EXPECT_FALSE(std::filesystem::exists(scoped.path / "figures"));
}

}  // namespace
}  // namespace ra::plots
