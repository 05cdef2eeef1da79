// End-to-end tests of `renderaudit run`: sharding, resume, failures, bad input.
#include <gtest/gtest.h>

#include <filesystem>

#include "tests/cli_harness.h"

namespace fs = std::filesystem;
using namespace ra::testing_cli;

namespace {

std::string experiment(const std::string& platforms, int points, int shard_size,
                       const std::string& extra = "") {
  return "seed = 42\nplatforms = [" + platforms +
         "]\n[views]\norientations = 2\nfov_deg = [30, 150]\nwindows = [64]\nnear = 0.01\n"
         "far = 10.0\n[primitives]\npoints = " +
         std::to_string(points) + "\n[run]\nshard_size = " + std::to_string(shard_size) + "\n" +
         extra;
}

TEST(RunCommand, OneShardAndManyShardsGiveIdenticalRecords) {
  const std::string dir = fresh_dir("shards");
  write_text(dir + "/one.toml", experiment("\"osmesa-llvmpipe\", \"reference\"", 600, 600));
  write_text(dir + "/many.toml", experiment("\"osmesa-llvmpipe\", \"reference\"", 600, 70));
  const Outcome a = run_renderaudit("run " + dir + "/one.toml --out " + dir + "/one --jobs 1");
  ASSERT_EQ(a.exit_code, 0) << a.output;
  const Outcome b = run_renderaudit("run " + dir + "/many.toml --out " + dir + "/many --jobs 2");
  ASSERT_EQ(b.exit_code, 0) << b.output;
  const auto ra = records_without_timing(dir + "/one"), rb = records_without_timing(dir + "/many");
  EXPECT_EQ(ra.size(), 2u * 4 * 600);  // platforms x views x points
  EXPECT_TRUE(ra == rb);
  EXPECT_TRUE(fs::exists(dir + "/many/manifest.json"));
  EXPECT_TRUE(fs::exists(dir + "/many/summary.md"));
}

TEST(RunCommand, AResumedRunEqualsAnUninterruptedOne) {
  const std::string dir = fresh_dir("resume");
  write_text(dir + "/e.toml", experiment("\"osmesa-llvmpipe\"", 300, 50));
  ASSERT_EQ(run_renderaudit("run " + dir + "/e.toml --out " + dir + "/full").exit_code, 0);
  ASSERT_EQ(run_renderaudit("run " + dir + "/e.toml --out " + dir + "/resumed").exit_code, 0);
  // Simulate a run killed mid-way: some shards missing, one half-written temporary file.
  int removed = 0;
  for (const auto& e : fs::directory_iterator(dir + "/resumed/records"))
    if (removed < 5 && e.path().extension() == ".csv") fs::remove(e.path()), ++removed;
  write_text(dir + "/resumed/records/osmesa-llvmpipe.point.v1.0-50.csv.tmp", "platform,vi");
  const Outcome again = run_renderaudit("run " + dir + "/e.toml --out " + dir + "/resumed");
  ASSERT_EQ(again.exit_code, 0) << again.output;
  EXPECT_NE(again.output.find("(19 finished earlier, 5 run now, 0 failed)"), std::string::npos)
      << again.output;
  EXPECT_TRUE(records_without_timing(dir + "/full") == records_without_timing(dir + "/resumed"));
  for (const auto& e : fs::directory_iterator(dir + "/resumed/records"))
    EXPECT_NE(e.path().extension(), ".tmp") << e.path();
}

TEST(RunCommand, ACrashingOrHangingWorkerIsReportedAndOtherShardsKept) {
  const std::string dir = fresh_dir("crash");
  write_text(dir + "/e.toml", experiment("\"faulty\"", 40, 10, "[faults]\ncrash = [13]\nhang = [27]\n"));
  const Outcome o = run_renderaudit("run " + dir + "/e.toml --out " + dir + "/run --timeout 3");
  EXPECT_EQ(o.exit_code, 1) << o.output;
  // 4 views x 4 shards; in each view the shard holding 13 crashes and the one holding 27 hangs.
  EXPECT_NE(o.output.find("16 shards (0 finished earlier, 8 run now, 8 failed)"), std::string::npos)
      << o.output;
  EXPECT_NE(o.output.find("FAILED faulty.point.v1.10-20: crashed (signal 11"), std::string::npos);
  EXPECT_NE(o.output.find("FAILED faulty.point.v3.20-30: timed out after 3 s"), std::string::npos);
  EXPECT_EQ(records_without_timing(dir + "/run").size(), 4u * 20);
  std::ifstream in(dir + "/run/manifest.json");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("\"status\": \"failed\""), std::string::npos);
  EXPECT_NE(text.find("faulty.point.v4.10-20"), std::string::npos);
}

TEST(RunCommand, BadExperimentWritesNothing) {
  const std::string dir = fresh_dir("bad");
  write_text(dir + "/e.toml", experiment("\"swrast\"", 10, 10));
  const Outcome o = run_renderaudit("run " + dir + "/e.toml --out " + dir + "/run");
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_NE(o.output.find("e.toml:2:14: unknown platform 'swrast' (allowed: "), std::string::npos)
      << o.output;
  EXPECT_FALSE(fs::exists(dir + "/run"));
}

TEST(RunCommand, RefusesARunDirectoryOfAnotherExperiment) {
  const std::string dir = fresh_dir("other");
  write_text(dir + "/a.toml", experiment("\"reference\"", 10, 10));
  write_text(dir + "/b.toml", experiment("\"reference\"", 20, 10));
  ASSERT_EQ(run_renderaudit("run " + dir + "/a.toml --out " + dir + "/run").exit_code, 0);
  const Outcome o = run_renderaudit("run " + dir + "/b.toml --out " + dir + "/run");
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_NE(o.output.find("holds a run of a different experiment"), std::string::npos) << o.output;
}

TEST(RunCommand, HelpNamesTheOptions) {
  const Outcome o = run_renderaudit("run --help");
  EXPECT_EQ(o.exit_code, 0);
  for (const char* opt : {"--out", "--jobs", "--timeout", "experiment file"})
    EXPECT_NE(o.output.find(opt), std::string::npos) << opt;
}

}  // namespace
