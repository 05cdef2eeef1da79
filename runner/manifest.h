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

}  // namespace ra
