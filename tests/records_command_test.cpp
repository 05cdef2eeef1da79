// End-to-end tests of `renderaudit records`: one filtered stream of a run's records, from either
// file format, with the cells as recorded, and clear errors for names the run does not have.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "tests/cli_harness.h"
#include "util/atomic_file.h"
#include "util/child_process.h"
#include "util/zstd_stream.h"

namespace fs = std::filesystem;
using namespace ra::testing_cli;

namespace {

std::string experiment(const std::string& extra = "") {
  return "seed = 5\nplatforms = [\"reference\"]\n[views]\norientations = 1\nfov_deg = [30, 150]\n"
         "windows = [32]\nnear = 0.01\nfar = 10.0\n[primitives]\npoints = 40\nlines = 30\n"
         "[run]\nshard_size = 25\n" + extra;
}

// The rows of every records file of the run, without header or seal, keyed by "kind,view,index"
// (read independently of the command: decompressed and split here).
std::map<std::string, std::string> rows_by_key(const std::string& run) {
  std::map<std::string, std::string> out;
  for (const auto& e : fs::directory_iterator(run + "/records")) {
    std::istringstream in(read_records_text(e.path().string()));
    std::string line;
    std::getline(in, line);  // header
    while (std::getline(in, line)) {
      if (line.empty() || line[0] == '#') continue;
      std::vector<std::string> f;
      std::stringstream cells(line);
      for (std::string c; std::getline(cells, c, ',');) f.push_back(c);
      out[f.at(9) + "," + f.at(1) + "," + f.at(10)] = line;  // kind, view, index
    }
  }
  return out;
}

class RecordsCommand : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new std::string(fresh_dir("records_command"));
    write_text(*dir_ + "/e.toml", experiment());
    write_text(*dir_ + "/plain.toml", experiment("records_format = \"csv\"\n"));
    ASSERT_EQ(run_renderaudit("run " + *dir_ + "/e.toml --out " + *dir_ + "/run --jobs 2 --quiet")
                  .exit_code, 0);
    ASSERT_EQ(run_renderaudit("run " + *dir_ + "/plain.toml --out " + *dir_ +
                              "/plain --jobs 2 --quiet").exit_code, 0);
  }
  static std::string* dir_;
};
std::string* RecordsCommand::dir_ = nullptr;

TEST_F(RecordsCommand, TheWholeRunIsOneStreamOfTheRecordedRows) {
  const Outcome o = run_renderaudit("records " + *dir_ + "/run");
  ASSERT_EQ(o.exit_code, 0) << o.output;
  const std::map<std::string, std::string> rows = rows_by_key(*dir_ + "/run");
  ASSERT_EQ(rows.size(), 2u * (40 + 30));
  std::istringstream in(o.output);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, ra::metrics::records_header());
  std::size_t n = 0;
  std::string first_kinds;
  while (std::getline(in, line)) {
    ++n;
    std::vector<std::string> f;
    std::stringstream cells(line);
    for (std::string c; std::getline(cells, c, ',');) f.push_back(c);
    ASSERT_GT(f.size(), 10u) << line;
    EXPECT_EQ(rows.at(f[9] + "," + f[1] + "," + f[10]), line);  // the cells as recorded
    if (n == 1 || n == 41) first_kinds += f[9] + "/" + f[1] + "/" + f[10] + " ";
  }
  EXPECT_EQ(n, rows.size());
  // The plan's order: view 1's points 0..39 come first, then view 1's lines.
  EXPECT_EQ(first_kinds, "point/1/0 line/1/0 ");
  // A plain-CSV run of the same experiment streams the same rows (its own render times aside).
  const std::string columns = "--columns platform,kind,view,index,status,visibility,pixels,pe,"
                              "lse_s,lse_u,te_s,te_u,ref_diff,pixel_hash,conformance";
  const Outcome plain = run_renderaudit("records " + *dir_ + "/plain " + columns);
  const Outcome zst = run_renderaudit("records " + *dir_ + "/run " + columns);
  ASSERT_EQ(plain.exit_code, 0) << plain.output;
  EXPECT_EQ(plain.output, zst.output);
  EXPECT_GT(plain.output.size(), 140u * 20);
}

TEST_F(RecordsCommand, FiltersAndColumnsSelectRowsAndCells) {
  const Outcome o = run_renderaudit("records " + *dir_ + "/run --kind line --view 2 --columns "
                                    "index,kind,view,lse_u");
  ASSERT_EQ(o.exit_code, 0) << o.output;
  const std::map<std::string, std::string> rows = rows_by_key(*dir_ + "/run");
  std::istringstream in(o.output);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "index,kind,view,lse_u");
  std::size_t n = 0;
  while (std::getline(in, line)) {
    std::vector<std::string> f;
    std::stringstream cells(line);
    for (std::string c; std::getline(cells, c, ',');) f.push_back(c);
    if (line.back() == ',') f.push_back("");
    ASSERT_EQ(f.size(), 4u) << line;
    EXPECT_EQ(f[0], std::to_string(n));
    EXPECT_EQ(f[1], "line");
    EXPECT_EQ(f[2], "2");
    std::vector<std::string> full;
    std::stringstream all(rows.at("line,2," + f[0]));
    for (std::string c; std::getline(all, c, ',');) full.push_back(c);
    EXPECT_EQ(f[3], full.at(17));  // lse_u
    ++n;
  }
  EXPECT_EQ(n, 30u);
}

