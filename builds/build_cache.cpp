// The build cache's sizes and the removal of builds (see the header).
#include "builds/build_cache.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <set>
#include <utility>

#include "rundir/build_record.h"
#include "builds/build_fetch.h"
#include "builds/git_command.h"
#include "util/atomic_file.h"
#include "util/dir_lock.h"
#include "util/errors.h"

namespace fs = std::filesystem;

namespace ra::builds {
namespace {

constexpr const char* kRemovingPrefix = ".removing-";

std::string cache_or_default(const std::string& cache) {
  return cache.empty() ? rundir::build_cache_dir() : cache;
}

bool starts_with(const std::string& s, const char* prefix) { return s.rfind(prefix, 0) == 0; }

// Whether the descriptor `fd` is the file at `path` now (not one renamed away or deleted since).
bool same_file(int fd, const std::string& path) {
  struct stat a {}, b {};
  return ::fstat(fd, &a) == 0 && ::stat(path.c_str(), &b) == 0 && a.st_dev == b.st_dev &&
         a.st_ino == b.st_ino;
}

// The exclusive lock a removal holds on a build's use-lock file; -1 when a user holds it (errno
// EWOULDBLOCK) or it cannot be opened.
int lock_for_removal(const std::string& dir, bool create) {
  const int fd = ::open(BuildInUse::lock_path(dir).c_str(),
                        O_RDWR | O_CLOEXEC | (create ? O_CREAT : 0), 0644);
  if (fd < 0) return -1;
  if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
    const int err = errno;
    ::close(fd);
    errno = err;
    return -1;
  }
  return fd;
}

// Deletes a folder renamed aside for removal, its use-lock file last (see the header). True when
// nothing of it is left, also when another removal's clean-up finished it.
bool delete_aside(const std::string& aside, std::error_code& ec) {
  const fs::path lock = BuildInUse::lock_path(aside);
  std::vector<fs::path> entries;
  for (const auto& e : fs::directory_iterator(aside, ec))
    if (e.path() != lock) entries.push_back(e.path());
  for (const fs::path& e : entries)
    if (fs::remove_all(e, ec); ec) break;
  std::error_code ignored;
  fs::remove(lock, ignored);
  fs::remove(aside, ec);
  std::error_code gone;
  if (!fs::exists(aside, gone) && !gone) ec.clear();
  return !ec;
}

}  // namespace

std::string BuildInUse::lock_path(const std::string& dir) { return dir + "/.in-use"; }

BuildInUse::BuildInUse(const std::string& dir) {
  const std::string path = lock_path(dir);
  const std::string gone = "the build " + dir +
                           " is gone (removed with `renderaudit builds remove`, or the cache was "
                           "cleared); build it again";
  std::error_code ec;
  if (!fs::is_regular_file(rundir::build_record_path(dir), ec)) throw util::UserError(gone);
  fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0 && (errno == EACCES || errno == EROFS || errno == EPERM)) {
    fd_ = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd_ < 0) return;  // a folder of someone else's: nobody here can remove it either
  }
  if (fd_ < 0)
    throw util::UserError(path + ": cannot open (" + std::strerror(errno) + ")");
  if (::flock(fd_, LOCK_SH | LOCK_NB) != 0) {
    ::close(fd_);
    fd_ = -1;
    throw util::UserError("the build " + dir + " is being removed (renderaudit builds remove); " +
                          "build it again when that is done");
  }
  // A removal may have renamed the folder away between the open and the lock.
  if (!same_file(fd_, path) || !fs::is_regular_file(rundir::build_record_path(dir), ec)) {
    ::close(fd_);
    fd_ = -1;
    throw util::UserError(gone);
  }
}

BuildInUse::~BuildInUse() {
  if (fd_ >= 0) ::close(fd_);
}

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
    else if (rundir::is_build_folder(e.path().string()))
      u.builds += bytes;
  }
  struct stat st {};
  if (::stat(cache.c_str(), &st) == 0) u.total += std::uintmax_t(st.st_blocks) * 512;
  return u;
}

bool build_drawn_with_now(const std::string& dir) {
  const int fd = lock_for_removal(dir, false);
  if (fd >= 0) {
    ::close(fd);
    return false;
  }
  return errno == EWOULDBLOCK;
}

