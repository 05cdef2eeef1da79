// A run's own experiment, checked against its manifest (see the header).
#include "rundir/run_experiment.h"

#include <algorithm>

#include "rundir/run_folder.h"
#include "util/errors.h"

namespace ra::rundir {

void require_unchanged_experiment(const Experiment& exp, const std::string& run_dir) {
  require_unchanged_experiment(exp, read_manifest_file_or_empty(run_folder::manifest(run_dir)),
                               run_dir);
}

void require_unchanged_experiment(const Experiment& exp, const RunManifest& m,
                                  const std::string& run_dir) {
  const std::string manifest_path = run_folder::manifest(run_dir);
  if (!m.experiment || m.experiment->hash.empty() || m.experiment->hash == exp.hash) return;
  const std::string toml = run_folder::experiment(run_dir);
  const ManifestExperiment& recorded = *m.experiment;
  const std::string recorded_seed =
      recorded.seed ? ", seed " + std::to_string(*recorded.seed) : std::string();
  throw util::UserError(
      toml + ": changed since the run's records were made: its hash is " + exp.hash + " (seed " +
      std::to_string(exp.seed) + "), " + manifest_path + " records experiment " + recorded.name +
      " with hash " + recorded.hash + recorded_seed +
      ". The records were drawn from the experiment the manifest names, so nothing is read, "
      "drawn or run against the edited copy; put back the experiment the run was made with "
      "(its text is in " + (recorded.file.empty() ? std::string("the original file") : recorded.file) +
      " if that is unchanged), or run the edited experiment into another --out");
}

Experiment load_run_experiment(const std::string& run_dir) {
  Experiment exp = load_experiment(run_folder::experiment(run_dir));
  require_unchanged_experiment(exp, run_dir);
  return exp;
}

std::vector<Shard> planned_shards_of_run(const std::string& run_dir, const Experiment& exp) {
  const RunManifest m = read_manifest_file_or_empty(run_folder::manifest(run_dir));
  std::vector<Shard> plan = plan_shards(exp);
  if (!m.platforms_run || m.platforms_run->empty()) return plan;
  const std::vector<std::string>& run = *m.platforms_run;
  plan.erase(std::remove_if(plan.begin(), plan.end(),
                            [&](const Shard& s) {
                              return std::find(run.begin(), run.end(), s.platform) == run.end();
                            }),
             plan.end());
  return plan;
}

}  // namespace ra::rundir
