// `renderaudit run EXPERIMENT.toml [--out DIR] [--jobs N] ...`.
#include <cstdio>
#include <cstdlib>

#include "analysis/run_summary.h"
#include "app/commands.h"
#include "rundir/experiment.h"
#include "runner/run_coordinator.h"
#include "runner/slurm_submission.h"
#include "util/duration_text.h"
#include "util/errors.h"
#include "util/number_text.h"
#include "util/program_name.h"
#include "util/shell_quote.h"

namespace ra::app {

namespace {

// `run --slurm`: the job array and the gather job submitted (or, with --dry-run, printed).
void submit_to_slurm(const runner::RunOptions& opt, util::SlurmOptions slurm_opt) {
  if (rundir::experiment_study_kind(opt.experiment_path) != rundir::StudyKind::kAudit)
    throw util::UserError(opt.experiment_path +
                          ": --slurm runs sharded experiments; a study "
                          "([timing], [lod], [regulation]) runs on one machine");
  if (opt.slice) throw util::UserError("--slurm cuts the run into slices itself; drop --slice");
  const char* sbatch = std::getenv("RENDERAUDIT_SBATCH");  // tests substitute a fake
  if (sbatch && *sbatch) slurm_opt.sbatch = sbatch;
  const runner::SlurmSubmission sub = runner::submit_slurm_run(opt, slurm_opt);
  if (slurm_opt.dry_run) {
    std::printf("# %s/slurm/array.sbatch, submitted with: sbatch --parsable array.sbatch\n%s\n",
                sub.run_dir.c_str(), sub.array_script.c_str());
    std::printf(
        "# %s/slurm/gather.sbatch, submitted with: sbatch --parsable "
        "--dependency=afterany:ARRAY_JOB gather.sbatch\n%s",
        sub.run_dir.c_str(), sub.gather_script.c_str());
    return;
  }
  std::printf(
      "%s: submitted %d slices as Slurm array job %s, gather job %s (afterany)\n"
      "follow it with: %s status %s [--wait]\n",
      sub.run_dir.c_str(), sub.slices, sub.array_job.c_str(), sub.gather_job.c_str(),
      util::program_for_commands().c_str(), util::shell_quote(sub.run_dir).c_str());
}

// Whether an error names the run folder `out` (or a file in it) first, as every refusal of the
// folder does ("DIR: holds a run of a different experiment", "DIR is being written by ...",
// "DIR/experiment.toml: changed since ..."), unlike an error in the experiment file.
bool about_run_folder(const std::string& message, std::string out) {
  while (out.size() > 1 && out.back() == '/') out.pop_back();
  return !out.empty() && message.rfind(out, 0) == 0 && message.size() > out.size() &&
         (message[out.size()] == ':' || message[out.size()] == '/' || message[out.size()] == ' ');
}

// Runs the experiment. Where the folder was named by something other than --out (make's
// OUT=DIR), the caller says how in RENDERAUDIT_OUT_HINT, and an error about the folder ends
// with it.
runner::RunResult run_with_folder_hint(const runner::RunOptions& opt) {
  try {
    return runner::run_experiment(opt);
  } catch (const util::UserError& e) {
    const char* hint = std::getenv("RENDERAUDIT_OUT_HINT");
    if (hint && *hint && about_run_folder(e.what(), opt.out_dir) &&
        !about_run_folder(e.what(), opt.experiment_path))
      throw util::UserError(std::string(e.what()) + "\nrenderaudit: " + hint);
    throw;
  }
}

// The shards of the run (not with --brief, whose one line says them), then each worker that
// failed and each primitive recorded as crash or timeout by this invocation.
void say_shards(const runner::RunResult& r, bool brief) {
  if (!brief)
    std::printf("%s: %zu shards (%zu finished earlier, %zu run now, %zu incomplete)\n",
                r.run_dir.c_str(), r.shards_total, r.shards_done_before, r.shards_run,
                r.shards_total - r.shards_complete);
  for (const auto& f : r.failures)
    std::printf("  worker failed: %s: %s\n", f.shard.c_str(), f.reason.c_str());
  for (const auto& f : r.failed_primitives)
    std::printf("  primitive %llu of %s recorded as %s: %s\n",
                static_cast<unsigned long long>(f.index), f.shard.c_str(),
                metrics::status_name(f.status), f.reason.c_str());
}

}  // namespace

void register_run_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand(
      "run",
      "Render and measure every case of an experiment in parallel shards.\n"
      "Results go to DIR (default outputs/<experiment name>): records/*.csv, manifest.json,\n"
      "summary.md. Re-running the same command over DIR resumes: finished shards are kept.\n"
      "A file with a [timing], [lod] or [regulation] table runs that study instead (into DIR,\n"
      "with its study.json; --jobs, --timeout, --expect-renderer and --slice do not apply to\n"
      "studies).");
  struct Options {
    runner::RunOptions opt;
    bool quiet = false;
    std::string shard_order = "cost";
    std::string slice;
    bool worker_per_shard = false;
    bool brief = false;
    bool slurm = false;
    util::SlurmOptions slurm_opt;
    ConformanceGate gate;
  };
  const auto opts = std::make_shared<Options>();  // alive as long as the callbacks
  cmd->add_option("experiment", opts->opt.experiment_path, "experiment file (TOML)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--out,-o", opts->opt.out_dir, "run directory (default: outputs/<name>)");
  cmd->add_option("--jobs,-j", opts->opt.jobs,
                  "worker processes at once (default: number of cores)")
      ->check(CLI::Range(1, 1024));
  cmd->add_option("--timeout", opts->opt.timeout_s,
                  "seconds before a shard is killed (default: run.shard_timeout_s, 600)")
      ->check(CLI::Range(1.0, 86400.0));
  cmd->add_option("--platform,-p", opts->opt.only_platforms,
                  "run only this platform's shards (repeatable; default: all of the experiment's)");
  cmd->add_option("--expect-renderer", opts->opt.expect_renderer,
                  "stop (exit 2) as soon as a Mesa platform's GL_RENDERER does not match this "
                  "regular expression, e.g. 'llvmpipe'");
  cmd->add_option("--shard-order", opts->shard_order,
                  "which shards start first: cost (the largest expected cost, so that no core "
                  "idles at the end; default) or plan (platform, view, kind)")
      ->check(CLI::IsMember({"cost", "plan"}));
  cmd->add_option("--slice", opts->slice,
                  "run only slice K/N of the shards (disjoint, deterministic, balanced by "
                  "expected cost), for N machines; gather them with `renderaudit merge`");
  cmd->add_flag("--worker-per-shard", opts->worker_per_shard,
                "start a worker process for every shard (default: a worker serves one platform's "
                "shards one after another, paying for its start and GL context once)");
  cmd->add_flag("--quiet,-q", opts->quiet, "no progress line");
  add_conformance_gate_options(cmd, opts->gate);
  cmd->add_flag("--brief", opts->brief,
                "the run in one line (primitives, shards, time) and where its summary went, not its "
                "table (`make` runs with it)");
  auto* on_slurm = cmd->add_flag(
      "--slurm", opts->slurm,
      "submit the run to Slurm instead: a job array of --slices tasks (each `run --slice K/N` "
      "into DIR/slices/K, --jobs cores each, default 2) and a gather job that merges them and "
      "finishes the run. DIR must be on a file system every node sees. Watch it with "
      "`renderaudit status DIR`");
  cmd->add_option("--slices", opts->slurm_opt.slices,
                  "--slurm: array tasks (default: min(shards, 16))")
      ->check(CLI::Range(1, 100000))
      ->needs(on_slurm);
  cmd->add_option("--partition", opts->slurm_opt.partition, "--slurm: the partition")
      ->needs(on_slurm);
  cmd->add_option("--max-parallel", opts->slurm_opt.max_parallel,
                  "--slurm: at most this many tasks at once (sbatch --array=...%M)")
      ->check(CLI::Range(1, 100000))
      ->needs(on_slurm);
  cmd->add_option("--time-limit", opts->slurm_opt.time_limit,
                  "--slurm: each task's time limit, in sbatch --time syntax (e.g. 2:00:00)")
      ->needs(on_slurm);
  cmd->add_flag("--dry-run", opts->slurm_opt.dry_run,
                "--slurm: print the sbatch scripts, submit nothing")
      ->needs(on_slurm);
  cmd->add_flag("--allow-node-local", opts->slurm_opt.allow_node_local,
                "--slurm: accept a DIR under /tmp or on a tmpfs (a one-node cluster)")
      ->needs(on_slurm);
  cmd->callback([opts, &exit_code] {
    opts->opt.progress = !opts->quiet;
    opts->opt.serve_shards = !opts->worker_per_shard;
    opts->opt.shard_order = opts->shard_order == "plan"
                                ? runner::RunOptions::ShardOrder::kPlan
                                : runner::RunOptions::ShardOrder::kLargestCostFirst;
    if (!opts->slice.empty()) opts->opt.slice = rundir::parse_slice(opts->slice);
    rundir::StudyRunOptions study;
    study.experiment = opts->opt.experiment_path;
    study.out_dir = opts->opt.out_dir;
    study.platforms = opts->opt.only_platforms;
    study.progress = !opts->quiet;
    if (opts->slurm) {
      if (opts->gate.fail_on_violations || !opts->gate.expectations.empty())
        throw util::UserError("--fail-on-violations and --expectations judge a finished run: "
                              "with --slurm, run `renderaudit conformance DIR` after the gather");
      return submit_to_slurm(opts->opt, opts->slurm_opt);
    }
    read_conformance_gate(opts->gate);  // a malformed file stops the run before it starts
    if (opts->gate.fail_on_violations &&
        rundir::experiment_study_kind(opts->opt.experiment_path) != rundir::StudyKind::kAudit)
      throw util::UserError(opts->opt.experiment_path +
                            ": --fail-on-violations judges the primitives of an audit "
                            "experiment; a study has no verdicts");
    if (run_study_if_declared(study, exit_code)) return;
    if (!opts->quiet) {  // what is drawn with, before the progress line
      const rundir::Experiment exp = rundir::load_experiment(opts->opt.experiment_path);
      const std::vector<std::string> platforms =
          opts->opt.only_platforms.empty() ? exp.platforms : opts->opt.only_platforms;
      std::string list;
      for (const std::string& p : platforms) list += (list.empty() ? "" : ", ") + p;
      std::fprintf(stderr, "renderaudit: %s draws with %s\n", opts->opt.experiment_path.c_str(),
                   list.c_str());
    }
    const runner::RunResult r = run_with_folder_hint(opts->opt);
    say_shards(r, opts->brief);
    if (!r.wrong_renderer.empty()) {
      std::printf("stopped: %s\n", r.wrong_renderer.c_str());
      exit_code = kExitUsage;
      return;
    }
    if (r.interrupted) {
      std::printf("interrupted: run the same command again to resume\n");
      exit_code = 130;
      return;
    }
    const std::string summary = analysis::write_run_summary(r.run_dir);
    if (!opts->brief) {
      std::printf("%s", summary.c_str());
      std::printf("summary: %s/summary.md\n", r.run_dir.c_str());
    } else {  // the run in one line: its size, what this invocation did, its time, the file
      const std::size_t incomplete = r.shards_total - r.shards_complete;
      std::printf("run: %s: %s primitives in %zu shards (%zu run now%s%s), %s; summary: "
                  "%s/summary.md\n",
                  r.run_dir.c_str(), util::grouped(r.primitives_total).c_str(), r.shards_total,
                  r.shards_run,
                  r.shards_done_before
                      ? (", " + std::to_string(r.shards_done_before) + " earlier").c_str()
                      : "",
                  incomplete ? (", " + std::to_string(incomplete) + " INCOMPLETE").c_str() : "",
                  util::elapsed_text(r.seconds).c_str(), r.run_dir.c_str());
    }
    if (r.failed_primitives_held.size() > r.failed_primitives.size())
      std::printf(
          "  %zu primitives recorded as crash or timeout by earlier invocations or "
          "merges (manifest.json lists them)\n",
          r.failed_primitives_held.size() - r.failed_primitives.size());
    // the exit code says what the directory holds, not what this invocation did
    const bool clean = r.shards_complete == r.shards_total && r.failed_primitives_held.empty();
    exit_code = conformance_gate_exit(opts->gate, r.run_dir, clean ? kExitOk : kExitFindings);
  });
}

}  // namespace ra::app
