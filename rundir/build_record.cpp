// A driver build's folder and its build.json (see the header).
#include "rundir/build_record.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "rundir/manifest.h"
#include "util/atomic_file.h"
#include "util/errors.h"
#include "util/json_file.h"

namespace fs = std::filesystem;

namespace ra::rundir {
namespace {

using json = nlohmann::json;

const char* kBuildJson = "build.json";

// A key of `j` of string type, else "" (absent) or an error naming the key (another type).
std::string text_of(const json& j, const char* key, const std::string& path) {
  const auto it = j.find(key);
  if (it == j.end() || it->is_null()) return "";
  if (!it->is_string())
    throw util::UserError(path + ": \"" + key + "\" must be a string, not " + it->dump());
  return it->get<std::string>();
}

bool flag_of(const json& j, const char* key, const std::string& path) {
  const auto it = j.find(key);
  if (it == j.end() || it->is_null()) return false;
  if (!it->is_boolean())
    throw util::UserError(path + ": \"" + key + "\" must be true or false, not " + it->dump());
  return it->get<bool>();
}

const json& object_of(const json& j, const char* key, const std::string& path) {
  static const json empty = json::object();
  const auto it = j.find(key);
  if (it == j.end() || it->is_null()) return empty;
  if (!it->is_object())
    throw util::UserError(path + ": \"" + key + "\" must be an object, not " + it->dump());
  return *it;
}

// nlohmann's "[json.exception.parse_error.101] " prefix off: the file and the place say enough.
std::string without_library_prefix(std::string why) {
  if (why.rfind("[json.exception.", 0) == 0 && why.find("] ") != std::string::npos)
    why.erase(0, why.find("] ") + 2);
  return why;
}

}  // namespace

std::string build_cache_dir() {
  if (const char* c = std::getenv("RENDERAUDIT_BUILD_CACHE"); c && *c) return c;
  if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x)
    return std::string(x) + "/renderaudit/builds";
  const char* home = std::getenv("HOME");
  return std::string(home && *home ? home : "/tmp") + "/.cache/renderaudit/builds";
}

std::string build_record_path(const std::string& dir) {
  return (fs::path(dir) / kBuildJson).string();
}

bool is_build_folder(const std::string& dir) {
  std::error_code ec;
  const std::string name = fs::path(dir).filename().string();
  return !name.empty() && name[0] != '.' && fs::is_regular_file(fs::path(dir) / kBuildJson, ec);
}

BuildRecord read_build_record(const std::string& dir) {
  const std::string path = build_record_path(dir);
  std::string text;
  try {
    text = util::read_file(path);
  } catch (const std::exception& e) {
    throw util::UserError(e.what());  // "cannot read PATH"
  }
  json j;
  try {
    j = util::parse_json_document(text, path);
  } catch (const json::exception& e) {
    throw util::UserError(path + ": " + without_library_prefix(e.what()));
  }
  // Every build.json the project wrote carries its header; a folder made by hand may not.
  if (j.is_object() && j.contains("schema"))
    require_document_header(j, kBuildDocument, kBuildDocumentVersion, path,
                            "a build of another renderaudit: fetch or build it again");
  if (!j.is_object()) throw util::UserError(path + ": not a JSON object");
  BuildRecord r;
  r.dir = dir;
  r.name = text_of(j, "name", path);
  r.suite = text_of(j, "suite", path);
  r.debian_version = text_of(j, "debian_version", path);
  r.fetched_utc = text_of(j, "fetched_utc", path);
  const json& gl = object_of(j, "gl", path);
  r.osmesa_version = text_of(object_of(gl, "osmesa", path), "version", path);
  r.egl_version = text_of(object_of(gl, "egl", path), "version", path);
  if (const auto files = j.find("files"); files != j.end() && !files->is_null()) {
    if (!files->is_array()) throw util::UserError(path + ": \"files\" must be a list of paths");
    for (const json& f : *files) {
      if (!f.is_string()) throw util::UserError(path + ": \"files\" must be a list of paths");
      r.files.push_back(f.get<std::string>());
    }
  }
  r.origin = j.contains("origin") ? text_of(j, "origin", path) : "Debian";
  const json& sb = object_of(j, "source_build", path);
  r.source = text_of(sb, "source", path);
  r.commit = text_of(sb, "commit", path);
  r.version = text_of(sb, "version", path);
  r.from_git = flag_of(sb, "git", path);
  r.clean = flag_of(sb, "clean", path);
  r.key = text_of(sb, "key", path);
  return r;
}

std::vector<BuildRecord> list_cached_builds(const std::string& cache_dir) {
  const std::string cache = cache_dir.empty() ? build_cache_dir() : cache_dir;
  std::error_code ec;
  if (fs::exists(cache, ec) && !fs::is_directory(cache, ec))
    throw util::UserError("the build cache " + cache +
                          " is not a folder (RENDERAUDIT_BUILD_CACHE, --cache): name a folder");
  std::vector<BuildRecord> out;
  for (const auto& e : fs::directory_iterator(cache, ec)) {
    const std::string dir = e.path().string();
    if (!is_build_folder(dir)) continue;
    const std::string folder = e.path().filename().string();
    try {
      BuildRecord b = read_build_record(dir);
      if (b.name != folder) b.recorded_name = b.name;
      b.name = folder;
      out.push_back(b);
    } catch (const std::exception& x) {
      BuildRecord s;
      s.name = folder;
      s.dir = dir;
      s.damaged = x.what();
      out.push_back(s);
    }
  }
  std::sort(out.begin(), out.end(),
            [](const BuildRecord& a, const BuildRecord& b) { return a.name < b.name; });
  return out;
}

std::string cached_build_of_suite(const std::string& suite) {
  std::string best;
  fs::file_time_type best_time{};
  for (const BuildRecord& b : list_cached_builds()) {
    if (!b.damaged.empty() || b.suite != suite) continue;
    std::error_code ec;
    const auto t = fs::last_write_time(fs::path(b.dir) / kBuildJson, ec);
    if (best.empty() || t > best_time) best = b.dir, best_time = t;
  }
  return best;
}

std::string build_library_dir(const std::string& dir) {
  // Debian packages unpacked (usr/lib/<multiarch>), a meson install prefix (lib/<multiarch>), others.
  const std::vector<std::string> candidates = {dir + "/usr/lib/x86_64-linux-gnu", dir + "/usr/lib",
                                               dir + "/lib/x86_64-linux-gnu", dir + "/lib", dir};
  std::error_code ec;
  for (const std::string& c : candidates)
    if (fs::exists(c + "/libOSMesa.so.8", ec) || fs::exists(c + "/libEGL_mesa.so.0", ec) ||
        fs::exists(c + "/libvulkan_lvp.so", ec))
      return c;
  return candidates.front();
}

}  // namespace ra::rundir
