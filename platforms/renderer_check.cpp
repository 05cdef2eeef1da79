// Early check of the driver a run loaded. See renderer_check.h.
#include "platforms/renderer_check.h"

#include <filesystem>
#include <nlohmann/json.hpp>

#include "util/atomic_file.h"
#include "util/errors.h"
#include "platforms/platform.h"

namespace fs = std::filesystem;

namespace ra::platforms {

RendererCheck::RendererCheck(std::string run_dir, const std::string& pattern)
    : run_dir_(std::move(run_dir)), pattern_(pattern) {
  if (pattern_.empty()) return;
  try {
    regex_ = std::regex(pattern_, std::regex::ECMAScript);
  } catch (const std::regex_error& e) {
    throw UserError("--expect-renderer '" + pattern_ + "': not a valid regular expression (" +
                    e.what() + ")");
  }
}

void require_run_driver(const std::string& run_dir, const std::string& platform,
                        const DriverInfo& loaded) {
  const std::optional<PlatformSpec> spec = find_platform(platform);
  if (!spec || !spec->draws_with_driver()) return;
  const std::string path = run_dir + "/drivers/" + platform + ".json";
  std::error_code ec;
  if (!fs::exists(path, ec)) return;
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(read_file(path));
  } catch (const std::exception& e) {
    throw UserError(path + ": not a readable driver file (" + e.what() + ")");
  }
  const std::string renderer = j.value("renderer", ""), version = j.value("version", "");
  if (renderer == loaded.renderer && version == loaded.version) return;
  std::string where;
  if (const auto b = j.find("build"); b != j.end() && b->is_object())
    if (const auto f = b->find("folder"); f != b->end() && f->is_string())
      where = ", build folder " + f->get<std::string>();
  throw UserError(std::string(kDriverMismatch) + ": " + platform + ": this process loaded GL_RENDERER '" +
                  loaded.renderer + "' GL_VERSION '" + loaded.version + "' (" + loaded.backend +
                  "), but the run's records were made with GL_RENDERER '" + renderer +
                  "' GL_VERSION '" + version + "' (" + path + where +
                  "); nothing was drawn. Draw with the driver that made the run: name its build "
                  "(PLATFORM@BUILD) or run in the environment the run was made in");
}

std::string RendererCheck::mismatch() {
  if (pattern_.empty()) return "";
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(run_dir_ + "/drivers", ec)) {
    if (entry.path().extension() != ".json") continue;
    const std::string name = entry.path().stem().string();
    const std::optional<PlatformSpec> spec = find_platform(name);
    if (!spec || !spec->draws_with_driver() || checked_.count(name)) continue;
    checked_.insert(name);
    std::string renderer;
    try {
      renderer = nlohmann::json::parse(read_file(entry.path().string())).value("renderer", "");
    } catch (const std::exception&) {
      checked_.erase(name);  // being written: look again next time
      continue;
    }
    if (!std::regex_search(renderer, regex_))
      return name + ": GL_RENDERER '" + renderer + "' does not match --expect-renderer '" +
             pattern_ + "'";
  }
  return "";
}

}  // namespace ra::platforms
