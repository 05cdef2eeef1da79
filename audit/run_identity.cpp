#include "audit/run_identity.h"

#include <filesystem>
#include <set>
#include <sstream>
#include <nlohmann/json.hpp>

#include "metrics/conformance.h"
#include "rundir/run_folder.h"
#include "util/atomic_file.h"
#include "util/errors.h"
#include "rundir/manifest.h"
#include "rundir/run_experiment.h"
#include "rundir/shard.h"
#include "util/json_file.h"

namespace fs = std::filesystem;

namespace ra::audit {
namespace {

std::string string_or(const nlohmann::json& j, const char* key, const std::string& fallback) {
  return j.is_object() && j.contains(key) && j[key].is_string() ? j[key].get<std::string>()
                                                                : fallback;
}

}  // namespace

RunIdentity load_run_identity(const std::string& dir) {
  RunIdentity run;
  run.dir = dir;
  if (!fs::is_directory(dir)) throw util::UserError(dir + ": no such run directory");
  const std::string manifest_path = rundir::run_folder::manifest(dir);
  if (!fs::exists(manifest_path))
    throw util::UserError(manifest_path + ": missing (not a run directory?)");
  const rundir::RunManifest manifest = rundir::read_manifest_file(manifest_path);
  const std::string toml = rundir::run_folder::experiment(dir);
  if (!fs::exists(toml)) throw util::UserError(toml + ": missing (not a run directory?)");
  run.experiment = rundir::load_run_experiment(dir);

  const rundir::ManifestExperiment exp = manifest.experiment.value_or(rundir::ManifestExperiment{});
  run.name = exp.name.empty() ? run.experiment.name : exp.name;
  run.hash = exp.hash;
  if (run.hash.empty())
    throw util::UserError(manifest_path + ": no experiment hash (not a renderaudit run manifest)");
  if (!exp.seed)
    throw util::UserError(manifest_path + ": no experiment seed (not a renderaudit run manifest)");
  run.seed = *exp.seed;
  run.status = manifest.status.empty() ? "unknown" : manifest.status;
  if (manifest.conformance_rules) {
    const int rules = *manifest.conformance_rules;
    if (rules > metrics::kConformanceRulesVersion)
      throw util::UserError(manifest_path + ": 'conformance_rules' must be an integer from 1 to " +
                            std::to_string(metrics::kConformanceRulesVersion) +
                            ", this renderaudit's (found " + std::to_string(rules) + ")");
    run.conformance_rules = rules;
  }

  // Drivers: the manifest's copy, else what the workers wrote into drivers/ (a run killed before
  // its manifest was finished still has those).
  nlohmann::json drivers = manifest.drivers.is_object() ? manifest.drivers : nlohmann::json::object();
  if (fs::is_directory(rundir::run_folder::drivers(dir)))
    for (const auto& e : fs::directory_iterator(rundir::run_folder::drivers(dir))) {
      const std::string platform = e.path().stem().string();
      if (e.path().extension() != ".json" || drivers.contains(platform)) continue;
      try {
        drivers[platform] =
            util::parse_json_document(util::read_file(e.path().string()), e.path().string());
      } catch (const std::exception&) {
      }
    }
  for (const auto& [platform, d] : drivers.items())
    run.drivers[platform] = {platform, string_or(d, "renderer", "unknown"),
                             string_or(d, "version", "unknown")};

  for (const rundir::ManifestShardNote& f : manifest.failures_or_none())
    run.manifest_failures.push_back({f.shard, f.reason.empty() ? "failed" : f.reason});
  return run;
}

namespace {

// The lines of one run's experiment.toml that the other's lacks, "-" for the baseline's and "+"
// for the current's, at most `most` of them; "" when a file cannot be read.
std::string experiment_difference(const std::string& baseline_dir, const std::string& current_dir,
                                  std::size_t most = 8) {
  const auto lines = [](const std::string& dir) {
    std::vector<std::string> out;
    std::istringstream in(util::read_file(rundir::run_folder::experiment(dir)));
    for (std::string line; std::getline(in, line);)
      if (line.find_first_not_of(" \t") != std::string::npos) out.push_back(line);
    return out;
  };
  std::vector<std::string> before, after;
  try {
    before = lines(baseline_dir), after = lines(current_dir);
  } catch (const std::exception&) {
    return "";
  }
  const std::multiset<std::string> in_before(before.begin(), before.end()),
      in_after(after.begin(), after.end());
  std::string out;
  std::size_t listed = 0, more = 0;
  const auto list = [&](const std::vector<std::string>& side, const std::multiset<std::string>& other,
                        const char* sign) {
    for (const std::string& l : side) {
      if (other.count(l)) continue;
      if (listed++ < most) out += std::string("\n  ") + sign + " " + l;
      else ++more;
    }
  };
  list(before, in_after, "-");
  list(after, in_before, "+");
  if (more) out += "\n  ... and " + std::to_string(more) + " more lines";
  return out;
}

}  // namespace

void require_same_experiment(const RunIdentity& baseline, const RunIdentity& current) {
  if (baseline.hash == current.hash && baseline.seed == current.seed) return;
  const std::string difference = experiment_difference(baseline.dir, current.dir);
  throw util::UserError(
      "not runs of the same experiment: baseline " + baseline.dir + " has experiment hash " +
      baseline.hash + " (seed " + std::to_string(baseline.seed) + "), current " + current.dir +
      " has experiment hash " + current.hash + " (seed " + std::to_string(current.seed) +
      "); an audit compares the same primitives, so both runs must come from the same "
      "experiment file." +
      (difference.empty() ? "" : " Their experiment.toml files differ in (- baseline, + current):" +
                                     difference) +
      "\nAn experiment changed on purpose needs a new baseline: a run of the new experiment "
      "(for the nightly audit: scripts/nightly.sh --promote " + current.dir + ")");
}

DriverIdentity driver_of(const RunIdentity& run, const std::string& platform) {
  const auto it = run.drivers.find(platform);
  return it != run.drivers.end() ? it->second : DriverIdentity{platform, "unknown", "unknown"};
}

std::vector<MissingShard> missing_shards(const RunIdentity& run, const std::string& platform,
                                         const std::string& side) {
  std::vector<MissingShard> out;
  for (const rundir::Shard& s : rundir::plan_shards(run.experiment)) {
    if (s.platform != platform || fs::exists(s.records_path(run.dir))) continue;
    MissingShard m{side, s.platform, s.kind, s.view, 0, s.begin, s.end, s.id(), "no records file"};
    for (const geometry::View& v : run.experiment.views)
      if (v.id == s.view) m.view_group = v.group;
    for (const ShardFailureNote& f : run.manifest_failures)
      if (f.shard == m.id) m.reason = f.reason;  // the last word on it
    out.push_back(m);
  }
  return out;
}

const char* failure_outcome_name(FailureOutcome o) {
  switch (o) {
    case FailureOutcome::kMissing:
      return "missing";
    case FailureOutcome::kPrimitivesFailed:
      return "primitives failed";
    case FailureOutcome::kRecovered:
      return "recovered";
    case FailureOutcome::kUnknown:
      return "unknown shard";
  }
  return "";
}

std::vector<ManifestFailure> manifest_failures_of(const RunIdentity& run,
                                                  const std::string& platform,
                                                  const std::string& side) {
  std::vector<ManifestFailure> out;
  const std::vector<rundir::Shard> plan = rundir::plan_shards(run.experiment);
  for (const ShardFailureNote& f : run.manifest_failures) {
    if (f.shard.rfind(platform + ".", 0) != 0) continue;
    ManifestFailure m{side, platform, f.shard, f.reason};
    for (const rundir::Shard& s : plan) {
      if (s.id() != f.shard) continue;
      m.kind = s.kind, m.view = s.view, m.begin = s.begin, m.end = s.end;
      for (const geometry::View& v : run.experiment.views)
        if (v.id == s.view) m.view_group = v.group;
      m.outcome = fs::exists(s.records_path(run.dir)) ? FailureOutcome::kRecovered
                                                      : FailureOutcome::kMissing;
    }
    out.push_back(m);
  }
  return out;
}

}  // namespace ra::audit
