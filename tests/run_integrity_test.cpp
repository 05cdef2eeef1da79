// End-to-end tests of a run directory's integrity (docs/operations.md, "Crashes and hangs", "Locking",
// "Incomplete runs", "Disk full"): one writer at a time, workers that die with their coordinator,
// damaged shards redone, incomplete runs refused by analyze and report, plans and names checked
// before anything is written, a full disk that leaves a manifest saying "failed".
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/mount.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "tests/cli_harness.h"
#include "util/child_process.h"

namespace fs = std::filesystem;
using namespace ra::testing_cli;

namespace {

std::string experiment(const std::string& name_line, const std::string& platforms,
                       const std::string& primitives, const std::string& extra = "") {
  return name_line + "seed = 7\nplatforms = [" + platforms +
         "]\n[views]\norientations = 1\nfov_deg = [30, 150]\nwindows = [64]\nnear = 0.01\n"
         "far = 10.0\n[primitives]\n" + primitives + "[run]\nshard_size = 100\n" + extra;
}

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), {});
}

// Processes whose command line mentions `needle` (the run directory of a test).
int processes_mentioning(const std::string& needle) {
  int n = 0;
  for (const auto& e : fs::directory_iterator("/proc")) {
    const std::string name = e.path().filename();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    std::string cmd = read_text(e.path().string() + "/cmdline");
    for (char& c : cmd)
      if (c == '\0') c = ' ';
    const std::string stat = read_text(e.path().string() + "/stat");
    const auto close = stat.rfind(')');
    const bool zombie = close != std::string::npos && close + 2 < stat.size() && stat[close + 2] == 'Z';
    const bool worker = cmd.find(" worker ") != std::string::npos ||
                        cmd.find(" serve-shards ") != std::string::npos;  // either kind of worker
    if (!zombie && cmd.find(needle) != std::string::npos && worker)
      ++n;
  }
  return n;
}

// A run whose workers hang (the faulty platform), started in the background.
ra::util::Child start_hanging_run(const std::string& dir) {
  write_text(dir + "/hang.toml",
             experiment("", "\"faulty\"", "points = 200\n",
                        "shard_timeout_s = 60\n[faults]\nhang = [5, 105]\n"));
  ra::util::ChildSpec spec;
  spec.argv = {RA_BINARY, "run", dir + "/hang.toml", "--out", dir + "/run", "--jobs", "2"};
  spec.stdout_path = spec.stderr_path = dir + "/coordinator.log";
  return ra::util::start_child(spec);
}

bool wait_for(const std::function<bool()>& condition, double seconds) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < end) {
    if (condition()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return condition();
}

TEST(RunIntegrity, ASecondRunOnTheSameDirectoryIsRefusedAndNamesTheFirst) {
  const std::string dir = fresh_dir("integrity_lock");
  const ra::util::Child first = start_hanging_run(dir);
  ASSERT_TRUE(wait_for([&] { return processes_mentioning(dir + "/run") >= 2; }, 20));
  const Outcome second = run_renderaudit("run " + dir + "/hang.toml --out " + dir + "/run");
  EXPECT_EQ(second.exit_code, 2) << second.output;
  EXPECT_NE(second.output.find(dir + "/run is being written by process " +
                               std::to_string(first.pid) + " (run) on host"),
            std::string::npos)
      << second.output;
  ::kill(first.pid, SIGINT);
  ra::util::wait_child(first.pid);
}

// A closed terminal (SIGHUP) stops a run as Ctrl-C does: the manifest says "interrupted", no
// worker and no temporary file is left behind.
TEST(RunIntegrity, AHangupLeavesAnInterruptedManifestAndNoTemporaries) {
  const std::string dir = fresh_dir("integrity_hup");
  const ra::util::Child coordinator = start_hanging_run(dir);
  ASSERT_TRUE(wait_for([&] { return processes_mentioning(dir + "/run") >= 2; }, 20));
  ::kill(coordinator.pid, SIGHUP);
  const int status = ra::util::wait_child(coordinator.pid);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 130) << status;
  EXPECT_EQ(processes_mentioning(dir + "/run"), 0);
  const nlohmann::json m = nlohmann::json::parse(read_text(dir + "/run/manifest.json"));
  EXPECT_EQ(m.at("status"), "interrupted");
  std::size_t temporaries = 0;
  for (const auto& e : fs::recursive_directory_iterator(dir + "/run"))
    temporaries += e.path().extension() == ".tmp";
  EXPECT_EQ(temporaries, 0u);
}

