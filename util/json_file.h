// A JSON file that may be absent or half-written by a writer at work (a manifest, a progress file):
// its value, or null. For readers that must not fail on what another process is writing.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace ra::util {

// The parsed file, or null when it is missing, unreadable or not JSON.
nlohmann::json read_json_or_null(const std::string& path);

}  // namespace ra::util
