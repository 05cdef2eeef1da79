// `run --slice K/N` on N "machines" and `merge`: the merged run equals a one-machine run in every
// non-timing column, for N = 1, 2, 3, 7 with shards of unequal cost, and analyze accepts it; what
// cannot be merged is refused before anything is written.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "tests/cli_harness.h"
#include "rundir/records_reader.h"
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
      const nlohmann::json m = nlohmann::json::parse(ra::util::read_file(out + "/manifest.json"));
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
    const nlohmann::json m = nlohmann::json::parse(ra::util::read_file(m_dir + "/manifest.json"));
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
  const nlohmann::json slice1 =
      nlohmann::json::parse(ra::util::read_file(dir + "/s2_1/manifest.json"));
  const nlohmann::json both =
      nlohmann::json::parse(ra::util::read_file(dir + "/twice/manifest.json"));
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
  nlohmann::json j = nlohmann::json::parse(ra::util::read_file(driver));
  j["version"] = "4.5 (Compatibility Profile) Mesa 99.0";
  ra::util::write_file_atomic(driver, j.dump());
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

// A faulty platform that crashes on primitive 5 of every view: 4 shards of 10 points per view,
// two views, so slice 1 of 2 and slice 2 of 2 each hold crash records.
const char* kCrashing =
    "seed = 3\nplatforms = [\"faulty\"]\n[views]\norientations = 1\nfov_deg = [30, 150]\n"
    "windows = [64]\nnear = 0.01\nfar = 10.0\n[primitives]\npoints = 40\n[run]\n"
    "shard_size = 10\n[faults]\ncrash = [5]\n";

std::size_t crash_records(const std::string& run_dir) {
  std::size_t n = 0;
  for (const auto& e : fs::directory_iterator(run_dir + "/records"))
    if (ra::rundir::is_records_file_name(e.path().filename().string()))
      ra::rundir::read_records(e.path().string(), [&](const ra::metrics::Record& r) {
        n += r.status == ra::metrics::CaseStatus::kCrash;
      });
  return n;
}

// The manifest describes what the directory holds however it was assembled: slices merged one at a
// time keep the first merge's inputs, shard times and failed primitives, and the exit code of
// merge and of the gather's run follows the crash records the directory holds.
TEST(MergeCommand, SlicesMergedOneAtATimeKeepEveryFactAndTheExitCodeFollowsTheRecords) {
  const std::string dir = fresh_dir("merge_incremental");
  write_text(dir + "/e.toml", kCrashing);
  std::size_t seconds = 0;
  for (int k = 1; k <= 2; ++k) {
    const std::string out = dir + "/s" + std::to_string(k);
    const Outcome o = run_renderaudit("run " + dir + "/e.toml --out " + out +
                                      " --quiet --timeout 20 --slice " + std::to_string(k) + "/2");
    ASSERT_LE(o.exit_code, 1) << o.output;  // 1 where its slice holds a crash record
    seconds += nlohmann::json::parse(ra::util::read_file(out + "/manifest.json"))
                   .at("shard_seconds")
                   .size();
  }
  ASSERT_EQ(crash_records(dir + "/s1") + crash_records(dir + "/s2"), 2u);  // one per view
  EXPECT_EQ(run_renderaudit("merge " + dir + "/s1 --out " + dir + "/m").exit_code, 1);
  const Outcome second = run_renderaudit("merge " + dir + "/s2 --out " + dir + "/m");
  EXPECT_EQ(second.exit_code, 1) << "complete, but the records hold crashes\n" << second.output;
  EXPECT_NE(second.output.find("2 primitives recorded as crash or timeout"), std::string::npos)
      << second.output;
  const nlohmann::json m = nlohmann::json::parse(ra::util::read_file(dir + "/m/manifest.json"));
  EXPECT_EQ(m.at("status"), "complete-with-failed-primitives");
  ASSERT_EQ(m.at("failed_primitives").size(), 2u);
  for (const auto& f : m.at("failed_primitives")) {
    EXPECT_EQ(f.at("index"), 5);
    EXPECT_EQ(f.at("status"), "crash");
    EXPECT_NE(f.at("reason").get<std::string>().find("signal"), std::string::npos) << f;
  }
  ASSERT_EQ(m.at("inputs").size(), 2u);
  EXPECT_EQ(m.at("inputs")[0].at("dir"), dir + "/s1");
  EXPECT_EQ(m.at("inputs")[1].at("dir"), dir + "/s2");
  EXPECT_EQ(m.at("shard_seconds").size(), seconds);
  // the gather's run over the merged directory: nothing left to run, and it still says exit 1
  const Outcome gather = run_renderaudit("run " + dir + "/e.toml --out " + dir + "/m --quiet");
  EXPECT_EQ(gather.exit_code, 1) << gather.output;
  EXPECT_NE(gather.output.find("2 primitives recorded as crash or timeout by earlier"),
            std::string::npos)
      << gather.output;
  // a plain re-run of a finished run with crash records answers as its first run did
  const Outcome first = run_renderaudit("run " + dir + "/e.toml --out " + dir + "/whole --quiet --timeout 20");
  EXPECT_EQ(first.exit_code, 1) << first.output;
  const Outcome again = run_renderaudit("run " + dir + "/e.toml --out " + dir + "/whole --quiet");
  EXPECT_EQ(again.exit_code, 1) << again.output;
  const nlohmann::json w = nlohmann::json::parse(ra::util::read_file(dir + "/whole/manifest.json"));
  EXPECT_EQ(w.at("failed_primitives").size(), 2u) << "listed once, not once per invocation";
  EXPECT_EQ(w.at("status"), "complete-with-failed-primitives");
}

