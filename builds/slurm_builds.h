// `bisect --slurm`: each round's builds as the tasks of one Slurm job array. Task k runs
// `renderaudit builds build SLOT_k` (builds/commit_builds.h) on whatever node Slurm gives it, so
// every node must see the program, the source's git folder (the object store and the slots in it,
// builds/build_slots.h) and the build cache at the same paths: a network file system. The drawing
// stays with the submitting process (the coordinator), which polls: a task has ended when it wrote
// its exit status beside its log; a task that left squeue without one died with its node, was
// cancelled or ran out of time. A task that failed or died is submitted again once (the same
// array index, alone), then its build counts as failed. A build no longer needed is scancelled.
// The scripts (round-R.sbatch), the tasks' logs and exit files are in the slots' folder, slurm/.
#pragma once

#include <functional>
#include <memory>
#include <string>

#include "builds/commit_builds.h"
#include "util/slurm_sbatch.h"

namespace ra::builds {

// Builds submitted with `slurm`'s options, `jobs` cores per task (sbatch --cpus-per-task and
// ninja -j); scripts and logs under `dir`; each poll's change of state said through `say`.
// Throws UserError for options that cannot go into a script or a `dir` local to one node (unless
// slurm.allow_node_local).
std::unique_ptr<CommitBuilds> slurm_commit_builds(const SourceBuildOptions& o, unsigned jobs,
                                                  const util::SlurmOptions& slurm, const std::string& dir,
                                                  std::function<void(const std::string&)> say,
                                                  double poll_s = 1.0);

}  // namespace ra::builds
