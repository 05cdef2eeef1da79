// Submitting a run to Slurm (see the header).
#include "runner/slurm_submission.h"

#include <algorithm>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>

#include "rundir/experiment.h"
#include "rundir/manifest.h"
#include "rundir/run_folder.h"
#include "runner/prepare_run_dir.h"
#include "rundir/shard.h"
#include "util/worker_program.h"
#include "util/atomic_file.h"
#include "util/child_process.h"
#include "util/errors.h"
#include "util/shell_quote.h"

namespace fs = std::filesystem;

namespace ra::runner {
namespace {

// The options every slice and the gather pass on to `run`.
std::string passed_on(const RunOptions& run, int jobs) {
  std::string s = " --jobs " + std::to_string(jobs) + " --quiet";
  for (const auto& p : run.only_platforms) s += " --platform " + util::shell_quote(p);
  if (run.timeout_s > 0) s += " --timeout " + std::to_string(run.timeout_s);
  if (!run.expect_renderer.empty()) s += " --expect-renderer " + util::shell_quote(run.expect_renderer);
  if (run.shard_order == RunOptions::ShardOrder::kPlan) s += " --shard-order plan";
  return s;
}

}  // namespace

SlurmSubmission submit_slurm_run(const RunOptions& run, const util::SlurmOptions& slurm) {
  const rundir::Experiment exp = rundir::load_experiment(run.experiment_path);
  util::validate_slurm_options(slurm);
  SlurmSubmission sub;
  sub.run_dir = fs::weakly_canonical(fs::absolute(run.out_dir.empty() ? "outputs/" + exp.name
                                                                      : run.out_dir))
                    .string();
  const std::string& dir = sub.run_dir;
  util::require_sbatch_value("--out", dir);  // in --output=DIR/slurm/...
  util::require_sbatch_value(run.experiment_path + ": the experiment's name", exp.name);  // --job-name
  if (!slurm.allow_node_local) {
    if (const std::string why = util::node_local_reason(dir); !why.empty())
      throw util::UserError(
          "--slurm: --out " + dir + " " + why +
          "; the tasks on other nodes could not write it nor the gather read it. "
          "Choose a directory on a shared file system (or --allow-node-local on a "
          "one-node cluster)");
  }
  std::vector<rundir::Shard> shards = rundir::plan_shards(exp);
  if (!run.only_platforms.empty())
    shards.erase(std::remove_if(shards.begin(), shards.end(),
                                [&](const rundir::Shard& s) {
                                  return std::find(run.only_platforms.begin(),
                                                   run.only_platforms.end(),
                                                   s.platform) == run.only_platforms.end();
                                }),
                 shards.end());
  if (shards.empty()) throw util::UserError("--slurm: " + run.experiment_path + " plans no shards");
  const int jobs = run.jobs > 0 ? run.jobs : 2;
  sub.slices = slurm.slices > 0 ? slurm.slices : int(std::min<size_t>(shards.size(), 16));
  if (size_t(sub.slices) > shards.size())
    throw util::UserError("--slices " + std::to_string(sub.slices) + ": the run has only " +
                          std::to_string(shards.size()) + " shards (allowed: 1 to " +
                          std::to_string(shards.size()) + ")");

  const std::string program = fs::read_symlink("/proc/self/exe").string();
  // The experiment file as given, where every node can read it (its name stays the run's name);
  // otherwise the run's copy on the shared disk. A file changed after submission is refused by
  // the tasks (another experiment's hash), never mixed in.
  std::string experiment = fs::absolute(run.experiment_path).lexically_normal().string();
  if (!slurm.allow_node_local && !util::node_local_reason(experiment).empty())
    experiment = rundir::run_folder::experiment(dir);
  const std::string n = std::to_string(sub.slices);
  const std::string opts = passed_on(run, jobs);
  const std::string slurm_dir = rundir::run_folder::slurm(dir);

  sub.array_script = util::sbatch_header("renderaudit-" + exp.name, jobs, slurm, slurm_dir + "/slice-%a.log", true);
  sub.array_script += "#SBATCH --array=1-" + n +
                      (slurm.max_parallel > 0 ? "%" + std::to_string(slurm.max_parallel) : "") +
                      "\n";
  sub.array_script +=
      "# One slice of the run (written by `renderaudit run --slurm`). A requeued task resumes it.\n"
      "set -u\n"
      "k=$SLURM_ARRAY_TASK_ID\n"
      "echo \"renderaudit: slice $k/" + n + " on $(hostname) (job ${SLURM_JOB_ID}, restart "
      "${SLURM_RESTART_COUNT:-0})\"\n"
      "exec " + util::shell_quote(program) + " run " + util::shell_quote(experiment) + " --out " + util::shell_quote(dir) +
      "/slices/$k --slice $k/" + n + opts + "\n";

  sub.gather_script =
      util::sbatch_header("renderaudit-" + exp.name + "-gather", jobs, slurm, slurm_dir + "/gather.log", true);
  sub.gather_script +=
      "# Runs after every task of the array has ended, however it ended (afterany): merges the\n"
      "# slices into the run directory, then runs what is still missing there (a cancelled task's\n"
      "# shards, a failed worker's), with a local run's retries and bisection, and writes the\n"
      "# manifest. Its exit status is the run's: 0 complete, 1 failures, 2 refused.\n"
      "set -u\n"
      "dir=" + util::shell_quote(dir) + "\n"
      "slices=()\n"
      "for d in \"$dir\"/slices/*; do [ -f \"$d/" + rundir::run_folder::kExperimentFile +
      "\" ] && slices+=(\"$d\"); done\n"
      "if [ ${#slices[@]} -gt 0 ]; then\n"
      "  " + util::shell_quote(program) + " merge \"${slices[@]}\" --out \"$dir\"\n"
      "  rc=$?\n"
      "  if [ $rc -gt 1 ]; then echo $rc > \"$dir/slurm/gather.exit\"; exit $rc; fi\n"
      "fi\n" +
      util::shell_quote(program) + " run " + util::shell_quote(experiment) + " --out \"$dir\"" + opts + "\n"
      "rc=$?\n"
      "echo $rc > \"$dir/slurm/gather.exit\"\n"
      "exit $rc\n";

  const std::vector<std::string> array_args;
  if (slurm.dry_run) return sub;

  // DIR made (or reopened: the same experiment only) before anything is submitted
  prepare_run_dir(exp, dir, "run --slurm");
  std::error_code ec;
  fs::create_directories(slurm_dir, ec);
  fs::create_directories(rundir::run_folder::slices(dir), ec);
  if (ec)
    throw util::UserError(rundir::run_folder::slices(dir) + ": cannot create (" + ec.message() +
                          ")");
  fs::remove(slurm_dir + "/gather.exit", ec);
  util::write_file_atomic(slurm_dir + "/array.sbatch", sub.array_script);
  util::write_file_atomic(slurm_dir + "/gather.sbatch", sub.gather_script);
  sub.array_job = util::submit_sbatch(slurm, {}, slurm_dir + "/array.sbatch");
  sub.gather_job =
      util::submit_sbatch(slurm, {"--dependency=afterany:" + sub.array_job}, slurm_dir + "/gather.sbatch");
  nlohmann::json jobs_json = {{"array_job", sub.array_job},  {"gather_job", sub.gather_job},
                              {"slices", sub.slices},        {"submitted", rundir::utc_now_iso8601()},
                              {"max_parallel", slurm.max_parallel}, {"cpus_per_task", jobs}};
  util::write_file_atomic(rundir::run_folder::slurm_jobs(dir), jobs_json.dump(1) + "\n");
  return sub;
}

}  // namespace ra::runner
