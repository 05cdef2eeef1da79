// A declarative experiment: platforms x views x primitive counts, parsed from a TOML file and
// validated before anything renders. The file format is documented in docs/experiments.md ("Experiment
// files"); experiments/quick.toml and experiments/nist2008.toml are complete examples.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "geometry/primitive.h"
#include "geometry/view.h"
#include "rundir/records_format.h"
#include "rundir/fault_plan.h"
#include "rundir/platform_spec.h"

namespace ra::rundir {

// `[builds.NAME]`: a driver build the experiment's `PLATFORM@NAME` platforms draw with
// (rundir/build_record.h). Its folder: `dir` (absolute, or under ~/), else the newest build
// that `renderaudit builds fetch SUITE` put in the cache for `suite`, else NAME in the cache.
struct DriverBuildDecl {
  std::string name;
  std::string dir;     // as written, ~ expanded; empty: from the cache
  std::string suite;   // e.g. "bookworm-backports"; optional
  std::string origin;  // where it came from, free text (e.g. "Debian"); optional
};

struct Experiment {
  std::string path;        // the file as given
  std::string name;        // `name` key, default the file's stem; names outputs/<name>/
  std::string text;        // the file's bytes
  std::string hash;        // hex FNV-1a 64 of the canonical TOML, [run] excluded
  uint64_t seed = 0;
  std::vector<std::string> platforms;
  std::vector<geometry::View> views;   // cartesian product, numbered as in the paper's Table 1
  std::array<uint64_t, 3> counts{};    // primitives per view, indexed by Kind
  uint64_t shard_size = 5000;          // primitives per shard
  double shard_timeout_s = 600;        // a shard still running after this is killed
  // Ceilings on the plan, checked before anything is written ([run] max_renders, max_shards): a
  // typo of a few zeros must not start a month-long run, and the coordinator's memory (about 150
  // bytes per planned shard) stays bounded.
  uint64_t max_renders = 2000000000;
  uint64_t max_shards = 1000000;
  // [run] records_format: "csv.zst" (default: a fifth of the size, read faster; every reader of the
  // project, pandas, R and DuckDB open it) or "csv" (plain text for tools that read no zstd).
  rundir::RecordsFormat records_format = rundir::RecordsFormat::kCsvZst;
  rundir::FaultPlan faults;
  std::map<std::string, DriverBuildDecl> builds;  // [builds.NAME], by NAME
};

// The platform `name` of `exp`, its build's folder resolved as DriverBuildDecl says. Throws
// UserError for a name the experiment cannot draw with (unknown, or a build it does not declare).
rundir::PlatformSpec experiment_platform(const Experiment& exp, const std::string& name);

// The fault plan the `faulty` test platform draws with: for `faulty@BUILD`, the [faults] table of
// BUILD's folder's faults.toml (so a test can stand in for two driver builds of one platform:
// renderaudit bisect's tests), else the experiment's. Throws UserError for a bad file.
rundir::FaultPlan fault_plan_for(const Experiment& exp, const rundir::PlatformSpec& spec);
rundir::FaultPlan load_fault_plan(const std::string& path);

// Limits checked by validation (also quoted in error messages).
constexpr int kMaxWindow = 16384;
constexpr uint64_t kMaxPrimitives = 100000000;  // per kind and view
constexpr int kMaxOrientations = 1000;
constexpr uint64_t kMaxShardsCeiling = 100000000;  // the largest run.max_shards allowed

// Parses and validates; throws UserError "file:line:column: what (allowed: ...)".
Experiment load_experiment(const std::string& path);
Experiment parse_experiment(const std::string& text, const std::string& path);

}  // namespace ra::rundir
