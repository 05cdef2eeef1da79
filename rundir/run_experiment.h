// DIR/experiment.toml, the copy of the experiment a run directory holds, is trusted only as the
// experiment its records were drawn from: the hash DIR/manifest.json records (experiment.hash)
// must be the copy's. A copy edited after the run (another seed, another view) would make a resumed
// run mix two experiments under one name, and every reader draw or count against an experiment the
// records were not made with; so every reader and every resume loads the copy through this check
// and stops (util::UserError, exit 2) naming the file when it changed.
#pragma once

#include <string>
#include <vector>

#include "rundir/experiment.h"
#include "rundir/manifest.h"
#include "rundir/shard.h"

namespace ra::rundir {

// DIR/experiment.toml, parsed and checked against DIR/manifest.json. A directory without a
// manifest, or whose manifest records no hash (one cut short by a full disk keeps the name only),
// has nothing to check against and is read as it is. Throws util::UserError naming the file when
// the copy's hash differs from the manifest's, and as load_experiment and read_manifest_file do.
Experiment load_run_experiment(const std::string& run_dir);

// The check alone, for `exp` already read from DIR/experiment.toml: throws util::UserError naming
// the file when the hash DIR/manifest.json records differs from exp.hash.
void require_unchanged_experiment(const Experiment& exp, const std::string& run_dir);
// The same against DIR/manifest.json already read as `manifest` (a reader that reports a manifest
// it cannot read in its own words: analyze, as an incomplete run).
void require_unchanged_experiment(const Experiment& exp, const RunManifest& manifest,
                                  const std::string& run_dir);

// The shards a run directory is meant to hold, in plan order: its experiment's plan, for the
// platforms its manifest says were run (`run --platform`, "platforms_run"; every platform when it
// names none), as `status` counts them. Throws as read_manifest_file does.
std::vector<Shard> planned_shards_of_run(const std::string& run_dir, const Experiment& exp);

}  // namespace ra::rundir
