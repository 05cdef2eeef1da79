// End-to-end tests of the seal rule (rundir/shard_records.h): every command that reads a run's
// records refuses a damaged records file, naming it, as `analyze` does: a compressed file cut at a
// frame boundary (its first 8,192 rows decode as a valid stream), one cut just before the seal's
// frame (all rows, no seal), two files run together, a flipped byte, appended text, an empty file,
// plain text in a .csv.zst, and <id>.csv beside <id>.csv.zst.
#include <gtest/gtest.h>
#include <zstd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "tests/cli_harness.h"

namespace fs = std::filesystem;
using namespace ra::testing_cli;

namespace {

constexpr const char* kShard = "egl-llvmpipe.point.v1.0-9000.csv.zst";

std::string read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), {});
}

void write_bytes(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
}

// One run of 9,000 points in one shard (two frames of rows and the seal's frame), made once.
const std::string& sealed_run() {
  static const std::string dir = [] {
    const std::string d = fresh_dir("seal_rule");
    write_text(d + "/e.toml",
               "name = \"seal\"\nseed = 3\nplatforms = [\"egl-llvmpipe\"]\n[views]\norientations = 1\n"
               "fov_deg = [30]\nwindows = [64]\nnear = 0.01\nfar = 10.0\n[primitives]\n"
               "points = 9000\n[run]\nshard_size = 9000\n");
    const Outcome r = run_renderaudit("run " + d + "/e.toml --out " + d + "/base --jobs 2");
    EXPECT_EQ(r.exit_code, 0) << r.output;
    return d;
  }();
  return dir;
}

// A copy of the sealed run whose shard file gets `bytes`.
std::string damaged_copy(const std::string& name, const std::string& bytes) {
  const std::string copy = sealed_run() + "/" + name;
  fs::remove_all(copy);
  fs::copy(sealed_run() + "/base", copy, fs::copy_options::recursive);
  write_bytes(copy + "/records/" + kShard, bytes);
  return copy;
}

// The compressed sizes of the zstd frames of `bytes`, in order.
std::vector<std::size_t> frame_sizes(const std::string& bytes) {
  std::vector<std::size_t> sizes;
  for (std::size_t at = 0; at < bytes.size();) {
    const std::size_t n = ZSTD_findFrameCompressedSize(bytes.data() + at, bytes.size() - at);
    if (ZSTD_isError(n)) break;
    sizes.push_back(n);
    at += n;
  }
  return sizes;
}

std::string shard_bytes() { return read_bytes(sealed_run() + "/base/records/" + kShard); }

// Every reader of records refuses `run` (a copy of the sealed run with a damaged shard file) and
// names the file; `analyze` says the run is incomplete.
void expect_every_reader_refuses(const std::string& run, const std::string& why) {
  const std::string file = run + "/records/" + kShard;
  const std::string base = sealed_run() + "/base";
  const Outcome audit = run_renderaudit("audit " + base + " " + run + " --no-history");
  EXPECT_EQ(audit.exit_code, 2) << why << "\n" << audit.output;
  EXPECT_NE(audit.output.find(file + ": damaged"), std::string::npos) << why << audit.output;
  const Outcome reverse = run_renderaudit("audit " + run + " " + base + " --no-history");
  EXPECT_EQ(reverse.exit_code, 2) << why << "\n" << reverse.output;
  const Outcome records = run_renderaudit("records " + run);
  EXPECT_EQ(records.exit_code, 2) << why;
  EXPECT_NE(records.output.find(file + ": damaged"), std::string::npos) << why;
  EXPECT_EQ(records.output.find("\n0,"), std::string::npos) << why << ": rows were printed";
  const Outcome status = run_renderaudit("status " + run);
  EXPECT_EQ(status.exit_code, 1) << why << "\n" << status.output;
  EXPECT_NE(status.output.find("damaged: " + file), std::string::npos) << why << status.output;
  EXPECT_NE(status.output.find(": experiment seal: damaged\n"), std::string::npos) << why
                                                                              << status.output;
  const Outcome stats = run_renderaudit("stats describe " + run + " --column pixels");
  EXPECT_EQ(stats.exit_code, 2) << why << "\n" << stats.output;
  EXPECT_NE(stats.output.find(file + ": damaged"), std::string::npos) << why << stats.output;
  const Outcome reproduce = run_renderaudit("reproduce " + run + " --platform egl-llvmpipe --kind "
                                            "point --view 1 --index 5 --out " + run + "/r.c");
  EXPECT_EQ(reproduce.exit_code, 2) << why << "\n" << reproduce.output;
  EXPECT_FALSE(fs::exists(run + "/r.c")) << why;
  const Outcome merge = run_renderaudit("merge " + run + " --out " + run + "-merged");
  EXPECT_EQ(merge.exit_code, 1) << why << "\n" << merge.output;
  EXPECT_NE(merge.output.find("damaged, not taken: " + file), std::string::npos) << merge.output;
  EXPECT_EQ(run_renderaudit("analyze " + run).exit_code, 3) << why;
}

}  // namespace

