// A JSON file that may be absent or half-written by a writer at work (a manifest, a progress file):
// its value, or null. For readers that must not fail on what another process is writing.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace ra::util {

// Run-directory documents (manifests, driver files, tallies) are a few levels deep; a parser that
// recurses would overflow the stack on a hostile file nested 100,000 levels deep.
constexpr int kMaxJsonDepth = 256;

// `text` parsed as JSON, after checking that arrays and objects nest at most kMaxJsonDepth deep.
// Throws UserError naming `path`, the byte offset and the limit when deeper, and
// nlohmann::json::parse_error when it is not JSON.
nlohmann::json parse_json_document(const std::string& text, const std::string& path);

// The parsed file, or null when it is missing, unreadable, not JSON or nested too deep.
nlohmann::json read_json_or_null(const std::string& path);

}  // namespace ra::util
