// Early check of the driver a run loaded. See renderer_check.h.
#include "platforms/renderer_check.h"

#include <filesystem>
#include <nlohmann/json.hpp>

#include "util/atomic_file.h"
#include "util/errors.h"
#include "platforms/platform.h"

namespace fs = std::filesystem;

namespace ra {

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

std::string RendererCheck::mismatch() {
  if (pattern_.empty()) return "";
  for (const PlatformSpec& spec : platform_specs()) {
    if (!spec.gallium_driver || checked_.count(spec.name)) continue;
    const std::string path = run_dir_ + "/drivers/" + spec.name + ".json";
    if (!fs::exists(path)) continue;
    checked_.insert(spec.name);
    std::string renderer;
    try {
      renderer = nlohmann::json::parse(read_file(path)).value("renderer", "");
    } catch (const std::exception&) {
      checked_.erase(spec.name);  // being written: look again next time
      continue;
    }
    if (!std::regex_search(renderer, regex_))
      return std::string(spec.name) + ": GL_RENDERER '" + renderer +
             "' does not match --expect-renderer '" + pattern_ + "'";
  }
  return "";
}

}  // namespace ra
