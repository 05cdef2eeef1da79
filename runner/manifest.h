// DIR/manifest.json: the provenance of a run directory (experiment, drivers, host, commit, times,
// failures), with a schema version of its own.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

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