TEST_F(RecordsCommand, TheCompressedStreamDecompressesToThePlainOne) {
  const Outcome plain = run_renderaudit("records " + *dir_ + "/run --kind point");
  const Outcome zst = run_renderaudit("records " + *dir_ + "/run --kind point --format csv.zst");
  ASSERT_EQ(zst.exit_code, 0) << zst.output;
  write_text(*dir_ + "/points.csv.zst", zst.output);
  EXPECT_EQ(ra::util::read_zstd_file(*dir_ + "/points.csv.zst"), plain.output);
}

TEST_F(RecordsCommand, UnknownNamesAreErrorsThatListWhatTheRunHas) {
  const struct {
    std::string args, message;
  } cases[] = {
      {"--platform softpipe", "--platform softpipe: not in run " + *dir_ + "/run (allowed: reference)"},
      {"--kind quad", "--kind quad: not in run " + *dir_ + "/run (allowed: point, line, triangle)"},
      {"--view 9", "--view 9: not in run " + *dir_ + "/run (allowed: 1, 2)"},
      {"--columns index,pee", "--columns pee: no such records column (allowed: platform, view,"},
      {"--format parquet", "--format parquet: unknown (allowed: csv, csv.zst)"},
      {"--columns index,pixels,index", "--columns index: named twice (each column once)"},
  };
  for (const auto& c : cases) {
    const Outcome o = run_renderaudit("records " + *dir_ + "/run " + c.args);
    EXPECT_EQ(o.exit_code, 2) << c.args << ": " << o.output;
    EXPECT_NE(o.output.find(c.message), std::string::npos) << o.output;
  }
}