std::string build_in_use_by(const std::string& dir) {
  std::string source;
  try {
    const rundir::BuildRecord b = rundir::read_build_record(dir);
    if (b.origin != "source") return "";
    source = b.source;
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
  // What earlier removals left: no longer builds, only their bytes. A removal running now holds
  // its folder's use-lock file, or has deleted it and is about to finish.
  for (const auto& e : fs::directory_iterator(cache, ec)) {
    if (!starts_with(e.path().filename().string(), kRemovingPrefix)) continue;
    const std::string aside = e.path().string();
    std::error_code lock_ec;
    if (fs::exists(BuildInUse::lock_path(aside), lock_ec)) {
      const int fd = lock_for_removal(aside, false);
      if (fd < 0) continue;  // a removal running now
      std::error_code del;
      delete_aside(aside, del);
      ::close(fd);
    } else {
      std::error_code del;
      fs::remove_all(aside, del);
    }
  }

  // A build is its folder: PLATFORM@FOLDER draws it, whatever its build.json calls it.
  const std::vector<rundir::BuildRecord> builds = rundir::list_cached_builds(cache);
  std::vector<std::string> held;
  for (const rundir::BuildRecord& b : builds) held.push_back(fs::path(b.dir).filename().string());
  std::vector<std::string> wanted, unknown;
  for (const std::string& name : names)
    if (std::find(wanted.begin(), wanted.end(), name) == wanted.end()) wanted.push_back(name);
  for (const std::string& name : wanted)
    if (std::find(held.begin(), held.end(), name) == held.end()) unknown.push_back(name);
  if (!unknown.empty()) {
    std::string list, missing;
    for (const std::string& h : held) list += (list.empty() ? "" : ", ") + h;
    for (const std::string& u : unknown) missing += (missing.empty() ? "'" : ", '") + u + "'";
    throw util::UserError(
        "builds remove: no build " + missing + " in " + cache + "; " +
        (held.empty() ? std::string("the cache holds no builds") : "it holds " + list) +
        " (nothing was removed)");
  }
  for (const std::string& name : wanted)
    if (const std::string why = build_in_use_by(cache + "/" + name); !why.empty())
      throw util::UserError("builds remove: " + name + " is in use: " + why +
                            ", which may build or draw with it; wait for it to finish (nothing "
                            "was removed)");
  // Every build locked before any is touched: one drawn with now stops the whole request.
  std::vector<int> locks;
  const auto release = [&] {
    for (int fd : locks) ::close(fd);
    locks.clear();
  };
  for (const std::string& name : wanted) {
    const std::string dir = cache + "/" + name;
    const int fd = lock_for_removal(dir, true);
    if (fd < 0) {
      const int err = errno;
      release();
      if (err == EWOULDBLOCK)
        throw util::UserError("builds remove: " + name +
                              " is in use: a process draws with it now (a watch night, a "
                              "bisection, a build that reused it); wait for it to finish "
                              "(nothing was removed)");
      throw util::UserError("builds remove: cannot lock " + BuildInUse::lock_path(dir) + " (" +
                            std::strerror(err) + "; nothing was removed)");
    }
    locks.push_back(fd);
  }

  std::vector<RemovedBuild> removed;
  std::string failed;
  for (std::size_t i = 0; i < wanted.size(); ++i) {
    const std::string& name = wanted[i];
    const std::string dir = cache + "/" + name;
    const std::string aside =
        cache + "/" + kRemovingPrefix + name + "-" + std::to_string(::getpid());
    RemovedBuild r{name, disk_usage(dir), ""};
    // One rename takes it out of the cache; only then are its files deleted.
    fs::rename(dir, aside, ec);
    if (ec) {
      failed += "\ncannot move " + dir + " aside (" + ec.message() + "); it is still a build";
      continue;
    }
    if (!delete_aside(aside, ec)) r.left = aside + " (" + ec.message() + ")";
    removed.push_back(r);
  }
  release();
  if (!failed.empty()) {
    std::string done;
    for (const RemovedBuild& r : removed) done += (done.empty() ? "" : ", ") + r.name;
    throw util::UserError("builds remove: " + (done.empty() ? "nothing was removed" : "removed " + done) +
                          ", but:" + failed);
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

}  // namespace ra::builds