TEST(SealRule, TheWholeRunIsReadByEveryReader) {
  const std::string base = sealed_run() + "/base";
  ASSERT_EQ(frame_sizes(shard_bytes()).size(), 3u);  // 8,192 rows, 808 rows, the seal
  const Outcome audit = run_renderaudit("audit " + base + " " + base + " --no-history");
  EXPECT_EQ(audit.exit_code, 0) << audit.output;
  EXPECT_NE(audit.output.find("9,000 primitives recorded"), std::string::npos) << audit.output;  // every row read
  const Outcome status = run_renderaudit("status " + base);
  EXPECT_EQ(status.exit_code, 0) << status.output;
  EXPECT_EQ(run_renderaudit("stats describe " + base + " --column pixels").exit_code, 0);
}

TEST(SealRule, AFileCutAtAFrameBoundaryIsDamagedForEveryReader) {
  const std::string bytes = shard_bytes();
  const std::vector<std::size_t> frames = frame_sizes(bytes);
  ASSERT_EQ(frames.size(), 3u);
  // the first frame alone: 8,192 rows, a valid zstd stream, 808 records gone
  expect_every_reader_refuses(damaged_copy("first-frame", bytes.substr(0, frames[0])),
                              "cut after the first frame");
  // every row, without the seal's frame
  expect_every_reader_refuses(damaged_copy("no-seal", bytes.substr(0, frames[0] + frames[1])),
                              "cut before the seal");
}

TEST(SealRule, TwoFilesRunTogetherAreDamagedForEveryReader) {
  const std::string bytes = shard_bytes();
  expect_every_reader_refuses(damaged_copy("twice", bytes + bytes), "a file appended to itself");
}

TEST(SealRule, StatusNamesEveryKindOfDamageAndQuickSaysItDidNotLook) {
  std::string flipped = shard_bytes();
  flipped[flipped.size() / 2] ^= 0x20;
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"flipped", flipped},
      {"garbage", shard_bytes() + "garbage\n"},
      {"empty", ""},
      {"text", "platform,kind\nreference,point\n"},
      {"cut-inside", shard_bytes().substr(0, 1000)}};
  for (const auto& [name, bytes] : cases) {
    const std::string run = damaged_copy("status-" + name, bytes);
    const Outcome status = run_renderaudit("status " + run);
    EXPECT_EQ(status.exit_code, 1) << name << "\n" << status.output;
    EXPECT_NE(status.output.find(": damaged\n"), std::string::npos) << name << status.output;
    EXPECT_NE(status.output.find("damaged: " + run + "/records/" + kShard), std::string::npos)
        << name << status.output;
    EXPECT_NE(status.output.find("0 done"), std::string::npos) << name << status.output;
    const Outcome quick = run_renderaudit("status " + run + " --quick");
    EXPECT_NE(quick.output.find("seals not checked (--quick)"), std::string::npos) << quick.output;
  }
}

