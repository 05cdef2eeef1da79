// What every renderaudit submission to Slurm shares (`run --slurm`, runner/slurm_submission.h;
// `bisect --slurm`, builds/slurm_builds.h): the options, the #SBATCH head of a script, the values
// that may stand in it, sbatch itself, and the check that a folder is not local to one node.
#pragma once

#include <string>
#include <vector>

namespace ra::util {

struct SlurmOptions {
  int slices = 0;            // run: array tasks; 0: min(shards, 16)
  int max_parallel = 0;      // at most this many tasks at once (--array=1-N%M); 0: no limit
  std::string partition;     // empty: the cluster's default
  std::string time_limit;    // per task, in sbatch's --time syntax (e.g. "2:00:00"); empty: none
  bool dry_run = false;      // run: print the scripts and the sbatch commands, submit nothing
  bool allow_node_local = false;  // accept folders that look node-local (/tmp, tmpfs)
  std::string sbatch = "sbatch";  // the submitting program (tests may substitute it)
};

// Why `dir` (absolute) is obviously local to one node ("is under /tmp", "is on a tmpfs"), or ""
// when it may be shared.
std::string node_local_reason(const std::string& dir);

// UserError when the partition or the time limit could not stand in an #SBATCH line.
void validate_slurm_options(const SlurmOptions& slurm);
// UserError naming `what` when `value` cannot stand in an #SBATCH line (white space, quotes,
// '#', '%': sbatch's own tokenizer would cut or change it).
void require_sbatch_value(const std::string& what, const std::string& value);

// "#!/bin/bash" and the #SBATCH lines of a job: its name, cores, log (appended to), partition and
// time limit; with `requeue`, Slurm runs a task again by itself when its node fails, else never.
std::string sbatch_header(const std::string& job_name, int jobs, const SlurmOptions& slurm,
                          const std::string& log, bool requeue);

// sbatch --parsable ARGS SCRIPT; the job id. UserError when sbatch cannot run or refuses.
std::string submit_sbatch(const SlurmOptions& slurm, const std::vector<std::string>& args,
                          const std::string& script_path);

}  // namespace ra::util
