// The build cache's sizes and the removal of builds (see the header).
#include "runner/build_cache.h"

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <set>
#include <utility>

#include "rundir/driver_build.h"
#include "runner/build_fetch.h"
#include "runner/git_command.h"
#include "util/atomic_file.h"
#include "util/dir_lock.h"
#include "util/errors.h"

namespace fs = std::filesystem;

namespace ra::runner {
namespace {

constexpr const char* kRemovingPrefix = ".removing-";

std::string cache_or_default(const std::string& cache) {
  return cache.empty() ? rundir::build_cache_dir() : cache;
}

bool starts_with(const std::string& s, const char* prefix) { return s.rfind(prefix, 0) == 0; }

}  // namespace

std::uintmax_t disk_usage(const std::string& path) {
  struct stat st {};
  if (::lstat(path.c_str(), &st) != 0) return 0;
  std::uintmax_t bytes = std::uintmax_t(st.st_blocks) * 512;
  if (!S_ISDIR(st.st_mode)) return bytes;
  std::set<std::pair<dev_t, ino_t>> linked;  // files with several names, counted once
  std::error_code ec;
  for (fs::recursive_directory_iterator it(path, fs::directory_options::skip_permission_denied, ec),
       end;
       !ec && it != end; it.increment(ec)) {
    if (::lstat(it->path().c_str(), &st) != 0) continue;
    if (!S_ISDIR(st.st_mode) && st.st_nlink > 1 && !linked.insert({st.st_dev, st.st_ino}).second)
      continue;
    bytes += std::uintmax_t(st.st_blocks) * 512;
  }
  return bytes;
}

CacheUsage cache_usage(const std::string& cache_dir) {
  const std::string cache = cache_or_default(cache_dir);
  CacheUsage u;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(cache, ec)) {
    const std::string name = e.path().filename().string();
    const std::uintmax_t bytes = disk_usage(e.path().string());
    u.total += bytes;
    if (name == ".incremental")
      u.incremental += bytes;
    else if (starts_with(name, ".fetch-") || starts_with(name, ".source-") ||
             starts_with(name, kRemovingPrefix))
      u.unfinished += bytes;
    else if (name[0] != '.' && fs::exists(e.path() / "build.json", ec))
      u.builds += bytes;
  }
  struct stat st {};
  if (::stat(cache.c_str(), &st) == 0) u.total += std::uintmax_t(st.st_blocks) * 512;
  return u;
}

std::string build_in_use_by(const std::string& dir) {
  std::string source;
  try {
    const nlohmann::json j = nlohmann::json::parse(util::read_file(dir + "/build.json"));
    if (j.value("origin", "") != "source" || !j.contains("source_build")) return "";
    source = j["source_build"].value("source", "");
  } catch (const std::exception&) {
    return "";  // a damaged build.json names no tree: nothing can be holding it
  }
  std::error_code ec;
  if (source.empty() || !fs::is_directory(source, ec)) return "";
  // The folder lock_source_tree takes: the git folder of a checkout, else the tree itself.
  const GitResult git_dir = git(source, {"rev-parse", "--absolute-git-dir"});
  const std::string holder =
      util::DirLock::current_holder(git_dir.ok && !git_dir.out.empty() ? git_dir.out : source);
  return holder.empty() ? "" : "its source tree " + source + " is held by " + holder;
}

std::vector<RemovedBuild> remove_builds(const std::string& cache_dir,
                                        const std::vector<std::string>& names) {
  const std::string cache = cache_or_default(cache_dir);
  std::error_code ec;
  if (!fs::is_directory(cache, ec))
    throw util::UserError("builds remove: the build cache " + cache +
                          " is not a folder (RENDERAUDIT_BUILD_CACHE, --cache)");
  // What earlier removals left: no longer builds, only their bytes.
  for (const auto& e : fs::directory_iterator(cache, ec))
    if (starts_with(e.path().filename().string(), kRemovingPrefix)) fs::remove_all(e.path(), ec);

  const std::vector<BuildSummary> builds = list_builds(cache);
  std::vector<std::string> held;
  for (const BuildSummary& b : builds) held.push_back(b.name);
  std::vector<std::string> wanted;
  for (const std::string& name : names)
    if (std::find(wanted.begin(), wanted.end(), name) == wanted.end()) wanted.push_back(name);
  for (const std::string& name : wanted) {
    if (std::find(held.begin(), held.end(), name) != held.end()) continue;
    std::string list;
    for (const std::string& h : held) list += (list.empty() ? "" : ", ") + h;
    throw util::UserError(
        "builds remove: no build '" + name + "' in " + cache + "; " +
        (held.empty() ? std::string("the cache holds no builds") : "it holds " + list) +
        " (nothing was removed)");
  }
  for (const std::string& name : wanted)
    if (const std::string why = build_in_use_by(cache + "/" + name); !why.empty())
      throw util::UserError("builds remove: " + name + " is in use: " + why +
                            ", which may build or draw with it; wait for it to finish (nothing "
                            "was removed)");

  std::vector<RemovedBuild> removed;
  for (const std::string& name : wanted) {
    const std::string dir = cache + "/" + name;
    const std::string aside =
        cache + "/" + kRemovingPrefix + name + "-" + std::to_string(::getpid());
    RemovedBuild r{name, disk_usage(dir)};
    // One rename takes it out of the cache; only then are its files deleted.
    fs::rename(dir, aside, ec);
    if (ec)
      throw util::UserError("builds remove: cannot move " + dir + " aside (" + ec.message() + ")");
    fs::remove_all(aside, ec);
    if (ec)
      throw util::UserError("builds remove: " + name + " is no longer a build, but " + aside +
                            " could not be deleted (" + ec.message() + "); delete it by hand");
    removed.push_back(r);
  }
  return removed;
}

std::string size_text(std::uintmax_t bytes) {
  static const char* const units[] = {"B", "KiB", "MiB", "GiB", "TiB", "PiB"};
  double v = double(bytes);
  std::size_t u = 0;
  while (u + 1 < std::size(units) && v >= 999.5) v /= 1024, ++u;
  char buf[32];
  if (u == 0)
    std::snprintf(buf, sizeof buf, "%llu B", static_cast<unsigned long long>(bytes));
  else
    std::snprintf(buf, sizeof buf, v < 9.95 ? "%.1f %s" : "%.0f %s", v, units[u]);
  return buf;
}

}  // namespace ra::runner
