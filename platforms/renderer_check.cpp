// Early check of the driver a run loaded. See renderer_check.h.
#include "platforms/renderer_check.h"

#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>

#include "platforms/driver_loading.h"
#include "platforms/platform.h"
#include "rundir/run_folder.h"
#include "util/atomic_file.h"
#include "util/errors.h"
#include "util/json_file.h"

namespace fs = std::filesystem;

namespace ra::platforms {

RendererCheck::RendererCheck(std::string run_dir, const std::string& pattern)
    : run_dir_(std::move(run_dir)), pattern_(pattern) {
  if (pattern_.empty()) return;
  try {
    regex_ = std::regex(pattern_, std::regex::ECMAScript);
  } catch (const std::regex_error& e) {
    throw util::UserError("--expect-renderer '" + pattern_ + "': not a valid regular expression (" +
                          e.what() + ")");
  }
}

namespace {

// The driver file's libraries (build.libraries: path and FNV-1a 64 of the bytes) against those
// this process loaded, matched by file name: a build folder copied or moved elsewhere keeps its
// file names and bytes, a library rebuilt, patched or replaced in place keeps neither its bytes
// nor its fingerprint. GL strings alone cannot tell two builds of one Mesa version apart.
void require_recorded_libraries(const std::string& path, const std::string& platform,
                                const nlohmann::json& driver_file) {
  const auto build = driver_file.find("build");
  if (build == driver_file.end() || !build->is_object()) return;
  const auto libraries = build->find("libraries");
  if (libraries == build->end() || !libraries->is_array() || libraries->empty()) return;
  std::map<std::string, LoadedLibrary> now;  // by file name
  for (LoadedLibrary& l : loaded_driver_libraries())
    now.emplace(fs::path(l.path).filename().string(), std::move(l));
  for (const nlohmann::json& recorded : *libraries) {
    if (!recorded.is_object() || !recorded.contains("path") || !recorded["path"].is_string() ||
        !recorded.contains("fnv1a64") || !recorded["fnv1a64"].is_string())
      throw util::UserError(path + ": build.libraries: each entry needs a \"path\" and an "
                            "\"fnv1a64\" string");
    const std::string recorded_path = recorded["path"].get<std::string>();
    const std::string recorded_hash = recorded["fnv1a64"].get<std::string>();
    const auto it = now.find(fs::path(recorded_path).filename().string());
    if (it == now.end() || it->second.fnv1a64 == recorded_hash) continue;
    throw util::UserError(
        std::string(rundir::kDriverMismatch) + ": " + platform + ": library " + it->second.path +
        " has fingerprint " + it->second.fnv1a64 + " (FNV-1a 64 of its bytes), but the run's "
        "records were made with " + recorded_path + " of fingerprint " + recorded_hash + " (" +
        path + "): the file changed since (rebuilt, patched or damaged), so this process would "
        "draw with another driver than the run's; nothing was drawn. Restore the build the run "
        "was made with, or start a new run directory");
  }
}

}  // namespace

void require_run_driver(const std::string& run_dir, const std::string& platform,
                        const DriverInfo& loaded) {
  const std::optional<rundir::PlatformSpec> spec = rundir::find_platform(platform);
  if (!spec || !spec->draws_with_driver()) return;
  const std::string path = rundir::run_folder::driver(run_dir, platform);
  std::error_code ec;
  if (!fs::exists(path, ec)) return;
  nlohmann::json j;
  try {
    j = util::parse_json_document(util::read_file(path), path);
  } catch (const std::exception& e) {
    throw util::UserError(path + ": not a readable driver file (" + e.what() + ")");
  }
  const std::string renderer = j.value("renderer", ""), version = j.value("version", "");
  if (renderer == loaded.renderer && version == loaded.version) {
    require_recorded_libraries(path, platform, j);
    return;
  }
  std::string where;
  if (const auto b = j.find("build"); b != j.end() && b->is_object())
    if (const auto f = b->find("folder"); f != b->end() && f->is_string())
      where = ", build folder " + f->get<std::string>();
  throw util::UserError(
      std::string(rundir::kDriverMismatch) + ": " + platform + ": this process loaded GL_RENDERER '" +
      loaded.renderer + "' GL_VERSION '" + loaded.version + "' (" + loaded.backend +
      "), but the run's records were made with GL_RENDERER '" + renderer + "' GL_VERSION '" +
      version + "' (" + path + where +
      "); nothing was drawn. Draw with the driver that made the run: name its build "
      "(PLATFORM@BUILD) or run in the environment the run was made in");
}

std::string RendererCheck::mismatch() {
  if (pattern_.empty()) return "";
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(rundir::run_folder::drivers(run_dir_), ec)) {
    if (entry.path().extension() != ".json") continue;
    const std::string name = entry.path().stem().string();
    const std::optional<rundir::PlatformSpec> spec = rundir::find_platform(name);
    if (!spec || !spec->draws_with_driver() || checked_.count(name)) continue;
    checked_.insert(name);
    std::string renderer;
    try {
      const std::string path = entry.path().string();
      renderer = util::parse_json_document(util::read_file(path), path).value("renderer", "");
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