TEST_F(RecordsCommand, AFullDiskIsSaidNotCrashedOn) {
  ra::util::ChildSpec spec;
  spec.argv = {RA_BINARY, "records", *dir_ + "/run"};
  spec.stdout_path = "/dev/full";
  spec.stderr_path = *dir_ + "/full.err";
  spec.stdin_null = true;
  const ra::util::ProgramResult r = ra::util::run_program(spec);
  EXPECT_EQ(r.exit_code(), 2);
  std::ifstream in(*dir_ + "/full.err");
  const std::string err((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(err.find("cannot write the records to standard output (No space left on device)"),
            std::string::npos)
      << err;
}

// A run with a missing shard: `records` and `stats describe` say it is incomplete and exit 3,
// writing nothing on stdout, unless asked to go on (--allow-incomplete), when they say it too.
TEST_F(RecordsCommand, AnIncompleteRunIsRefusedByRecordsAndStatsUnlessAllowed) {
  const std::string run = *dir_ + "/incomplete";
  fs::remove_all(run);
  fs::copy(*dir_ + "/run", run, fs::copy_options::recursive);
  ASSERT_TRUE(fs::remove(run + "/records/reference.point.v1.25-40.csv.zst"));
  ra::util::ChildSpec spec;
  spec.argv = {RA_BINARY, "records", run};
  spec.stdout_path = *dir_ + "/incomplete.out";
  spec.stderr_path = *dir_ + "/incomplete.err";
  spec.stdin_null = true;
  EXPECT_EQ(ra::util::run_program(spec).exit_code(), 3);
  EXPECT_EQ(fs::file_size(*dir_ + "/incomplete.out"), 0u);
  const std::string said = ra::util::read_file(*dir_ + "/incomplete.err");
  EXPECT_NE(said.find(run + ": incomplete: 1 planned shards of the selection have no records file "
                      "(reference.point.v1.25-40)"),
            std::string::npos) << said;
  EXPECT_NE(said.find("--allow-incomplete"), std::string::npos) << said;
  const Outcome allowed = run_renderaudit("records " + run + " --allow-incomplete");
  EXPECT_EQ(allowed.exit_code, 0) << allowed.output;
  EXPECT_NE(allowed.output.find("incomplete run: 1 planned shards"), std::string::npos);

  const Outcome stats = run_renderaudit("stats describe " + run + " --column pixels");
  EXPECT_EQ(stats.exit_code, 3) << stats.output;
  EXPECT_NE(stats.output.find(run + ": incomplete: 1 of 8 planned shards have no records file "
                              "(reference.point.v1.25-40); 125 of 140 planned primitives are there"),
            std::string::npos) << stats.output;
  EXPECT_EQ(stats.output.find("quartiles"), std::string::npos) << stats.output;
  const Outcome stats_allowed =
      run_renderaudit("stats describe " + run + " --column pixels --allow-incomplete");
  EXPECT_EQ(stats_allowed.exit_code, 0) << stats_allowed.output;
  EXPECT_NE(stats_allowed.output.find("incomplete run: 1 of 8 planned shards"), std::string::npos)
      << stats_allowed.output;
  EXPECT_EQ(run_renderaudit("stats describe " + *dir_ + "/run --column pixels").exit_code, 0);
}

// Runs renderaudit with `args` and its stdout on the write end of a pipe whose read end is
// already closed (a reader that stopped before the first byte: a write can only fail with EPIPE),
// or on /dev/full (every write fails with ENOSPC). Returns the exit status (128 + signal when
// killed) and what it said on stderr.
struct Ended {
  int status = -1;
  std::string err;
};
Ended run_into(const std::vector<std::string>& args, bool dev_full, const std::string& err_path) {
  int fds[2];
  if (::pipe(fds) != 0) return {};
  ::close(fds[0]);  // nobody will read
  const pid_t pid = ra::util::fork_child([&]() -> int {
    const int out = dev_full ? ::open("/dev/full", O_WRONLY) : fds[1];
    ::dup2(out, 1);
    ::signal(SIGPIPE, SIG_DFL);  // as a shell starts it
    const int err = ::open(err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ::dup2(err, 2);
    std::vector<char*> argv{const_cast<char*>(RA_BINARY)};
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    ::execv(RA_BINARY, argv.data());
    return 127;
  });
  ::close(fds[1]);
  const int status = ra::util::wait_child(pid);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status),
          ra::util::read_file(err_path)};
}

// A reader that stops early (`renderaudit records RUN | head`) is normal use: every command that
// writes to stdout ends quietly with its own exit code, as cat does, not with exit 2 and an error
// (nor the 141 of a death by SIGPIPE). A full disk (/dev/full) stays an error, said with its cause.
TEST_F(RecordsCommand, AReaderThatStopsEarlyEndsACommandQuietlyAFullDiskDoesNot) {
  const std::string run = *dir_ + "/run", err = *dir_ + "/pipe.err";
  const std::vector<std::vector<std::string>> commands = {
      {"records", run},
      {"records", run, "--format", "csv.zst"},
      {"stats", "describe", run, "--column", "pixels"},
      {"show", run, "-p", "reference", "-k", "line", "-v", "1", "-i", "3", "-o",
       *dir_ + "/line.png"},
      {"run", *dir_ + "/e.toml", "--out", run, "--jobs", "2", "--quiet"},
      {"--help"},
  };
  for (const auto& args : commands) {
    std::string line;
    for (const std::string& a : args) line += " " + a;
    const Ended gone = run_into(args, false, err);
    EXPECT_EQ(gone.status, 0) << line << ": " << gone.err;
    EXPECT_EQ(gone.err, "") << line;
    if (args.front() == "run" || args.front() == "--help") continue;  // output to a pipe only
    const Ended full = run_into(args, true, err);
    EXPECT_EQ(full.status, 2) << line << ": " << full.err;
    EXPECT_NE(full.err.find("standard output (No space left on device)"), std::string::npos)
        << line << ": " << full.err;
  }
}

// The same through a real pipe into `head -3`, with a stream larger than a pipe holds (64 KiB),
// so that records is still writing when head has gone: three lines, exit 0, nothing on stderr.
TEST_F(RecordsCommand, RecordsIntoHeadEndsQuietly) {
  write_text(*dir_ + "/large.toml",
             "seed = 9\nplatforms = [\"reference\"]\n[views]\norientations = 1\nfov_deg = [30]\n"
             "windows = [32]\nnear = 0.01\nfar = 10.0\n[primitives]\npoints = 4000\n");
  const std::string large = *dir_ + "/large";
  ASSERT_EQ(run_renderaudit("run " + *dir_ + "/large.toml --out " + large + " --jobs 2 --quiet")
                .exit_code, 0);
  ra::util::ChildSpec spec;
  spec.argv = {"/bin/bash", "-c",
               "set -o pipefail; \"$0\" records \"$1\" | head -3 > \"$2\"", RA_BINARY, large,
               *dir_ + "/head.out"};
  spec.stdin_null = true;
  const ra::util::ProgramResult r = ra::util::run_program(spec);
  EXPECT_EQ(r.exit_code(), 0) << r.output;
  EXPECT_EQ(r.output, "");
  const std::string head = ra::util::read_file(*dir_ + "/head.out");
  EXPECT_EQ(std::count(head.begin(), head.end(), '\n'), 3) << head;
  EXPECT_EQ(head.rfind(ra::metrics::records_header(), 0), 0u) << head;
  const Outcome all = run_renderaudit("records " + large);
  EXPECT_GT(all.output.size(), std::size_t{256} << 10);  // far more than a pipe holds
}

}  // namespace