TEST(RunIntegrity, WorkersDieWithAKilledCoordinatorAndAnalyzeSaysTheRunWasKilled) {
  const std::string dir = fresh_dir("integrity_kill");
  const ra::util::Child coordinator = start_hanging_run(dir);
  ASSERT_TRUE(wait_for([&] { return processes_mentioning(dir + "/run") >= 2; }, 20));
  ::kill(coordinator.pid, SIGKILL);
  ra::util::wait_child(coordinator.pid);
  EXPECT_TRUE(wait_for([&] { return processes_mentioning(dir + "/run") == 0; }, 3))
      << processes_mentioning(dir + "/run") << " workers outlived their coordinator";
  const Outcome a = run_renderaudit("analyze " + dir + "/run");
  EXPECT_EQ(a.exit_code, 3) << a.output;
  EXPECT_NE(a.output.find("the run was killed"), std::string::npos) << a.output;
}

TEST(RunIntegrity, ADamagedShardIsSetAsideAndRedoneToIdenticalRecords) {
  const std::string dir = fresh_dir("integrity_damage");
  write_text(dir + "/e.toml", experiment("", "\"reference\"", "points = 300\nlines = 100\n"));
  ASSERT_EQ(run_renderaudit("run " + dir + "/e.toml --out " + dir + "/run --jobs 2").exit_code, 0);
  const auto before = records_without_timing(dir + "/run");
  const std::string shard = dir + "/run/records/reference.point.v1.100-200.csv.zst";
  std::string text = read_records_text(shard);
  const auto second_row = text.find('\n', text.find('\n') + 1) + 1;
  text.erase(second_row, text.find('\n', second_row) + 1 - second_row);  // drop one record
  write_records_text(shard, text);  // compressed again: valid zstd, but the seal's hash fails
  // analyze reads the seal while it loads the rows (which parse): the run is refused all the same
  const Outcome a = run_renderaudit("analyze " + dir + "/run");
  EXPECT_EQ(a.exit_code, 3) << a.output;
  EXPECT_NE(a.output.find("damaged shard reference.point.v1.100-200: its trailer does not match "
                          "its contents (99 rows"),
            std::string::npos)
      << a.output;
  const Outcome again = run_renderaudit("run " + dir + "/e.toml --out " + dir + "/run --jobs 2");
  EXPECT_EQ(again.exit_code, 0) << again.output;
  EXPECT_NE(again.output.find("not a complete shard file: its trailer does not match"),
            std::string::npos)
      << again.output;
  EXPECT_TRUE(fs::exists(shard + ".damaged"));
  EXPECT_EQ(records_without_timing(dir + "/run"), before);
  const auto manifest = nlohmann::json::parse(read_text(dir + "/run/manifest.json"));
  ASSERT_EQ(manifest["damaged_shards_redone"].size(), 1u);
  EXPECT_EQ(manifest["damaged_shards_redone"][0]["shard"], "reference.point.v1.100-200");
}

// A compressed shard file cut short (a full disk, a killed copy) is damaged for analyze and redone
// by run, whether the cut falls inside a frame or just before the seal's frame.
TEST(RunIntegrity, ACutCompressedShardIsRefusedThenRedone) {
  const std::string dir = fresh_dir("integrity_cut");
  write_text(dir + "/e.toml", experiment("", "\"reference\"", "points = 200\n"));
  ASSERT_EQ(run_renderaudit("run " + dir + "/e.toml --out " + dir + "/run --jobs 2").exit_code, 0);
  const auto before = records_without_timing(dir + "/run");
  const std::string shard = dir + "/run/records/reference.point.v2.0-100.csv.zst";
  const std::string bytes = read_text(shard);
  write_text(shard, bytes.substr(0, bytes.size() / 2));
  const Outcome a = run_renderaudit("analyze " + dir + "/run");
  EXPECT_EQ(a.exit_code, 3) << a.output;
  EXPECT_NE(a.output.find("damaged shard reference.point.v2.0-100: no trailer (the file was cut "
                          "short)"), std::string::npos) << a.output;
  const Outcome r = run_renderaudit("run " + dir + "/e.toml --out " + dir + "/run --jobs 2");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("not a complete shard file: no trailer"), std::string::npos) << r.output;
  EXPECT_EQ(records_without_timing(dir + "/run"), before);
  EXPECT_EQ(run_renderaudit("analyze " + dir + "/run").exit_code, 0);
}