// One rule for a slice's size in `run --slice` and `run --slurm --slices`: every slice holds a
// shard, so more slices than shards is refused before anything is written.
TEST(MergeCommand, MoreSlicesThanShardsIsRefusedAsSlurmRefusesIt) {
  const std::string dir = fresh_dir("merge_empty_slice");
  write_text(dir + "/e.toml", kExperiment);  // 64 shards
  const Outcome o = run_renderaudit("run " + dir + "/e.toml --out " + dir + "/x --slice 100/100");
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_NE(o.output.find("--slice 100/100: the run has only 64 shards (allowed: N from 1 to 64)"),
            std::string::npos)
      << o.output;
  EXPECT_FALSE(fs::exists(dir + "/x"));
  const Outcome p = run_renderaudit("run " + dir + "/e.toml --out " + dir +
                                    "/x --slice 3/20 --platform reference");  // 32 shards
  EXPECT_EQ(p.exit_code, 0) << p.output;
  const Outcome q = run_renderaudit("run " + dir + "/e.toml --out " + dir +
                                    "/y --slice 1/33 --platform reference");
  EXPECT_EQ(q.exit_code, 2) << q.output;
  EXPECT_NE(q.output.find("the run has only 32 shards"), std::string::npos) << q.output;
}

// Slices cut with another shard_size, or without the driver file of a platform whose records they
// hold, are refused with the reason before anything is written.
TEST(MergeCommand, AnotherShardSizeOrAMissingDriverFileIsSaid) {
  const std::string dir = fresh_dir("merge_shard_size");
  write_text(dir + "/e.toml", kExperiment);
  std::string other = kExperiment;
  other.replace(other.find("shard_size = 50"), 15, "shard_size = 40");
  write_text(dir + "/f.toml", other);
  ASSERT_EQ(run_renderaudit("run " + dir + "/e.toml --out " + dir + "/a --quiet --slice 1/2 "
                            "--platform reference").exit_code, 0);
  ASSERT_EQ(run_renderaudit("run " + dir + "/f.toml --out " + dir + "/b --quiet --slice 2/2 "
                            "--platform reference").exit_code, 0);
  const Outcome o = run_renderaudit("merge " + dir + "/a " + dir + "/b --out " + dir + "/m");
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_NE(o.output.find("merge: " + dir + "/b was cut into shards of 40 primitives ([run] "
                          "shard_size), " + dir + "/a into shards of 50"),
            std::string::npos)
      << o.output;
  EXPECT_FALSE(fs::exists(dir + "/m"));
  // a slice without drivers/P.json for a platform it holds records of
  ASSERT_EQ(run_renderaudit("run " + dir + "/e.toml --out " + dir + "/c --quiet --slice 2/2 "
                            "--platform osmesa-llvmpipe").exit_code, 0);
  fs::remove(dir + "/c/drivers/osmesa-llvmpipe.json");
  const Outcome d = run_renderaudit("merge " + dir + "/a " + dir + "/c --out " + dir + "/n");
  EXPECT_EQ(d.exit_code, 2) << d.output;
  EXPECT_NE(d.output.find("merge: " + dir + "/c holds records of osmesa-llvmpipe but no "
                          "drivers/osmesa-llvmpipe.json"),
            std::string::npos)
      << d.output;
  EXPECT_FALSE(fs::exists(dir + "/n"));
  EXPECT_EQ(run_renderaudit("merge " + dir + "/a " + dir + "/c --out " + dir +
                            "/n --allow-driver-mismatch").exit_code, 1);  // merged; shards missing
}

// Slices drawn with other library bytes (another libOSMesa of the same GL strings) are not one
// run: merge refuses them, naming both driver files and both fingerprints, and writes nothing.
TEST(MergeCommand, SlicesDrawnWithOtherLibraryBytesAreRefusedNamingBoth) {
  const std::string dir = fresh_dir("merge_libraries");
  write_text(dir + "/e.toml",
             "seed = 11\nplatforms = [\"osmesa-llvmpipe\"]\n[views]\norientations = 1\n"
             "fov_deg = [30]\nwindows = [64]\nnear = 0.01\nfar = 10.0\n[primitives]\n"
             "points = 100\n[run]\nshard_size = 50\n");
  for (const char* k : {"1", "2"})
    ASSERT_EQ(run_renderaudit("run " + dir + "/e.toml --out " + dir + "/s" + k +
                              " --quiet --slice " + k + "/2").exit_code, 0);
  const std::string second = dir + "/s2/drivers/osmesa-llvmpipe.json";
  nlohmann::json driver = nlohmann::json::parse(ra::util::read_file(second));
  nlohmann::json& library = driver.at("build").at("libraries").at(0);
  const std::string first_fingerprint = library.at("fnv1a64").get<std::string>();
  const std::string other_fingerprint =
      first_fingerprint == "0123456789abcdef" ? "fedcba9876543210" : "0123456789abcdef";
  library["fnv1a64"] = other_fingerprint;
  write_text(second, driver.dump(2) + "\n");
  const std::string file = fs::path(library.at("path").get<std::string>()).filename().string();
  const Outcome o = run_renderaudit("merge " + dir + "/s1 " + dir + "/s2 --out " + dir + "/m");
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_NE(o.output.find("drew with library " + file + " of fingerprint " + other_fingerprint +
                          " (FNV-1a 64 of its bytes) in " + second + " but of fingerprint " +
                          first_fingerprint + " in " + dir + "/s1/drivers/osmesa-llvmpipe.json"),
            std::string::npos)
      << o.output;
  EXPECT_FALSE(fs::exists(dir + "/m"));
}

}  // namespace

