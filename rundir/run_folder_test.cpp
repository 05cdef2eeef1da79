// Tests of rundir/run_folder.h: the names are the run directory's format on disk, which earlier
// runs, scripts and docs rely on; a name changed here is a change of that format.
#include "rundir/run_folder.h"

#include <gtest/gtest.h>

namespace ra::rundir::run_folder {
namespace {

TEST(RunFolder, NamesTheFilesAndFoldersOfARunDirectory) {
  EXPECT_EQ(experiment("out/q"), "out/q/experiment.toml");
  EXPECT_EQ(manifest("out/q"), "out/q/manifest.json");
  EXPECT_EQ(records("out/q"), "out/q/records");
  EXPECT_EQ(driver("out/q", "osmesa-llvmpipe"), "out/q/drivers/osmesa-llvmpipe.json");
  EXPECT_EQ(shard_log("out/q", "s"), "out/q/logs/s.log");
  EXPECT_EQ(shard_log("out/q", "s", true), "out/q/logs/s.retry.log");
  EXPECT_EQ(parts("out/q"), "out/q/parts");
  EXPECT_EQ(slurm_jobs("out/q"), "out/q/slurm/jobs.json");
  EXPECT_EQ(progress("out/q"), "out/q/progress.json");
  EXPECT_EQ(tally("out/q"), "out/q/analysis/tally.json");
  EXPECT_EQ(figure_data("out/q"), "out/q/analysis/figures.json");
  EXPECT_EQ(figure_index("out/q"), "out/q/figures/index.json");
  EXPECT_EQ(report_pdf("out/q"), "out/q/report/report.pdf");
  EXPECT_EQ(audit_json(audit("out/q")), "out/q/audit/audit.json");
  EXPECT_EQ(bisection(bisect("out/q")), "out/q/bisect/bisect.json");
  EXPECT_EQ(reproduce("out/q"), "out/q/reproduce");
  EXPECT_EQ(reproducer_source("out/q", "osmesa-llvmpipe", "line", 5, 721),
            "out/q/reproduce/osmesa-llvmpipe.line.v5.721.c");
  EXPECT_EQ(study("out/q"), "out/q/study.json");
}

}  // namespace
}  // namespace ra::rundir::run_folder