TEST(RunIntegrity, AnalyzeAndReportRefuseAnIncompleteRunAndSayWhatIsMissing) {
  const std::string dir = fresh_dir("integrity_incomplete");
  write_text(dir + "/e.toml", experiment("", "\"reference\"", "points = 200\n"));
  ASSERT_EQ(run_renderaudit("run " + dir + "/e.toml --out " + dir + "/run --jobs 2").exit_code, 0);
  fs::remove(dir + "/run/records/reference.point.v2.100-200.csv.zst");
  const Outcome a = run_renderaudit("analyze " + dir + "/run");
  EXPECT_EQ(a.exit_code, 3) << a.output;
  EXPECT_NE(a.output.find("INCOMPLETE: 3 of 4 shards, 300 of 400 primitives"), std::string::npos)
      << a.output;
  EXPECT_NE(a.output.find("missing shard reference.point.v2.100-200 (primitives 100-199)"),
            std::string::npos)
      << a.output;
  EXPECT_FALSE(fs::exists(dir + "/run/analysis/README.md"));
  const Outcome r = run_renderaudit("report " + dir + "/run");
  EXPECT_EQ(r.exit_code, 3) << r.output;

  const Outcome allowed = run_renderaudit("analyze " + dir + "/run --allow-incomplete");
  EXPECT_EQ(allowed.exit_code, 0) << allowed.output;
  EXPECT_NE(read_text(dir + "/run/analysis/README.md").find("missing shard reference.point.v2.100-200"),
            std::string::npos);
}

// A records file of schema version 2 as written before shard files were sealed: the seal gone, the
// header of version 2, each row without the last five cells (those versions 3 and 4 added).
std::string as_unsealed_version_2(const std::string& sealed) {
  std::string out;
  std::istringstream lines(sealed);
  bool header = true;
  for (std::string line; std::getline(lines, line); header = false) {
    if (line.rfind("# complete", 0) == 0) continue;
    if (header) {
      out += ra::metrics::records_header_v2() + "\n";
      continue;
    }
    for (int cells = 0; cells < 5; ++cells) line.erase(line.rfind(','));
    out += line + "\n";
  }
  return out;
}

// Records written before shard files were sealed are checked row by row: a primitive outside its
// shard, or one missing, is named.
TEST(RunIntegrity, AnUnsealedRecordOutsideItsShardIsReported) {
  const std::string dir = fresh_dir("integrity_unsealed");
  write_text(dir + "/e.toml", experiment("", "\"reference\"", "points = 200\n"));
  ASSERT_EQ(run_renderaudit("run " + dir + "/e.toml --out " + dir + "/run --jobs 2").exit_code, 0);
  for (const auto& e : fs::directory_iterator(dir + "/run/records")) {  // as an older version wrote
    const std::string path = e.path().string();
    write_text(ra::rundir::records_file_stem(path) + ".csv",
               as_unsealed_version_2(read_records_text(path)));
    fs::remove(path);
  }
  EXPECT_EQ(run_renderaudit("analyze " + dir + "/run").exit_code, 0);  // old runs stay readable
  const std::string shard = dir + "/run/records/reference.point.v1.0-100.csv";
  std::string text = read_text(shard);
  const auto at = text.find(",point,5,");  // primitive 5 now claims to be 150
  ASSERT_NE(at, std::string::npos);
  text.replace(at, 9, ",point,150,");
  write_text(shard, text);
  const Outcome a = run_renderaudit("analyze " + dir + "/run");
  EXPECT_EQ(a.exit_code, 3) << a.output;
  EXPECT_NE(a.output.find("primitive 150 lies outside the shard (primitives 0-99)"), std::string::npos)
      << a.output;
}

