// `run --slice K/N` on N "machines" and `merge`: the merged run equals a one-machine run in every
// non-timing column, for N = 1, 2, 3, 7 with shards of unequal cost, and analyze accepts it; what
// cannot be merged is refused before anything is written.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "tests/cli_harness.h"
#include "util/atomic_file.h"

namespace fs = std::filesystem;
using namespace ra::testing_cli;

namespace {

const char* kExperiment =
    "seed = 11\nplatforms = [\"osmesa-llvmpipe\", \"reference\"]\n[views]\norientations = 1\n"
    "fov_deg = [30, 150]\nwindows = [64, 200]\nnear = 0.01\nfar = 10.0\n[primitives]\n"
    "points = 200\nlines = 100\ntriangles = 100\n[run]\nshard_size = 50\n";

std::string merge_line(const std::string& dir, int n) {
  std::string line = "merge";
  for (int k = 1; k <= n; ++k) line += " " + dir + "/s" + std::to_string(n) + "_" + std::to_string(k);
  return line + " --out " + dir + "/merged" + std::to_string(n);
}

TEST(MergeCommand, SlicesMergedEqualAOneMachineRunForOneTwoThreeAndSevenSlices) {
  const std::string dir = fresh_dir("merge_identity");
  write_text(dir + "/e.toml", kExperiment);
  const Outcome whole = run_renderaudit("run " + dir + "/e.toml --out " + dir + "/whole --quiet");
  ASSERT_EQ(whole.exit_code, 0) << whole.output;
  const auto expected = records_without_timing(dir + "/whole");
  ASSERT_EQ(expected.size(), 2u * 4 * 400);  // platforms x views x primitives
  for (int n : {1, 2, 3, 7}) {
    std::size_t shards = 0;
    for (int k = 1; k <= n; ++k) {
      const std::string out = dir + "/s" + std::to_string(n) + "_" + std::to_string(k);
      const Outcome o = run_renderaudit("run " + dir + "/e.toml --out " + out + " --quiet --slice " +
                                        std::to_string(k) + "/" + std::to_string(n));
      ASSERT_EQ(o.exit_code, 0) << o.output;
      const nlohmann::json m = nlohmann::json::parse(ra::read_file(out + "/manifest.json"));
      EXPECT_EQ(m.at("slice").at("index"), k);
      EXPECT_EQ(m.at("slice").at("count"), n);
      EXPECT_EQ(m.at("status"), "complete");  // its slice is whole
      shards += m.at("slice").at("shards").get<std::size_t>();
    }
    EXPECT_EQ(shards, 64u) << n;  // disjoint slices that cover the plan
    const Outcome merged = run_renderaudit(merge_line(dir, n));
    ASSERT_EQ(merged.exit_code, 0) << merged.output;
    EXPECT_NE(merged.output.find("64 of 64 shards (64 copied now, 0 found in several inputs"),
              std::string::npos)
        << merged.output;
    const std::string m_dir = dir + "/merged" + std::to_string(n);
    EXPECT_TRUE(records_without_timing(m_dir) == expected) << n;
    const nlohmann::json m = nlohmann::json::parse(ra::read_file(m_dir + "/manifest.json"));
    EXPECT_EQ(m.at("status"), "complete");
    EXPECT_EQ(m.at("inputs").size(), std::size_t(n));
    EXPECT_TRUE(m.at("inputs")[0].contains("host"));
    const Outcome analyze = run_renderaudit("analyze " + m_dir);
    EXPECT_EQ(analyze.exit_code, 0) << analyze.output;
  }
}

TEST(MergeCommand, AMissingSliceADifferentExperimentAndAnotherDriverAreSaid) {
  const std::string dir = fresh_dir("merge_refusals");
  write_text(dir + "/e.toml", kExperiment);
  for (int k = 1; k <= 2; ++k)
    ASSERT_EQ(run_renderaudit("run " + dir + "/e.toml --out " + dir + "/s2_" + std::to_string(k) +
                              " --quiet --slice " + std::to_string(k) + "/2")
                  .exit_code,
              0);
  // a slice is said to be a slice, and the remedy is merge: not "incomplete ... run it again"
  const Outcome slice = run_renderaudit("analyze " + dir + "/s2_1");
  EXPECT_EQ(slice.exit_code, 3) << slice.output;
  EXPECT_NE(slice.output.find("a slice (1 of 2, one machine's share; "), std::string::npos)
      << slice.output;
  EXPECT_NE(slice.output.find("renderaudit merge SLICE_DIR_1 ... SLICE_DIR_2 --out DIR"),
            std::string::npos)
      << slice.output;
  EXPECT_EQ(slice.output.find("INCOMPLETE"), std::string::npos) << slice.output;
  EXPECT_EQ(slice.output.find("missing shard"), std::string::npos) << slice.output;
  EXPECT_EQ(slice.output.find("same `renderaudit run` command"), std::string::npos) << slice.output;
  // one slice of two: merged, but incomplete (exit 1, the missing shards listed); analyze refuses
  const Outcome half = run_renderaudit("merge " + dir + "/s2_1 --out " + dir + "/half");
  EXPECT_EQ(half.exit_code, 1) << half.output;
  EXPECT_NE(half.output.find("missing: "), std::string::npos) << half.output;
  EXPECT_EQ(run_renderaudit("analyze " + dir + "/half").exit_code, 3);
  // the second slice later completes it (a merge over a merge keeps what is there)
  const Outcome rest = run_renderaudit("merge " + dir + "/s2_2 --out " + dir + "/half");
  EXPECT_EQ(rest.exit_code, 0) << rest.output;
  // a shard in two inputs is taken once
  const Outcome twice =
      run_renderaudit("merge " + dir + "/s2_1 " + dir + "/half --out " + dir + "/twice");
  EXPECT_EQ(twice.exit_code, 0) << twice.output;
  EXPECT_TRUE(records_without_timing(dir + "/twice") == records_without_timing(dir + "/half"));
  const nlohmann::json slice1 = nlohmann::json::parse(ra::read_file(dir + "/s2_1/manifest.json"));
  const nlohmann::json both = nlohmann::json::parse(ra::read_file(dir + "/twice/manifest.json"));
  EXPECT_EQ(both.at("shards").at("in_several_inputs"), slice1.at("slice").at("shards"));
  EXPECT_EQ(both.at("shards").at("complete"), 64);

  // another experiment
  write_text(dir + "/other.toml", std::string(kExperiment).replace(0, 9, "seed = 12"));
  ASSERT_EQ(run_renderaudit("run " + dir + "/other.toml --out " + dir + "/other --quiet --slice 1/2")
                .exit_code,
            0);
  const Outcome other =
      run_renderaudit("merge " + dir + "/s2_1 " + dir + "/other --out " + dir + "/mixed");
  EXPECT_EQ(other.exit_code, 2) << other.output;
  EXPECT_NE(other.output.find("only slices of one experiment can be merged"), std::string::npos)
      << other.output;
  EXPECT_FALSE(fs::exists(dir + "/mixed"));

  // another driver build
  const std::string driver = dir + "/s2_2/drivers/osmesa-llvmpipe.json";
  nlohmann::json j = nlohmann::json::parse(ra::read_file(driver));
  j["version"] = "4.5 (Compatibility Profile) Mesa 99.0";
  ra::write_file_atomic(driver, j.dump());
  const Outcome drift =
      run_renderaudit("merge " + dir + "/s2_1 " + dir + "/s2_2 --out " + dir + "/drift");
  EXPECT_EQ(drift.exit_code, 2) << drift.output;
  EXPECT_NE(drift.output.find("platform osmesa-llvmpipe drew with"), std::string::npos)
      << drift.output;
  EXPECT_FALSE(fs::exists(dir + "/drift"));
  EXPECT_EQ(run_renderaudit("merge " + dir + "/s2_1 " + dir + "/s2_2 --out " + dir +
                            "/drift --allow-driver-mismatch")
                .exit_code,
            0);

  EXPECT_EQ(run_renderaudit("run " + dir + "/e.toml --out " + dir + "/x --slice 3/2").exit_code, 2);
}

}  // namespace
