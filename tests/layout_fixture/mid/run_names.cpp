// Spells run folder names: two findings (lines 7 and 8); the prose and the comment are fine.
#include <filesystem>
#include <string>

namespace ra::mid {
// DIR + "/manifest.json" in a comment: fine
std::string manifest_of(const std::string& dir) { return dir + "/manifest.json"; }
std::filesystem::path experiment_of(const std::filesystem::path& p) { return p / "experiment.toml"; }
const char* help() { return "run directory (holds experiment.toml and manifest.json)"; }
}  // namespace ra::mid