// Every records file of schema version 3 or later was written sealed: one without its seal is
// damaged for analyze as it is for run (which redoes it), even when its rows look whole: nothing
// vouches for its values any more.
TEST(RunIntegrity, AnUnsealedFileOfTheCurrentVersionIsDamagedForAnalyzeAsForRun) {
  const std::string dir = fresh_dir("integrity_unsealed_v3");
  write_text(dir + "/e.toml", experiment("", "\"reference\"", "points = 200\n"));
  ASSERT_EQ(run_renderaudit("run " + dir + "/e.toml --out " + dir + "/run --jobs 2").exit_code, 0);
  const std::string shard = dir + "/run/records/reference.point.v1.0-100.csv.zst";
  std::string text = read_records_text(shard);
  text.erase(text.rfind("# complete"));
  write_records_text(shard, text);
  const Outcome a = run_renderaudit("analyze " + dir + "/run");
  EXPECT_EQ(a.exit_code, 3) << a.output;
  EXPECT_NE(a.output.find("damaged shard reference.point.v1.0-100: no trailer"), std::string::npos)
      << a.output;
  EXPECT_NE(a.output.find("records of schema version " +
                         std::to_string(ra::metrics::kRecordsSchemaVersion) +
                         " are always written sealed"),
            std::string::npos)
      << a.output;
  const Outcome r = run_renderaudit("run " + dir + "/e.toml --out " + dir + "/run --jobs 2");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("not a complete shard file: no trailer"), std::string::npos) << r.output;
  EXPECT_EQ(run_renderaudit("analyze " + dir + "/run").exit_code, 0);
}

TEST(RunIntegrity, APlanAboveTheCeilingIsRefusedBeforeAnythingIsWritten) {
  const std::string dir = fresh_dir("integrity_plan");
  std::string toml = experiment("", "\"reference\"", "points = 100000000\n");
  toml.replace(toml.find("orientations = 1"), 16, "orientations = 1000");
  toml.replace(toml.find("shard_size = 100"), 16, "shard_size = 1");
  write_text(dir + "/big.toml", toml);
  const Outcome o = run_renderaudit("run " + dir + "/big.toml --out " + dir + "/run");
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_NE(o.output.find("the plan is too large: 1 platforms x 2000 views x 100000000 primitives "
                          "per view = 200000000000 renders in 200000000000 shards, above "
                          "run.max_renders = 2000000000"),
            std::string::npos)
      << o.output;
  EXPECT_FALSE(fs::exists(dir + "/run"));
}

TEST(RunIntegrity, NamesThatAreNotPlainFileNamesAreRefused) {
  const std::string dir = fresh_dir("integrity_names");
  for (const std::string name : {"..", ".", "a/b", ".hidden", "tab\there"}) {
    write_text(dir + "/e.toml", experiment("name = \"" + name + "\"\n", "\"reference\"", "points = 1\n"));
    ra::util::ChildSpec spec;
    spec.argv = {RA_BINARY, "run", dir + "/e.toml"};
    const ra::util::ProgramResult r = ra::util::run_program(spec);
    EXPECT_EQ(r.exit_code(), 2) << name << ": " << r.output;
    EXPECT_NE(r.output.find(dir + "/e.toml:1:8: 'name' must be a plain file name"), std::string::npos)
        << name << ": " << r.output;
  }
}

// A folder of something else is refused, and nothing (not even the lock file) is written into it.
TEST(RunIntegrity, AForeignFolderIsRefusedAndLeftUntouched) {
  const std::string dir = fresh_dir("integrity_foreign");
  write_text(dir + "/thesis.tex", "mine");
  write_text(dir + "/e.toml", experiment("", "\"reference\"", "points = 1\n"));
  fs::rename(dir + "/e.toml", dir + "/../integrity_foreign_e.toml");
  const Outcome o = run_renderaudit("run " + dir + "/../integrity_foreign_e.toml --out " + dir);
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_NE(o.output.find("exists and is not a run directory"), std::string::npos) << o.output;
  std::size_t entries = 0;
  for (const auto& e : fs::directory_iterator(dir)) ++entries, (void)e;
  EXPECT_EQ(entries, 1u);  // thesis.tex alone
  fs::remove(dir + "/../integrity_foreign_e.toml");
}

TEST(RunIntegrity, AnUnwritableOutputDirectoryIsBadInput) {
  const Outcome o = run_renderaudit("run " RA_SOURCE_DIR "/experiments/quick.toml --out /proc/renderaudit-x");
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_NE(o.output.find("/proc/renderaudit-x: cannot create the run directory"), std::string::npos)
      << o.output;
}

