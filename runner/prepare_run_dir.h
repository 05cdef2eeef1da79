// The run folder of a run being written (`run`, `merge`, a Slurm submission): created or
// reopened, and claimed by its lock before anything in it is judged, so that two writers started
// together never judge each other's half-made directory. The names of what it holds are
// rundir/run_folder.h's.
#pragma once

#include <memory>
#include <string>

#include "rundir/experiment.h"
#include "util/dir_lock.h"

namespace ra::runner {

// Creates DIR (records/, drivers/, logs/, experiment.toml) or reopens a run of the same experiment,
// holding DIR/.lock for the returned lock's life. `who` names the writer in the lock ("run",
// "merge"). Throws ra::util::UserError for a folder of something else (refused before anything is
// written into it), a run of another experiment, or a directory that cannot be created.
std::unique_ptr<util::DirLock> prepare_run_dir(const rundir::Experiment& exp, const std::string& dir,
                                               const std::string& who = "run");

// Removes the temporary files of writers that are gone (the caller holds the lock).
void remove_temporaries(const std::string& dir);

}  // namespace ra::runner
