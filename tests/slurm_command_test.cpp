// `run --slurm` without a cluster: the sbatch scripts it writes (dry run), its refusals, and the
// whole path through a stand-in sbatch that runs each array task and then the gather at once, as
// Slurm would; and `renderaudit status` of finished, running and sliced runs. The same run on a
// real Slurm, with a cancelled and a requeued task, is tests/scripts/slurm-test.sh (ctest
// slurm_job_array).
#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <utility>
#include <vector>

#include "runner/run_progress.h"
#include "tests/cli_harness.h"
#include "util/atomic_file.h"
#include "util/dir_lock.h"

namespace fs = std::filesystem;
using namespace ra::testing_cli;

namespace {

const char* kExperiment =
    "seed = 5\nplatforms = [\"reference\", \"osmesa-llvmpipe\"]\n[views]\norientations = 1\n"
    "fov_deg = [30, 150]\nwindows = [64, 200]\nnear = 0.01\nfar = 10.0\n[primitives]\n"
    "points = 200\nlines = 100\ntriangles = 100\n[run]\nshard_size = 50\n";  // 64 shards

// A stand-in for sbatch: prints a job id (101, 102, ...) and runs the script at once, every task
// of an array in turn with SLURM_ARRAY_TASK_ID set; records its arguments in sbatch.calls.
const char* kFakeSbatch = R"(#!/bin/bash
here=$(dirname "$0")
echo "$*" >> "$here/sbatch.calls"
script="${@: -1}"
n=$(cat "$here/sbatch.count" 2>/dev/null || echo 100); n=$((n + 1)); echo $n > "$here/sbatch.count"
tasks=$(sed -n 's/^#SBATCH --array=1-\([0-9]*\).*/\1/p' "$script")
if [ -n "$tasks" ]; then
  for k in $(seq "$tasks"); do
    SLURM_ARRAY_TASK_ID=$k SLURM_JOB_ID=$n bash "$script" >> "$here/tasks.log" 2>&1
  done
else
  SLURM_JOB_ID=$n bash "$script" >> "$here/tasks.log" 2>&1
fi
echo "$n"
)";

std::string fake_sbatch(const std::string& dir, const std::string& text = kFakeSbatch) {
  const std::string path = dir + "/sbatch";
  write_text(path, text);
  fs::permissions(path, fs::perms::owner_all);
  return path;
}

TEST(SlurmCommand, DryRunPrintsAnArrayOfSlicesAndAGatherAndWritesNothing) {
  const std::string dir = fresh_dir("slurm_dry_run");
  write_text(dir + "/e.toml", kExperiment);
  const Outcome o = run_renderaudit(
      "run " + dir + "/e.toml --out " + dir + "/run --slurm --dry-run --allow-node-local "
      "--slices 3 --max-parallel 2 --partition gpu --time-limit 1:30:00 --jobs 4 "
      "--platform reference --timeout 60");
  ASSERT_EQ(o.exit_code, 0) << o.output;
  for (const char* line :
       {"#SBATCH --array=1-3%2\n", "#SBATCH --partition=gpu\n", "#SBATCH --time=1:30:00\n",
        "#SBATCH --cpus-per-task=4\n", "#SBATCH --requeue\n", "--slice $k/3 --jobs 4 --quiet "
        "--platform reference --timeout 60", "/run/slices/$k", " merge \"${slices[@]}\" --out",
        "echo $rc > \"$dir/slurm/gather.exit\"", "--dependency=afterany:ARRAY_JOB"})
    EXPECT_NE(o.output.find(line), std::string::npos) << line << "\n" << o.output;
  EXPECT_FALSE(fs::exists(dir + "/run")) << "a dry run writes nothing";
}

