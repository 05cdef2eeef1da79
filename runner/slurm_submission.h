// `renderaudit run EXP --out DIR --slurm`: the run as one Slurm job array, a task per slice
// (`run --slice K/N` into DIR/slices/K), and a gather job that waits for the whole array (afterany:
// it runs even when tasks failed or were cancelled), merges the slices into DIR and then runs
// whatever is still missing there, with the retries and bisection of a local run, before writing
// the manifest. Tasks are submitted with --requeue: a task whose node fails is run again and
// resumes its slice (finished shards are kept). DIR must be on a file system every node sees.
//
// DIR/slurm/ keeps the two sbatch scripts, their logs (slice-K.log, gather.log), jobs.json (the
// job ids, for `renderaudit status`) and gather.exit (the gather's exit status, once it ends).
#pragma once

#include <string>

#include "runner/run_coordinator.h"
#include "util/slurm_sbatch.h"

namespace ra::runner {

struct SlurmSubmission {
  std::string run_dir;                      // absolute
  int slices = 0;
  std::string array_script, gather_script;  // the texts submitted (or printed)
  std::string array_job, gather_job;        // job ids; empty on a dry run
};

// Plans, writes the scripts and submits them (nothing submitted on a dry run). The run options
// give the experiment, DIR, the cores per task (`jobs`, default 2) and what every slice passes on
// (--platform, --timeout, --expect-renderer, --shard-order). Throws ra::util::UserError for a study
// experiment, a node-local DIR, a missing sbatch, or a refused submission (with sbatch's words).
SlurmSubmission submit_slurm_run(const RunOptions& run, const util::SlurmOptions& slurm);

}  // namespace ra::runner