// A 1.5 MiB file system fills during the run (plain CSV records): workers and the coordinator name the file and the
// free space, the manifest says "failed", nothing half-written stays; with more room the same
// command completes, identical to a run elsewhere.
TEST(RunIntegrity, AFullDiskFailsCleanlyAndTheRerunCompletesIdentically) {
  const std::string dir = fresh_dir("integrity_full");
  const std::string mnt = dir + "/small";
  fs::create_directories(mnt);
  if (::mount("tmpfs", mnt.c_str(), "tmpfs", 0, "size=1536k") != 0)
    GTEST_SKIP() << "cannot mount a tmpfs here (not root?): " << std::strerror(errno);
  // Plain CSV: compressed, these records would fit in the 1.5 MiB.
  write_text(dir + "/e.toml", experiment("", "\"reference\"", "points = 3000\nlines = 2000\n",
                                         "records_format = \"csv\"\n"));
  const Outcome full = run_renderaudit("run " + dir + "/e.toml --out " + mnt + "/run --jobs 2");
  EXPECT_EQ(full.exit_code, 2) << full.output;  // an I/O error (its manifest too), not a finding
  EXPECT_NE(full.output.find("No space left on device"), std::string::npos) << full.output;
  EXPECT_NE(full.output.find("bytes free on the file system of " + mnt + "/run"), std::string::npos)
      << full.output;
  const auto manifest = nlohmann::json::parse(read_text(mnt + "/run/manifest.json"));
  EXPECT_EQ(manifest["status"], "failed");
  for (const auto& e : fs::recursive_directory_iterator(mnt + "/run"))
    EXPECT_NE(e.path().extension(), ".tmp") << e.path();

  ASSERT_EQ(::mount("tmpfs", mnt.c_str(), "tmpfs", MS_REMOUNT, "size=64m"), 0);
  const Outcome again = run_renderaudit("run " + dir + "/e.toml --out " + mnt + "/run --jobs 2");
  EXPECT_EQ(again.exit_code, 0) << again.output;
  ASSERT_EQ(run_renderaudit("run " + dir + "/e.toml --out " + dir + "/elsewhere --jobs 2").exit_code, 0);
  EXPECT_EQ(records_without_timing(mnt + "/run"), records_without_timing(dir + "/elsewhere"));
  ::umount(mnt.c_str());
}

// The manifest's hash is the experiment of the records: a copy of experiment.toml edited after the
// run (another seed) is refused by a resumed run and by every reader, naming the file, and nothing
// is drawn or counted against it; put back, the run finishes.
TEST(RunIntegrity, AnEditedExperimentCopyIsRefusedByEveryReaderAndByRun) {
  const std::string dir = fresh_dir("integrity_edited_experiment");
  write_text(dir + "/e.toml", "seed = 2008\nplatforms = [\"reference\"]\n[views]\norientations = 1\n"
                              "fov_deg = [30]\nwindows = [64]\nnear = 0.01\nfar = 10.0\n"
                              "[primitives]\npoints = 400\n[run]\nshard_size = 100\n");
  const std::string run = dir + "/run";
  ASSERT_EQ(run_renderaudit("run " + dir + "/e.toml --out " + run + " --jobs 2 --quiet").exit_code, 0);
  const std::string copy = run + "/experiment.toml";
  const std::string original = read_text(copy);
  std::string edited = original;
  edited.replace(edited.find("seed = 2008"), 11, "seed = 2009");
  write_text(copy, edited);
  const std::string shard = run + "/records/reference.point.v1.300-400.csv.zst";
  ASSERT_TRUE(fs::remove(shard));
  const std::string named = copy + ": changed since the run's records were made";
  const std::vector<std::string> commands = {
      "run " + copy + " --out " + run + " --jobs 2",
      "run " + dir + "/e.toml --out " + run + " --jobs 2",
      "status " + run,
      "records " + run + " --allow-incomplete",
      "stats describe " + run + " --column pixels --allow-incomplete",
      "merge " + run + " --out " + dir + "/merged",
      "analyze " + run + " --allow-incomplete",
      "audit " + run + " " + run + " --no-history",
      "show " + run + " --platform reference --kind point --view 1 --index 15 --out " + dir +
          "/p.png",
      "reproduce " + run + " --platform reference --kind point --view 1 --index 15 --out " + dir +
          "/r.c"};
  for (const std::string& c : commands) {
    SCOPED_TRACE(c);
    const Outcome o = run_renderaudit(c);
    EXPECT_EQ(o.exit_code, 2) << o.output;
    EXPECT_NE(o.output.find(named), std::string::npos) << o.output;
  }
  EXPECT_FALSE(fs::exists(shard));  // nothing was drawn with the edited seed
  EXPECT_FALSE(fs::exists(dir + "/merged/records"));
  EXPECT_FALSE(fs::exists(dir + "/p.png"));
  EXPECT_FALSE(fs::exists(dir + "/r.c"));
  write_text(copy, original);
  const Outcome resumed = run_renderaudit("run " + dir + "/e.toml --out " + run + " --jobs 2");
  EXPECT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_TRUE(fs::exists(shard));
}