TEST(SlurmCommand, RefusesANodeLocalDirectoryAStudyAndASliceAndSaysWhatSbatchSaid) {
  const std::string dir = fresh_dir("slurm_refusals");
  write_text(dir + "/e.toml", kExperiment);
  Outcome o = run_renderaudit("run " + dir + "/e.toml --out " + dir + "/run --slurm --dry-run");
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_NE(o.output.find("is under /tmp, which every node has its own of"), std::string::npos)
      << o.output;
  o = run_renderaudit("run " + std::string(RA_SOURCE_DIR) +
                      "/experiments/timing_smoke.toml --slurm --dry-run --allow-node-local");
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_NE(o.output.find("a study ([timing], [lod], [regulation]) runs on one machine"),
            std::string::npos)
      << o.output;
  o = run_renderaudit("run " + dir + "/e.toml --out " + dir +
                      "/run --slurm --allow-node-local --slice 1/2");
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_NE(o.output.find("drop --slice"), std::string::npos) << o.output;
  o = run_renderaudit("run " + dir + "/e.toml --out " + dir + "/run --slices 3");
  EXPECT_EQ(o.exit_code, 2) << "--slices needs --slurm";
  o = run_renderaudit("run " + dir + "/e.toml --out " + dir +
                      "/run --slurm --allow-node-local --slices 65 --dry-run");
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_NE(o.output.find("the run has only 64 shards (allowed: 1 to 64)"), std::string::npos)
      << o.output;
  // sbatch refusing the script (a wrong partition, say): its words, exit 2
  const std::string refusing =
      fake_sbatch(dir, "#!/bin/bash\necho 'sbatch: error: invalid partition specified: x' >&2\n"
                       "exit 1\n");
  o = run_command("env RENDERAUDIT_SBATCH=" + refusing + " " + RA_BINARY + " run " + dir +
                  "/e.toml --out " + dir + "/run --slurm --allow-node-local --partition x");
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_NE(o.output.find("sbatch refused"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("invalid partition specified: x"), std::string::npos) << o.output;
}

// Every value that reaches an #SBATCH line is checked before anything is written or submitted:
// sbatch's own tokenizer would split it at white space, consume quotes, cut it at '#', expand '%',
// and a line break would put a command into the script.
TEST(SlurmCommand, ValuesSbatchCannotCarryAreRefusedWithTheReason) {
  const std::string dir = fresh_dir("slurm_injection");
  write_text(dir + "/e.toml", kExperiment);
  const std::string run = "run " + dir + "/e.toml --slurm --dry-run --allow-node-local ";
  const std::vector<std::pair<std::string, std::string>> refused = {
      {"--out '" + dir + "/nl\ntouch " + dir + "/injected #'", "a line break would end the #SBATCH line"},
      {"--out '" + dir + "/my runs'", "sbatch splits an #SBATCH line at white space"},
      {"--out \"" + dir + "/it's\"", "sbatch's #SBATCH parser consumes '"},
      {"--out " + dir + "/run#2", "'#' starts a comment in an #SBATCH line"},
      {"--out " + dir + "/run%j", "sbatch expands '%' patterns"},
      {"--out " + dir + "/run --partition 'gpu\ntouch x'", "not a Slurm partition name"},
      {"--out " + dir + "/run --time-limit '1:00:00 --wrap=id'", "not in sbatch --time syntax"},
      {"--out " + dir + "/run --time-limit 1:00:00:00", "not in sbatch --time syntax"},
  };
  for (const auto& [args, reason] : refused) {
    const Outcome o = run_renderaudit(run + args);
    EXPECT_EQ(o.exit_code, 2) << args << "\n" << o.output;
    EXPECT_NE(o.output.find(reason), std::string::npos) << args << "\n" << o.output;
    EXPECT_EQ(o.output.find("#SBATCH --array"), std::string::npos) << "no script printed";
  }
  EXPECT_FALSE(fs::exists(dir + "/injected"));
  // what sbatch's syntax allows is taken as given
  for (const char* limit : {"90", "90:30", "2:00:00", "1-12", "1-12:30", "1-12:30:15", "UNLIMITED"}) {
    const Outcome o = run_renderaudit(run + "--out " + dir + "/run --time-limit " + limit +
                                      " --partition gpu,debug_2");
    EXPECT_EQ(o.exit_code, 0) << limit << "\n" << o.output;
    EXPECT_NE(o.output.find("#SBATCH --time=" + std::string(limit) + "\n"), std::string::npos)
        << o.output;
    EXPECT_NE(o.output.find("#SBATCH --partition=gpu,debug_2\n"), std::string::npos) << o.output;
  }
  EXPECT_FALSE(fs::exists(dir + "/run")) << "dry runs write nothing";
}

// A manifest edited by hand: every field status acts on is checked, and the message names the
// file and the key (a slice of count 0 crashed it; a numeric status gave a bare JSON error).
TEST(SlurmCommand, StatusNamesTheFileAndKeyOfABadManifestField) {
  const std::string dir = fresh_dir("status_bad_manifest");
  write_text(dir + "/e.toml",
             "seed = 5\nplatforms = [\"reference\"]\n[views]\norientations = 1\nfov_deg = [30]\n"
             "windows = [64]\nnear = 0.01\nfar = 10.0\n[primitives]\npoints = 20\n[run]\n"
             "shard_size = 10\n");
  ASSERT_EQ(run_renderaudit("run " + dir + "/e.toml --out " + dir + "/run --quiet --slice 1/2")
                .exit_code, 0);
  const std::string path = dir + "/run/manifest.json";
  const nlohmann::json good = nlohmann::json::parse(ra::util::read_file(path));
  ASSERT_EQ(run_renderaudit("status " + dir + "/run").exit_code, 0);
  const std::vector<std::pair<std::function<void(nlohmann::json&)>, std::string>> edits = {
      {[](nlohmann::json& m) { m["slice"] = {{"index", 0}, {"count", 0}}; },
       "'slice.count' must be an integer from 1 to 100000 (found 0)"},
      {[](nlohmann::json& m) { m["slice"] = {{"index", 3}, {"count", 2}}; },
       "'slice.index' must be an integer from 1 to 2 (found 3)"},
      {[](nlohmann::json& m) { m["slice"] = {{"index", "1"}, {"count", 2}}; },
       "'slice.index' must be an integer from 1 to 2 (found \"1\")"},
      {[](nlohmann::json& m) { m["status"] = 3; }, "'status' must be a string (found 3)"},
      {[](nlohmann::json& m) { m["experiment"]["name"] = nullptr; },
       "'experiment.name' must be a string (found null)"},
      {[](nlohmann::json& m) { m["platforms_run"] = {"reference", 1}; },
       "'platforms_run' must be an array of platform names"},
      {[](nlohmann::json& m) { m["failures"] = {{{"shard", 7}}}; },
       "'failures[].shard' must be a string (found 7)"},
      {[](nlohmann::json& m) { m = nlohmann::json::array(); },
       "'(the document)' must be a JSON object (found [])"},
  };
  for (const auto& [edit, message] : edits) {
    nlohmann::json m = good;
    edit(m);
    ra::util::write_file_atomic(path, m.dump());
    const Outcome o = run_renderaudit("status " + dir + "/run");
    EXPECT_EQ(o.exit_code, 2) << message << "\n" << o.output;
    EXPECT_NE(o.output.find(path + ": " + message), std::string::npos) << o.output;
    EXPECT_EQ(o.output.find("json.exception"), std::string::npos) << o.output;
  }
}

// A submitted run whose scheduler cannot be asked (squeue missing, the controller down) is not
// called incomplete: status says why it cannot tell and exits 4, and --wait stops with it rather
// than answering as if the run had ended.
TEST(SlurmCommand, StatusSaysWhenTheSchedulerCannotBeAsked) {
  const std::string dir = fresh_dir("status_no_scheduler");
  write_text(dir + "/e.toml", kExperiment);
  const std::string sbatch = fake_sbatch(dir, "#!/bin/bash\n"
      "n=$(cat \"$(dirname \"$0\")/count\" 2>/dev/null || echo 300); n=$((n + 1))\n"
      "echo $n > \"$(dirname \"$0\")/count\"; echo $n\n");  // submits, runs nothing
  const std::string run = dir + "/run";
  ASSERT_EQ(run_command("env RENDERAUDIT_SBATCH=" + sbatch + " " + RA_BINARY + " run " + dir +
                        "/e.toml --out " + run + " --slurm --allow-node-local --slices 2")
                .exit_code, 0);
  auto status = [&](const std::string& squeue, const std::string& extra = "") {
    return run_command("env RENDERAUDIT_SQUEUE=" + squeue + " " + RA_BINARY + " status " + run +
                       extra);
  };
  const std::string down = dir + "/squeue_down";
  write_text(down, "#!/bin/sh\necho 'squeue: error: Unable to contact slurm controller "
                   "(connect failure)' >&2\nexit 1\n");
  fs::permissions(down, fs::perms::owner_all);
  for (const std::string& squeue : {dir + "/no_such_squeue", down}) {
    const Outcome o = status(squeue);
    EXPECT_EQ(o.exit_code, 4) << o.output;
    EXPECT_NE(o.output.find(run + ": experiment experiment: unknown\n"), std::string::npos)
        << o.output;
    EXPECT_NE(o.output.find("the scheduler could not be asked"), std::string::npos) << o.output;
    EXPECT_EQ(status(squeue, " --wait --every 0.1").exit_code, 4);
  }
  EXPECT_NE(status(dir + "/no_such_squeue").output.find("squeue: squeue not found"),
            std::string::npos);
  EXPECT_NE(status(down).output.find("Unable to contact slurm controller"), std::string::npos);
  // the scheduler answering that the tasks wait: queued (exit 3), as before
  const std::string pending = dir + "/squeue_pending";
  write_text(pending, "#!/bin/sh\necho '301_1|PENDING|Resources'\necho '302|PENDING|Dependency'\n");
  fs::permissions(pending, fs::perms::owner_all);
  const Outcome q = status(pending);
  EXPECT_EQ(q.exit_code, 3) << q.output;
  EXPECT_NE(q.output.find(run + ": experiment experiment: queued\n"), std::string::npos)
      << q.output;
}

TEST(SlurmCommand, TheScriptsRunAsSlurmWouldGiveTheOneMachineRun) {
  const std::string dir = fresh_dir("slurm_fake");
  write_text(dir + "/e.toml", kExperiment);
  const Outcome whole = run_renderaudit("run " + dir + "/e.toml --out " + dir + "/whole --quiet");
  ASSERT_EQ(whole.exit_code, 0) << whole.output;
  const std::string sbatch = fake_sbatch(dir);
  const std::string run = dir + "/run";
  const Outcome o =
      run_command("env RENDERAUDIT_SBATCH=" + sbatch + " " + RA_BINARY + " run " + dir +
                  "/e.toml --out " + run + " --slurm --allow-node-local --slices 5 --jobs 1");
  ASSERT_EQ(o.exit_code, 0) << o.output << ra::util::read_file(dir + "/tasks.log");
  EXPECT_NE(o.output.find("submitted 5 slices as Slurm array job 101, gather job 102"),
            std::string::npos)
      << o.output;
  const std::string calls = ra::util::read_file(dir + "/sbatch.calls");
  EXPECT_NE(calls.find("--parsable " + run + "/slurm/array.sbatch\n"), std::string::npos) << calls;
  EXPECT_NE(calls.find("--parsable --dependency=afterany:101 " + run + "/slurm/gather.sbatch\n"),
            std::string::npos)
      << calls;
  const nlohmann::json jobs = nlohmann::json::parse(ra::util::read_file(run + "/slurm/jobs.json"));
  EXPECT_EQ(jobs.at("array_job"), "101");
  EXPECT_EQ(jobs.at("gather_job"), "102");
  EXPECT_EQ(jobs.at("slices"), 5);
  EXPECT_EQ(ra::util::read_file(run + "/slurm/gather.exit"), "0\n");
  for (int k = 1; k <= 5; ++k)
    EXPECT_TRUE(fs::exists(run + "/slices/" + std::to_string(k) + "/manifest.json")) << k;
  EXPECT_TRUE(records_without_timing(run) == records_without_timing(dir + "/whole"));
  const nlohmann::json m = nlohmann::json::parse(ra::util::read_file(run + "/manifest.json"));
  EXPECT_EQ(m.at("status"), "complete");
  EXPECT_EQ(m.at("inputs").size(), 5u);
  EXPECT_EQ(m.at("shard_seconds").size(), 64u) << "every shard's time, from its slice";
  EXPECT_EQ(m.at("invocations").back().at("shards_to_run"), 0) << "the gather found all";
  // squeue has forgotten both jobs (they ended): what it answers then
  const std::string squeue = dir + "/squeue";
  write_text(squeue, "#!/bin/sh\necho 'slurm_load_jobs error: Invalid job id specified' >&2\n"
                     "exit 1\n");
  fs::permissions(squeue, fs::perms::owner_all);
  const Outcome status = run_command("env RENDERAUDIT_SQUEUE=" + squeue + " " +
                                     std::string(RA_BINARY) + " status " + run);
  EXPECT_EQ(status.exit_code, 0) << status.output;
  EXPECT_NE(status.output.find(": experiment e: complete\n"), std::string::npos) << status.output;
  EXPECT_NE(status.output.find("64 planned, 64 done (100%), 0 running, 0 failed, 0 waiting"),
            std::string::npos)
      << status.output;
  EXPECT_NE(status.output.find("gather job 102: ended, exit 0"), std::string::npos)
      << status.output;
}

TEST(SlurmCommand, StatusSaysWhatIsDoneRunningAndLeftWhileAWriterIsAtWork) {
  const std::string dir = fresh_dir("status_running");
  write_text(dir + "/e.toml", std::string("name = \"e\"\n") + kExperiment);
  // slice 1 of 2 finished: a run directory with 32 of the 64 shards
  ASSERT_EQ(run_renderaudit("run " + dir + "/e.toml --out " + dir + "/run --slice 2/2 --quiet")
                .exit_code, 0);
  const Outcome o = run_renderaudit("run " + dir + "/e.toml --out " + dir +
                                    "/run/slices/1 --quiet --slice 1/2");
  ASSERT_EQ(o.exit_code, 0) << o.output;
  for (const auto& e : fs::directory_iterator(dir + "/run/records")) fs::remove(e.path());
  fs::remove(dir + "/run/manifest.json");
  // ... and a writer at work in DIR, with two shards running and 100 s left
  ra::util::DirLock lock(dir + "/run", "run");
  ra::runner::RunProgress p;
  p.host = "node7";
  p.pid = 4242;
  p.shards_to_run = 32;
  p.shards_finished = 3;
  p.running = {"reference.point.v1.0-50", "reference.point.v1.50-100"};
  p.left_s = 100;
  ra::runner::write_run_progress(dir + "/run", p);
  Outcome s = run_renderaudit("status " + dir + "/run");
  EXPECT_EQ(s.exit_code, 3) << s.output;
  EXPECT_NE(s.output.find(": experiment e: running\n"), std::string::npos) << s.output;
  // the two running shards are slice 2's only if slice 1 lacks them
  const bool in_slice_1 = fs::exists(dir + "/run/slices/1/records/reference.point.v1.0-50.csv.zst");
  const int running = (in_slice_1 ? 0 : 1) +
                      (fs::exists(dir + "/run/slices/1/records/reference.point.v1.50-100.csv.zst")
                           ? 0 : 1);
  EXPECT_NE(s.output.find("64 planned, 32 done (50%), " + std::to_string(running) + " running, 0 "
                          "failed, " + std::to_string(32 - running) + " waiting"),
            std::string::npos)
      << s.output;
  EXPECT_NE(s.output.find("3 of 32 shards, left 0:01:40"), std::string::npos) << s.output;
  EXPECT_NE(s.output.find("time left: about 0:01:40"), std::string::npos) << s.output;
  s = run_renderaudit("status " + dir + "/run --json");
  const nlohmann::json j = nlohmann::json::parse(s.output);
  EXPECT_EQ(j.at("state"), "running");
  EXPECT_EQ(j.at("done"), 32);
  EXPECT_EQ(j.at("writers").at(0).at("progress").at("host"), "node7");
  // a run of one platform of two (--platform) is complete with that platform's 32 shards
  ASSERT_EQ(run_renderaudit("run " + dir + "/e.toml --out " + dir + "/one --platform reference "
                            "--quiet").exit_code, 0);
  s = run_renderaudit("status " + dir + "/one");
  EXPECT_EQ(s.exit_code, 0) << s.output;
  EXPECT_NE(s.output.find("32 planned, 32 done (100%), 0 running, 0 failed, 0 waiting"),
            std::string::npos)
      << s.output;
  // ... and `analyze` agrees with `status` (it refused such a run as incomplete); --quiet prints
  // where the files went, not the tables
  const Outcome a = run_renderaudit("analyze " + dir + "/one --quiet");
  EXPECT_EQ(a.exit_code, 0) << a.output;
  EXPECT_NE(a.output.find("Wrote "), std::string::npos) << a.output;
  EXPECT_EQ(a.output.find("### Table"), std::string::npos) << a.output;
  s = run_renderaudit("status " + dir);
  EXPECT_EQ(s.exit_code, 2);
  EXPECT_NE(s.output.find("not a run directory (no experiment.toml)"), std::string::npos);
}

}  // namespace
