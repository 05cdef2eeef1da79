// DIR/manifest.json: the provenance of a run directory (experiment, drivers, host, commit, times,
// failures), with a schema version of its own.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace ra {

constexpr int kManifestSchemaVersion = 1;

std::string project_commit();   // the git commit this binary was built from
std::string project_version();  // renderaudit's version
nlohmann::json host_description();  // hostname, CPU model, cores, OS
std::string utc_now_iso8601();

// The opening of every JSON document the project writes, one spelling for all of them:
// {"schema": "renderaudit-NAME", "schema_version": VERSION} and, with `provenance`, "tool" (name,
// version, commit), "host" (host_description) and "created_utc", as the run manifest has.
nlohmann::json document_header(const std::string& name, int version, bool provenance = true);

}  // namespace ra

namespace ra {

// The fields of a manifest that `status` acts on, each checked for its type and range when read:
// a manifest edited by hand or by another tool gives an error naming the file and the key, never
// a crash or a bare JSON library message. Absent fields keep these defaults.
struct ManifestFields {
  std::string status;                       // "complete", "running", ...; "" when absent
  std::string experiment_name;              // experiment.name; "" when absent
  bool has_platforms_run = false;
  std::vector<std::string> platforms_run;   // --platform of the run
  bool has_slice = false;
  int slice_index = 1, slice_count = 1;     // 1 <= index <= count <= 100000
  std::vector<std::string> failed_shards;   // failures[].shard
};

// `manifest` as parsed from `path` (null: nothing known, the defaults). Throws ra::UserError
// "PATH: 'KEY' must be ... (found ...)".
ManifestFields read_manifest_fields(const nlohmann::json& manifest, const std::string& path);

// Writes the manifest atomically. When that fails (a full disk, typically), the manifest already
// on disk is overwritten in place, within the blocks it already occupies, by a shortened one with
// "status": "failed" and the reason, so that it never stays "running"; then throws
// std::runtime_error naming the file and the free space.
void write_manifest(const std::string& path, const nlohmann::json& manifest);

// The conformance rules (metrics/conformance.h) a run directory's records were judged by: its
// manifest's "conformance_rules", 1 for a manifest of an earlier run without it, 0 for none (a
// new directory). Throws UserError naming `path` when the value is not a positive integer.
int conformance_rules_of(const nlohmann::json& manifest, const std::string& path);

}  // namespace ra