// Every damaged file a resumed run sets aside is kept: a second damage to the same shard, or to the
// manifest, is kept as .damaged.2 beside the first copy, which keeps its bytes.
TEST(RunIntegrity, EveryDamagedCopyIsKeptNoneOverwritten) {
  const std::string dir = fresh_dir("integrity_damaged_copies");
  write_text(dir + "/e.toml", experiment("", "\"reference\"", "points = 200\n"));
  const std::string run = dir + "/run";
  const std::string resume = "run " + dir + "/e.toml --out " + run + " --jobs 2";
  ASSERT_EQ(run_renderaudit(resume).exit_code, 0);
  const std::string shard = run + "/records/reference.point.v1.0-100.csv.zst";
  const std::string manifest = run + "/manifest.json";
  for (const std::string damage : {"first damage\n", "second damage\n"}) {
    SCOPED_TRACE(damage);
    write_text(shard, damage);
    write_text(manifest, damage);
    const Outcome o = run_renderaudit(resume);
    EXPECT_EQ(o.exit_code, 0) << o.output;
  }
  EXPECT_EQ(read_text(shard + ".damaged"), "first damage\n");
  EXPECT_EQ(read_text(shard + ".damaged.2"), "second damage\n");
  EXPECT_EQ(read_text(manifest + ".damaged"), "first damage\n");
  EXPECT_EQ(read_text(manifest + ".damaged.2"), "second damage\n");
  EXPECT_EQ(run_renderaudit("status " + run).exit_code, 0);
}

// A full disk under analyze, merge or reproduce is an error (exit 2, the system's words), never the
// findings code 1 that says the command ran and found failures.
TEST(RunIntegrity, AFullDiskIsAnErrorNotAFinding) {
  const std::string dir = fresh_dir("integrity_full_error");
  const std::string mnt = dir + "/small";
  fs::create_directories(mnt);
  if (::mount("tmpfs", mnt.c_str(), "tmpfs", 0, "size=4m") != 0)
    GTEST_SKIP() << "cannot mount a tmpfs here (not root?): " << std::strerror(errno);
  write_text(dir + "/e.toml", experiment("", "\"egl-llvmpipe\"", "points = 200\n"));
  const Outcome made = run_renderaudit("run " + dir + "/e.toml --out " + mnt + "/run --jobs 2");
  ASSERT_EQ(made.exit_code, 0) << made.output;
  {  // fill the file system to its last byte
    std::ofstream fill(mnt + "/fill", std::ios::binary);
    const std::string block(4096, 'x');
    while (fill.write(block.data(), std::streamsize(block.size()))) {
    }
  }
  for (const std::string& c :
       {"analyze " + mnt + "/run", "merge " + mnt + "/run --out " + mnt + "/merged",
        "reproduce " + mnt + "/run --platform egl-llvmpipe --kind point --view 1 --index 5 --out " +
            mnt + "/r.c"}) {
    SCOPED_TRACE(c);
    const Outcome o = run_renderaudit(c);
    EXPECT_EQ(o.exit_code, 2) << o.output;
    EXPECT_NE(o.output.find("No space left on device"), std::string::npos) << o.output;
  }
  ::umount(mnt.c_str());
}

}  // namespace