TEST(SealRule, BothFormatsOfOneShardAreRefusedNamingBoth) {
  const std::string run = damaged_copy("both", shard_bytes());
  const std::string zst = run + "/records/" + kShard;
  const std::string csv = zst.substr(0, zst.size() - 4);
  write_bytes(csv, read_records_text(zst));  // the same rows, sealed, in the other format
  const std::string both = csv + " and " + zst + ": both hold records";
  for (const std::string& command :
       {"records " + run, "audit " + sealed_run() + "/base " + run + " --no-history",
        "merge " + run + " --out " + run + "-merged", "stats describe " + run + " --column pixels",
        "reproduce " + run + " --platform egl-llvmpipe --kind point --view 1 --index 5 --out " + run +
            "/r.c",
        "run " + sealed_run() + "/e.toml --out " + run}) {
    const Outcome o = run_renderaudit(command);
    EXPECT_EQ(o.exit_code, 2) << command << "\n" << o.output;
    EXPECT_NE(o.output.find(both), std::string::npos) << command << "\n" << o.output;
  }
  const Outcome status = run_renderaudit("status " + run);
  EXPECT_EQ(status.exit_code, 1) << status.output;
  EXPECT_NE(status.output.find(both), std::string::npos) << status.output;
  const Outcome analyze = run_renderaudit("analyze " + run);
  EXPECT_EQ(analyze.exit_code, 3) << analyze.output;
  EXPECT_NE(analyze.output.find(both), std::string::npos) << analyze.output;
  EXPECT_TRUE(fs::exists(csv) && fs::exists(zst));  // nothing was removed or renamed
}

// A sealed file under another shard's name (cp point.v1.0-100 point.v1.100-200): its seal is whole,
// but its rows are not the shard's, so every reader refuses it as damaged, naming it, and a resumed
// run sets it aside and draws the shard; nothing is counted twice.
TEST(SealRule, AShardFileUnderAnotherShardsNameIsDamagedForEveryReader) {
  const std::string dir = fresh_dir("seal_rule_renamed");
  write_text(dir + "/e.toml",
             "name = \"renamed\"\nseed = 3\nplatforms = [\"reference\"]\n[views]\norientations = 1\n"
             "fov_deg = [30]\nwindows = [64]\nnear = 0.01\nfar = 10.0\n[primitives]\n"
             "points = 300\n[run]\nshard_size = 100\n");
  const std::string base = dir + "/base", run = dir + "/copied";
  ASSERT_EQ(run_renderaudit("run " + dir + "/e.toml --out " + base + " --jobs 2 --quiet").exit_code, 0);
  fs::copy(base, run, fs::copy_options::recursive);
  const std::string file = run + "/records/reference.point.v1.100-200.csv.zst";
  fs::copy_file(run + "/records/reference.point.v1.0-100.csv.zst", file,
                fs::copy_options::overwrite_existing);
  const Outcome status = run_renderaudit("status " + run);
  EXPECT_EQ(status.exit_code, 1) << status.output;
  EXPECT_NE(status.output.find("damaged: " + file), std::string::npos) << status.output;
  EXPECT_NE(status.output.find("another shard's records under this shard's name"),
            std::string::npos) << status.output;
  const Outcome records = run_renderaudit("records " + run);
  EXPECT_EQ(records.exit_code, 2) << records.output;
  EXPECT_NE(records.output.find(file + ": damaged: its first row records point 0 of view 1 on "
                                "reference where shard reference.point.v1.100-200's records "
                                "point 100"),
            std::string::npos) << records.output;
  const Outcome stats = run_renderaudit("stats describe " + run + " --column pixels");
  EXPECT_EQ(stats.exit_code, 2) << stats.output;
  EXPECT_NE(stats.output.find(file + ": damaged"), std::string::npos) << stats.output;
  const Outcome merge = run_renderaudit("merge " + run + " --out " + dir + "/merged");
  EXPECT_EQ(merge.exit_code, 1) << merge.output;
  EXPECT_NE(merge.output.find("damaged, not taken: " + file), std::string::npos) << merge.output;
  EXPECT_EQ(run_renderaudit("analyze " + run).exit_code, 3);
  EXPECT_EQ(run_renderaudit("audit " + base + " " + run + " --no-history").exit_code, 2);
  const Outcome resumed = run_renderaudit("run " + dir + "/e.toml --out " + run + " --jobs 2");
  EXPECT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_NE(resumed.output.find(file + ": not a complete shard file"), std::string::npos)
      << resumed.output;
  EXPECT_TRUE(fs::exists(file + ".damaged"));
  EXPECT_EQ(records_without_timing(run), records_without_timing(base));
}

