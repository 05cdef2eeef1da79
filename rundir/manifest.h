// DIR/manifest.json: the provenance of a run directory (experiment, drivers, host, commit, times,
// failures), with a schema version of its own.
#pragma once

#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace ra::rundir {

constexpr int kManifestSchemaVersion = 1;

std::string project_commit();   // the git commit this binary was built from
std::string project_version();  // renderaudit's version
nlohmann::json host_description();  // hostname, CPU model, cores, OS
std::string utc_now_iso8601();

// The opening of every JSON document the project writes, one spelling for all of them:
// {"schema": "renderaudit-NAME", "schema_version": VERSION} and, with `provenance`, "tool" (name,
// version, commit), "host" (host_description) and "created_utc", as the run manifest has.
nlohmann::json document_header(const std::string& name, int version, bool provenance = true);
// The check every reader of such a document makes before it reads on: whether `doc` is an object
// whose "schema" is "renderaudit-NAME" and whose "schema_version" is `version`.
bool has_document_header(const nlohmann::json& doc, const std::string& name, int version);
// The same, as an error: unless has_document_header, throws util::UserError
// "PATH: expected schema renderaudit-NAME version VERSION (REMEDY)", the parenthesis only when
// `remedy` is not empty (e.g. "run `renderaudit analyze DIR` again").
void require_document_header(const nlohmann::json& doc, const std::string& name, int version,
                             const std::string& path, const std::string& remedy = "");

}  // namespace ra::rundir

namespace ra::rundir {

// DIR/manifest.json as a type. `run` writes it when it starts ("running") and when it ends,
// `merge` when it has gathered its inputs; `status`, analyze, report and audit read it. Every field
// is checked for its type (and range) when read: a manifest edited by hand or by another tool gives
// an error naming the file, the key and what it must be, never a crash or a bare JSON library
// message. Writing gives the keys, values and order the file had (keys in alphabetical order, as
// nlohmann::json sorts them); keys this version does not know are kept as they were read.
// Times are UTC, ISO 8601 ("2026-11-26T05:42:52Z"); durations are seconds of wall time.

// A shard one run or merge noted: a worker that crashed, hung or failed ("failures"), or a records
// file found damaged and redone ("damaged_shards_redone").
struct ManifestShardNote {
  std::string shard, reason;
};

// A primitive the records hold as crash or timeout, with the reason the run gave.
struct ManifestFailedPrimitive {
  std::string shard;     // id of the whole shard
  uint64_t index = 0;    // the primitive's index in its kind
  std::string status;    // "crash" or "timeout" (metrics/records.h status_name)
  std::string reason;
};

struct ManifestExperiment {
  std::string name, file, hash;
  std::optional<uint64_t> seed;
  std::vector<std::string> platforms;
};

struct ManifestSlice {
  int index = 1, count = 1;              // 1 <= index <= count <= 100000
  std::optional<uint64_t> shards;        // shards in the slice
};

// One `run` of the directory. The fields from elapsed_s on are written when it ends: a run killed
// before its end leaves them absent.
struct ManifestInvocation {
  std::string started;
  uint64_t jobs = 0, shards_to_run = 0;
  std::optional<double> elapsed_s;       // wall seconds of the invocation
  std::string shard_order;               // "largest-expected-cost-first" or "plan"
  std::optional<double> worker_busy_s;   // worker-seconds, every worker from start to end
  std::optional<uint64_t> worker_processes;
  std::string workers;                   // "serve-shards" or "per-shard"
  std::optional<double> idle_core_s;     // jobs x elapsed_s - worker_busy_s, at least 0
};

struct ManifestShardCounts {
  uint64_t total = 0, complete = 0;
  std::optional<uint64_t> in_several_inputs;  // a merge: shards more than one input held
};

// An input of `merge`: where it came from, what was taken, and its own manifest's provenance.
struct ManifestInput {
  std::string dir;
  uint64_t shards_taken = 0;
  std::map<std::string, std::string> drivers;  // platform -> "GL_RENDERER | GL_VERSION"
  // the input manifest's slice, host, invocations, status, started, finished and failures, as
  // it had them (a JSON object)
  nlohmann::json provenance = nlohmann::json::object();
};

struct RunManifest {
  std::string schema;                          // "renderaudit-manifest"; "" when absent
  std::optional<int64_t> schema_version;
  std::string status;                          // "running", "complete", "failed", ...; "" absent
  std::string reason;                          // why the status is "failed" when the write failed
  std::optional<int> conformance_rules;        // metrics/conformance.h; absent before its time
  std::optional<ManifestExperiment> experiment;
  nlohmann::json tool;                         // name, version, commit; null when absent
  nlohmann::json host;                         // host_description(); null when absent
  std::optional<std::vector<std::string>> platforms_run;  // `run --platform`
  std::optional<ManifestSlice> slice;                     // `run --slice K/N`
  std::optional<std::vector<ManifestInvocation>> invocations;
  std::string started, finished, merged;       // "" when absent
  nlohmann::json drivers;                      // platform -> its drivers/PLATFORM.json; null absent
  std::optional<std::map<std::string, double>> shard_seconds;  // shard id -> worker wall seconds
  std::optional<ManifestShardCounts> shards;
  std::optional<std::vector<ManifestShardNote>> failures, damaged_shards_redone;
  std::optional<std::vector<ManifestFailedPrimitive>> failed_primitives;
  std::string wrong_renderer;                  // why --expect-renderer stopped the run; "" absent
  std::optional<std::vector<std::string>> missing_shards;  // a merge: planned shards no input held
  std::optional<std::vector<ManifestInput>> inputs;        // a merge's inputs
  nlohmann::json unknown = nlohmann::json::object();       // keys not listed above, as read

  // The conformance rules the directory's records were judged by: conformance_rules, 1 for a
  // manifest of an earlier run without it (it has invocations), 0 for none (a new directory).
  int rules_judged_by() const;
  // The failures listed, or none.
  const std::vector<ManifestShardNote>& failures_or_none() const;
  // The last invocation, or null when there is none.
  const ManifestInvocation* last_invocation() const;
};

// `manifest` as parsed from `path` (null: nothing known, every field absent). Throws
// ra::util::UserError "PATH: 'KEY' must be ... (found ...)".
RunManifest read_manifest(const nlohmann::json& manifest, const std::string& path);
// DIR/manifest.json at `path`: throws UserError naming the file when it is missing, not JSON, or a
// field has the wrong type.
RunManifest read_manifest_file(const std::string& path);
// The manifest file's JSON; null when the file is missing. A file that is there but is not a JSON
// document (empty, cut, NaN, bad UTF-8, nested too deep) throws UserError naming it: manifests are
// written by an atomic rename, so such a file is damaged, not half-written.
nlohmann::json read_manifest_json(const std::string& path);
// As read_manifest_file, but a missing file reads as the empty manifest.
RunManifest read_manifest_file_or_empty(const std::string& path);

// The manifest as its file holds it.
nlohmann::json manifest_json(const RunManifest& manifest);

// Writes the manifest atomically. When that fails (a full disk, typically), the manifest already
// on disk is overwritten in place, within the blocks it already occupies, by a shortened one with
// "status": "failed" and the reason, so that it never stays "running"; then throws
// std::runtime_error naming the file and the free space.
void write_manifest(const std::string& path, const RunManifest& manifest);

}  // namespace ra::rundir
