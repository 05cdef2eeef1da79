// Is a run directory whole (run_completeness.cpp)? A tiny run of the reference platform (4 points
// in shards of 2) written by hand with sealed shard files: whole, a shard missing, damaged, a stray
// file, no plan, a killed or still running writer; and the headline, Markdown and remedy of each.
#include "analysis/run_completeness.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "analysis/records_testing.h"
#include "rundir/experiment.h"
#include "rundir/manifest.h"
#include "rundir/run_folder.h"
#include "rundir/shard.h"
#include "rundir/shard_file.h"
#include "util/dir_lock.h"

namespace ra::analysis {
namespace {

namespace fs = std::filesystem;

// One platform, one view (view 1 of the paper's Table 1), 4 points, 2 per shard: the shards
// reference.point.v1.0-2 and reference.point.v1.2-4.
const char* kExperiment = R"(name = "tiny"
seed = 7
platforms = ["reference"]
[views]
orientations = 1
fov_deg = [30]
windows = [128]
near = 0.01
far = 10.0
[primitives]
points = 4
[run]
shard_size = 2
records_format = "csv"
)";

class RunCompletenessTest : public ::testing::Test {
 protected:
  void SetUp() override {
    run_ = dir_.path.string();
    std::ofstream(rundir::run_folder::experiment(run_)) << kExperiment;
    exp_ = rundir::load_experiment(rundir::run_folder::experiment(run_));
    plan_ = rundir::plan_shards(exp_);
    fs::create_directories(rundir::run_folder::records(run_));
    write_manifest("complete");
    for (const rundir::Shard& s : plan_) write_shard(s);
  }
  void write_manifest(const std::string& status) {
    rundir::RunManifest m;
    m.schema = "renderaudit-manifest";
    m.schema_version = rundir::kManifestSchemaVersion;
    m.status = status;
    rundir::ManifestExperiment e;
    e.name = exp_.name;
    e.hash = exp_.hash;
    e.seed = exp_.seed;
    e.platforms = exp_.platforms;
    m.experiment = e;
    rundir::write_manifest(rundir::run_folder::manifest(run_), m);
  }
  // The shard's sealed records file, one ok point record per primitive, in index order.
  void write_shard(const rundir::Shard& s) {
    rundir::RecordsFileWriter w(s.records_path(run_, rundir::RecordsFormat::kCsv),
                                rundir::RecordsFormat::kCsv);
    for (std::uint64_t i = s.begin; i < s.end; ++i) w.write(testing::point("reference", 1, i, 0.25));
    w.finish();
  }
  std::string shard_path(std::size_t i) const {
    return plan_[i].records_path(run_, rundir::RecordsFormat::kCsv);
  }
  testing::ScopedTempDir dir_{"run_completeness"};
  std::string run_;
  rundir::Experiment exp_;
  std::vector<rundir::Shard> plan_;
};

TEST_F(RunCompletenessTest, AWholeRunCountsEveryShardAndPrimitive) {
  ASSERT_EQ(plan_.size(), 2u);
  EXPECT_EQ(plan_[0].id(), "reference.point.v1.0-2");
  const RunCompleteness c = check_run_completeness(run_);
  EXPECT_TRUE(c.has_plan);
  EXPECT_TRUE(c.complete());
  EXPECT_EQ(c.shards_planned, 2u);
  EXPECT_EQ(c.shards_whole, 2u);
  EXPECT_EQ(c.primitives_planned, 4u);
  EXPECT_EQ(c.primitives_present, 4u);
  EXPECT_TRUE(c.problems.empty());
  EXPECT_EQ(c.one_line(), "complete: 2 of 2 shards, 4 of 4 primitives (manifest: complete)");
  EXPECT_EQ(c.markdown(), "**Run complete: 2 of 2 shards, 4 of 4 primitives (manifest: complete).**\n");
}

// A missing shard is named with its primitive range; the counts leave it out; the remedy is to
// finish the run.
TEST_F(RunCompletenessTest, AMissingShardIsNamedWithItsPrimitives) {
  fs::remove(shard_path(1));
  const RunCompleteness c = check_run_completeness(run_);
  EXPECT_FALSE(c.complete());
  EXPECT_EQ(c.shards_whole, 1u);
  EXPECT_EQ(c.primitives_present, 2u);
  EXPECT_EQ(c.problems, (std::vector<std::string>{
                            "missing shard reference.point.v1.2-4 (primitives 2-3)"}));
  EXPECT_EQ(c.one_line(),
            "INCOMPLETE: 1 of 2 shards, 2 of 4 primitives; 1 problem (manifest: complete)");
  EXPECT_EQ(c.remedy("analyze"),
            "Finish the run (the same `renderaudit run` command), or pass --allow-incomplete to "
            "analyze it as it is.");
}

// A shard file with a row appended after its seal is damaged, not whole; a records file of
// another shard size is a stray that would be counted twice. Markdown lists at most max_listed.
TEST_F(RunCompletenessTest, ADamagedShardAndAStrayFileAreProblems) {
  std::ofstream(shard_path(0), std::ios::app) << "appended,after,the,seal\n";
  std::ofstream(rundir::run_folder::records(run_) + "/reference.point.v1.0-4.csv") << "x\n";
  const RunCompleteness c = check_run_completeness(run_);
  EXPECT_FALSE(c.complete());
  EXPECT_EQ(c.shards_whole, 1u);
  EXPECT_EQ(c.primitives_present, 2u);
  ASSERT_EQ(c.problems.size(), 2u);
  EXPECT_EQ(c.problems[0].rfind("damaged shard reference.point.v1.0-2: ", 0), 0u) << c.problems[0];
  EXPECT_EQ(c.problems[1],
            "records/reference.point.v1.0-4.csv is not a shard of this experiment's plan (another "
            "shard_size?): its records would be counted twice");
  EXPECT_NE(c.one_line().find("; 2 problems"), std::string::npos) << c.one_line();
  const std::string md = c.markdown(1);
  EXPECT_NE(md.find("\n- " + c.problems[0] + "\n"), std::string::npos) << md;
  EXPECT_EQ(md.find(c.problems[1]), std::string::npos) << md;
  EXPECT_NE(md.find("- ... and 1 more\n"), std::string::npos) << md;
}

// Without experiment.toml there is no plan: completeness is unknown, never "complete".
TEST_F(RunCompletenessTest, NoExperimentFileMeansCompletenessIsUnknown) {
  fs::remove(rundir::run_folder::experiment(run_));
  const RunCompleteness c = check_run_completeness(run_);
  EXPECT_FALSE(c.has_plan);
  EXPECT_FALSE(c.complete());
  EXPECT_EQ(c.shards_planned, 0u);
  EXPECT_EQ(c.one_line(), "completeness unknown: no experiment.toml, so no plan to compare with");
}

// "running" with nobody writing: the run was killed, a problem. With a writer holding the
// directory's lock: not complete, and the headline names who writes.
TEST_F(RunCompletenessTest, ARunningManifestIsKilledWithoutAWriterAndIncompleteWithOne) {
  write_manifest("running");
  const RunCompleteness killed = check_run_completeness(run_);
  EXPECT_FALSE(killed.complete());
  EXPECT_TRUE(killed.writer.empty());
  ASSERT_EQ(killed.problems.size(), 1u);
  EXPECT_EQ(killed.problems[0].rfind("the manifest says \"running\" but nobody is writing", 0), 0u);

  const util::DirLock lock(run_, "run");
  const RunCompleteness running = check_run_completeness(run_);
  EXPECT_FALSE(running.writer.empty());
  EXPECT_TRUE(running.problems.empty());
  EXPECT_FALSE(running.complete());
  EXPECT_NE(running.one_line().find("; being written now by " + running.writer), std::string::npos)
      << running.one_line();
}

// The headline and remedy of a slice (one machine's share) and of a run of some platforms,
// from the fields alone.
TEST(RunCompletenessText, ASliceAndAPlatformSubsetSayWhatTheyAre) {
  RunCompleteness slice;
  slice.has_plan = true;
  slice.shards_planned = 6;
  slice.shards_whole = 2;
  slice.primitives_planned = 600;
  slice.primitives_present = 200;
  slice.slice_index = 2;
  slice.slice_count = 3;
  slice.shards_of_other_slices = 4;
  EXPECT_FALSE(slice.complete());
  EXPECT_EQ(slice.one_line(),
            "a slice (2 of 3, one machine's share; 4 shards belong to the other slices): 2 of 6 "
            "shards, 200 of 600 primitives");
  EXPECT_EQ(slice.remedy("report"),
            "Join the 3 slices with `renderaudit merge SLICE_DIR_1 ... SLICE_DIR_3 --out DIR` and "
            "report DIR, or pass --allow-incomplete to report this slice alone.");

  RunCompleteness some;
  some.has_plan = true;
  some.shards_planned = some.shards_whole = 2;
  some.primitives_planned = some.primitives_present = 10;
  some.platforms_run = {"osmesa-llvmpipe", "osmesa-softpipe"};
  some.shards_of_other_platforms = 2;
  EXPECT_TRUE(some.complete());
  EXPECT_EQ(some.one_line(),
            "complete: 2 of 2 shards, 10 of 10 primitives of the platforms run (--platform "
            "osmesa-llvmpipe, osmesa-softpipe; the 2 shards of the others were not asked for)");
}

}  // namespace
}  // namespace ra::analysis
