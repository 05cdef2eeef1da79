// The build cache's housekeeping (`renderaudit builds list`, `renderaudit builds remove`): what it
// holds on disk, and the removal of builds.
//
// Sizes are disk usage as du counts it: the blocks allocated to every file and folder under a
// folder (symbolic links not followed), a file with several hard links counted once.
//
// A build is removed in two steps: one rename of CACHE/NAME to CACHE/.removing-NAME-PID, then the
// deletion of that folder. A crash between the two or during the deletion leaves a hidden folder
// that no listing, run or bisection takes for a build; the next `builds remove` deletes it. A build
// is never half removed under its own name.
//
// A build in use is refused: a source build (`builds build`, bisect, watch) whose source tree is
// held by a build, bisection or night now (lock_source_tree, source_tree.h) may be drawn with or
// rebuilt by that process until it ends; and a build a process draws with holds BuildInUse, a
// shared lock (flock) on BUILD/.in-use that `builds remove` must take exclusively. The lock is
// the kernel's, so a user killed however it dies holds nothing. A removal holds its exclusive lock
// on the file (which moves with the folder) until the folder is gone, and deletes that file last,
// so that a second removal's clean-up of unfinished removals leaves a running one alone.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace ra::builds {

// A build held for drawing: `builds remove` refuses it while this object lives (any number of
// users share it).
class BuildInUse {
 public:
  // Takes the shared lock of the build folder `dir`. UserError when the folder holds no build
  // (removed, or never built) or a removal holds it now. In a folder this process cannot write
  // (another user's cache), nothing is taken: such a build cannot be removed from here either.
  explicit BuildInUse(const std::string& dir);
  ~BuildInUse();
  BuildInUse(const BuildInUse&) = delete;
  BuildInUse& operator=(const BuildInUse&) = delete;

  static std::string lock_path(const std::string& dir);  // DIR/.in-use

 private:
  int fd_ = -1;
};

// Bytes allocated on disk to `path` and everything under it (0 when it does not exist).
std::uintmax_t disk_usage(const std::string& path);

// What the cache holds on disk.
struct CacheUsage {
  std::uintmax_t total = 0;        // everything under the cache folder
  std::uintmax_t builds = 0;       // the build folders (with a build.json)
  std::uintmax_t incremental = 0;  // .incremental/: meson build folders kept between builds
  std::uintmax_t unfinished = 0;   // .fetch-*, .source-*, .removing-*: fetches, builds and
                                   // removals that did not finish (a crash, or one running now)
};
CacheUsage cache_usage(const std::string& cache);

// Whether a process holds BuildInUse on the build folder `dir` now. Takes nothing.
bool build_drawn_with_now(const std::string& dir);

// Who holds the source tree of the build folder `dir` now ("process P (bisect) on host H since
// T"), or "" when nobody does or the build is not from a source tree.
std::string build_in_use_by(const std::string& dir);

struct RemovedBuild {
  std::string name;
  std::uintmax_t bytes = 0;  // disk usage freed
  // Not empty when the build left the cache but its files could not all be deleted: the folder
  // they are in and why (the next removal deletes it).
  std::string left;
};

// Removes the builds `names` (folder names, as `builds list` shows them) from the cache (empty:
// build_cache_dir()). Checks every name first and removes none when one fails: UserError when a
// name is not a build folder of the cache (naming the builds it holds) or when a build is in use
// (a process holds its source tree or draws with it: BuildInUse). Also deletes what earlier
// removals left (.removing-*), but not a removal that is running now.
std::vector<RemovedBuild> remove_builds(const std::string& cache,
                                        const std::vector<std::string>& names);

// "0 B", "512 B", "4.0 KiB", "119 MiB", "1.2 GiB": binary units, as `du -h` counts (its 119M is
// 119 MiB), 3 significant digits at most.
std::string size_text(std::uintmax_t bytes);

}  // namespace ra::builds
