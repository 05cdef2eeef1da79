// Tests of runner/run_plan.h on a hand-made experiment whose shards' relative costs are known
// from the measured ranking (rundir/shard_cost.h): softpipe triangles in the 907-pixel view cost
// the most, the reference rasterizer's points the least.
#include "runner/run_plan.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "rundir/shard_file.h"
#include "util/errors.h"

namespace fs = std::filesystem;

namespace ra::runner {
namespace {

rundir::Experiment two_platforms() {
  rundir::Experiment exp;
  geometry::View small, big;
  small.id = 1, small.width = small.height = 128, small.fov_deg = 30;
  big.id = 2, big.width = big.height = 907, big.fov_deg = 150;
  exp.views = {small, big};
  exp.platforms = {"reference", "osmesa-softpipe"};
  exp.counts = {2000, 2000, 2000};
  exp.shard_size = 1000;
  return exp;  // 2 platforms x 2 views x 3 kinds x 2 shards = 24 shards
}

std::vector<std::string> ids(const std::vector<rundir::Shard>& shards) {
  std::vector<std::string> out;
  for (const rundir::Shard& s : shards) out.push_back(s.id());
  return out;
}

TEST(RunPlan, ThePlatformFilterKeepsPlanOrder) {
  const rundir::Experiment exp = two_platforms();
  EXPECT_EQ(shards_of_run(exp, {}, std::nullopt).size(), 24u);
  const std::vector<rundir::Shard> soft = shards_of_run(exp, {"osmesa-softpipe"}, std::nullopt);
  ASSERT_EQ(soft.size(), 12u);
  std::vector<rundir::Shard> expected;
  for (const rundir::Shard& s : rundir::plan_shards(exp))
    if (s.platform == "osmesa-softpipe") expected.push_back(s);
  EXPECT_EQ(ids(soft), ids(expected));
  EXPECT_THROW(require_experiment_platforms(exp, "e.toml", {"egl-zink"}), util::UserError);
  EXPECT_NO_THROW(require_experiment_platforms(exp, "e.toml", {"reference"}));
}

TEST(RunPlan, SlicesPartitionTheRunAndNoSliceIsEmpty) {
  const rundir::Experiment exp = two_platforms();
  std::size_t total = 0;
  for (int k = 1; k <= 5; ++k) total += shards_of_run(exp, {}, rundir::Slice{k, 5}).size();
  EXPECT_EQ(total, 24u);
  try {
    shards_of_run(exp, {"reference"}, rundir::Slice{1, 13});
    ADD_FAILURE() << "13 slices of 12 shards were accepted";
  } catch (const util::UserError& e) {
    EXPECT_EQ(std::string(e.what()),
              "--slice 1/13: the run has only 12 shards (allowed: N from 1 to 12)");
  }
}

class RunQueueTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = (fs::temp_directory_path() / ("ra_run_plan_" + std::to_string(::getpid()))).string();
    fs::remove_all(dir_);
    fs::create_directories(dir_ + "/records");
  }
  void TearDown() override { fs::remove_all(dir_); }
  // A sealed plain-CSV records file of `s` with its size in rows, each naming its primitive
  // (platform, view, ..., kind, index) in order: what check_shard_file accepts.
  void write_whole(const rundir::Shard& s) {
    const std::string path = s.records_path(dir_, rundir::RecordsFormat::kCsv);
    {
      std::ofstream out(path, std::ios::binary);
      out << "header\n";
      for (uint64_t i = s.begin; i < s.end; ++i)
        out << s.platform << "," << s.view << ",0,0,0,0,0,0,0," << geometry::kind_name(s.kind)
            << "," << i << "\n";
    }
    rundir::seal_shard_file(path);
  }
  std::string dir_;
};

TEST_F(RunQueueTest, ResumesKeepsWholeFilesRedoesDamagedOnesAndStartsTheCostliestFirst) {
  const rundir::Experiment exp = two_platforms();
  const std::vector<rundir::Shard> shards = shards_of_run(exp, {}, std::nullopt);
  const rundir::Shard& whole = shards[0];    // reference point v1 0-1000: kept
  const rundir::Shard& damaged = shards[1];  // reference point v1 1000-2000: cut short
  write_whole(whole);
  const std::string damaged_path = damaged.records_path(dir_, rundir::RecordsFormat::kCsv);
  std::ofstream(damaged_path) << "header\n1\n";

  const RunQueue q = queue_shards(shards, exp, dir_, true, 7.5);
  EXPECT_EQ(q.done_before, 1u);
  ASSERT_EQ(q.damaged.size(), 1u);
  EXPECT_EQ(q.damaged[0].shard, damaged.id());
  EXPECT_FALSE(q.damaged[0].reason.empty());
  EXPECT_FALSE(fs::exists(damaged_path));
  EXPECT_TRUE(fs::exists(damaged_path + ".damaged"));  // kept as evidence
  ASSERT_EQ(q.todo.size(), 23u);
  // softpipe triangles in the large view first, the two of them in plan order; reference last
  EXPECT_EQ(q.todo[0].shard.id(), "osmesa-softpipe.triangle.v2.0-1000");
  EXPECT_EQ(q.todo[1].shard.id(), "osmesa-softpipe.triangle.v2.1000-2000");
  EXPECT_EQ(q.todo.back().shard.platform, "reference");
  for (std::size_t i = 0; i < q.todo.size(); ++i) {
    EXPECT_NE(q.todo[i].shard.id(), whole.id());
    EXPECT_EQ(q.todo[i].attempt, 1);
    EXPECT_FALSE(q.todo[i].is_part());
    EXPECT_EQ(q.todo[i].timeout_s, 7.5);
    if (i > 0) {
      EXPECT_GE(expected_cost_of(q.todo[i - 1].shard, exp), expected_cost_of(q.todo[i].shard, exp));
    }
  }
}

TEST_F(RunQueueTest, PlanOrderQueuesWhatIsLeftInPlanOrder) {
  const rundir::Experiment exp = two_platforms();
  const std::vector<rundir::Shard> shards = shards_of_run(exp, {}, std::nullopt);
  write_whole(shards[5]);
  const RunQueue q = queue_shards(shards, exp, dir_, false, 1);
  std::vector<rundir::Shard> expected = shards;
  expected.erase(expected.begin() + 5);
  std::vector<rundir::Shard> got;
  for (const WorkItem& w : q.todo) got.push_back(w.shard);
  EXPECT_EQ(ids(got), ids(expected));
  EXPECT_EQ(q.done_before, 1u);
  EXPECT_TRUE(q.damaged.empty());
}

}  // namespace
}  // namespace ra::runner
