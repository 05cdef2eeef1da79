// Creating, reopening and claiming a run's output directory (see the header).
#include "runner/prepare_run_dir.h"

#include <filesystem>
#include <system_error>

#include "rundir/manifest.h"
#include "rundir/run_experiment.h"
#include "rundir/run_folder.h"
#include "runner/shard_recovery.h"
#include "util/atomic_file.h"
#include "util/errors.h"

namespace fs = std::filesystem;

namespace ra::runner {

// Temporary files of writers that are gone (we hold the lock, so none is being written).
void remove_temporaries(const std::string& dir) {
  std::error_code ec;
  for (const std::string& folder :
       {rundir::run_folder::records(dir), rundir::run_folder::drivers(dir), dir})
    for (const auto& e : fs::directory_iterator(folder, ec))
      if (e.path().extension() == ".tmp") fs::remove(e.path(), ec);
}

std::unique_ptr<util::DirLock> prepare_run_dir(const rundir::Experiment& exp, const std::string& dir,
                                               const std::string& who) {
  std::error_code ec;
  // A folder of something else is refused before anything is written into it (a run's folder
  // has experiment.toml, or at least the .lock of a run that is making it).
  if (fs::is_directory(dir, ec) && !fs::is_empty(dir, ec) &&
      !fs::exists(rundir::run_folder::experiment(dir)) &&
      !fs::exists(util::DirLock::lock_path(dir)))
    throw util::UserError(dir +
                          ": exists and is not a run directory (no experiment.toml); choose "
                          "another --out");
  fs::create_directories(dir, ec);
  if (ec) throw util::UserError(dir + ": cannot create the run directory (" + ec.message() + ")");
  auto lock = std::make_unique<util::DirLock>(dir, who);
  const std::string copy = rundir::run_folder::experiment(dir);
  bool empty = true;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path() != fs::path(util::DirLock::lock_path(dir))) empty = false;
  if (fs::exists(copy)) {
    const rundir::Experiment previous = rundir::load_experiment(copy);
    // The copy is the experiment of the records only while the manifest's hash is its own. A
    // manifest that is not JSON is kept aside and replaced by the run (starting_manifest): there is
    // no hash to hold the copy to.
    bool manifest_readable = true;
    try {
      rundir::read_manifest_json(rundir::run_folder::manifest(dir));
    } catch (const util::UserError&) {
      manifest_readable = false;
    }
    if (manifest_readable) rundir::require_unchanged_experiment(previous, dir);
    if (previous.hash != exp.hash)
      throw util::UserError(dir + ": holds a run of a different experiment (hash " + previous.hash +
                            ", this one " + exp.hash +
                            "); choose another --out or remove the directory");
    // [run] is outside the hash, but shard_size names the records files: another size would
    // write every shard again under new names beside the old ones, and count each twice.
    if (previous.shard_size != exp.shard_size)
      throw util::UserError(
          dir + ": holds a run cut into shards of " + std::to_string(previous.shard_size) +
          " primitives ([run] shard_size), " + exp.path + " asks for " +
          std::to_string(exp.shard_size) +
          ": shard_size names the records files, so the two cannot share a "
          "directory; set shard_size = " +
          std::to_string(previous.shard_size) + " again, or choose another --out");
  } else if (!empty) {
    throw util::UserError(dir +
                          ": exists and is not a run directory (no experiment.toml); choose "
                          "another --out");
  }
  for (const std::string& folder :
       {rundir::run_folder::records(dir), rundir::run_folder::drivers(dir),
        rundir::run_folder::logs(dir)}) {
    fs::create_directories(folder, ec);
    if (ec) throw util::UserError(folder + ": cannot create (" + ec.message() + ")");
  }
  fs::remove_all(rundir::run_folder::parts(dir));  // a bisection cut short restarts from scratch
  if (!fs::exists(copy)) util::write_file_atomic(copy, exp.text);
  remove_temporaries(dir);  // what a killed run left behind: their shards are redone
  return lock;
}

}  // namespace ra::runner
