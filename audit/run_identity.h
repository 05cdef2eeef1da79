// What an audit needs to know about a run directory before comparing records: which experiment
// (manifest.json: hash, seed; experiment.toml: views, counts, shard size), which drivers drew it
// (GL_RENDERER / GL_VERSION per platform), and what is missing (shards without a records file,
// shard failures the manifest lists). docs/records.md describes the files.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "audit/audit_summary.h"
#include "rundir/experiment.h"
#include "geometry/primitive.h"

namespace ra::audit {

// A shard failure as the manifest lists it ("failures": the coordinator notes every worker that
// crashed, hung or failed, including those it then re-ran or bisected).
struct ShardFailureNote {
  std::string shard, reason;
};

struct RunIdentity {
  std::string dir;         // as given
  rundir::Experiment experiment;  // DIR/experiment.toml (its own [run] shard size)
  std::string name, hash;  // manifest.json "experiment": name, hash
  uint64_t seed = 0;       // manifest.json "experiment": seed
  std::string status;      // manifest.json "status": "complete", "failed", "running", ...
  int conformance_rules = 1;  // manifest.json "conformance_rules" (absent: 1), metrics/conformance.h
  std::map<std::string, DriverIdentity> drivers;    // by platform; "unknown" when never recorded
  std::vector<ShardFailureNote> manifest_failures;  // in the manifest's order
};

// Reads DIR/manifest.json and DIR/experiment.toml. Throws ra::util::UserError naming the file when either
// is missing or unreadable (DIR is then not a run directory).
RunIdentity load_run_identity(const std::string& dir);

// Throws ra::util::UserError naming both directories, both experiment hashes and both seeds when the runs
// are not of the same experiment (different hash or seed).
void require_same_experiment(const RunIdentity& baseline, const RunIdentity& current);

// The driver of `platform` in the run ("unknown" renderer and version when the run never recorded
// it, e.g. every shard of that platform failed).
DriverIdentity driver_of(const RunIdentity& run, const std::string& platform);

// A planned shard (rundir/shard.h) of a platform that has no records file, i.e. a shard that
// crashed, timed out or never ran.
struct MissingShard {
  std::string side;  // "baseline" or "current"
  std::string platform;
  geometry::Kind kind = geometry::Kind::kPoint;
  int view = 0, view_group = 0;  // view 1-based; view_group 0 = A
  uint64_t begin = 0, end = 0;   // primitive indices [begin, end)
  std::string id;                // the shard id, e.g. "faulty.point.v1.10-20"
  std::string reason;  // the manifest's reason when it lists the shard, else "no records file"
};

// The shards of `platform` planned by the run's own experiment.toml whose records file is absent.
std::vector<MissingShard> missing_shards(const RunIdentity& run, const std::string& platform,
                                         const std::string& side);

// What became of a shard failure the manifest lists, judged from the run directory (so the audit
// does not depend on how the coordinator words its notes):
enum class FailureOutcome {
  kMissing,           // the shard has no records file: it failed (also a MissingShard)
  kPrimitivesFailed,  // its records hold crash / timeout records: the coordinator bisected it
  kRecovered,         // its records are complete and none failed: the failure did not recur
  kUnknown,           // not a shard of the experiment's plan: counted as a failure
};
const char* failure_outcome_name(FailureOutcome o);  // "missing", "primitives failed", ...

struct ManifestFailure {
  std::string side;  // "baseline" or "current"
  std::string platform, shard, reason;
  geometry::Kind kind = geometry::Kind::kPoint;
  int view = 0, view_group = 0;
  uint64_t begin = 0, end = 0;
  FailureOutcome outcome = FailureOutcome::kUnknown;
};

// The manifest failures of `platform`'s shards, with outcome kMissing, kRecovered (records file
// present; the caller turns it into kPrimitivesFailed when a crash / timeout record lies in
// [begin, end)) or kUnknown.
std::vector<ManifestFailure> manifest_failures_of(const RunIdentity& run,
                                                  const std::string& platform,
                                                  const std::string& side);

}  // namespace ra::audit
