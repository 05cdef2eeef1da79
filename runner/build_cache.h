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
// held by a build, bisection or night now (lock_source_tree, source_build.h) may be drawn with or
// rebuilt by that process until it ends.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace ra::runner {

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

// Who holds the source tree of the build folder `dir` now ("process P (bisect) on host H since
// T"), or "" when nobody does or the build is not from a source tree.
std::string build_in_use_by(const std::string& dir);

struct RemovedBuild {
  std::string name;
  std::uintmax_t bytes = 0;  // disk usage freed
};

// Removes the builds `names` from the cache (empty: build_cache_dir()). Checks every name first
// and removes none when one fails: UserError when a name is not a build of the cache (naming the
// builds it holds) or when a build is in use (naming the process). Also deletes what earlier
// removals left (.removing-*).
std::vector<RemovedBuild> remove_builds(const std::string& cache,
                                        const std::vector<std::string>& names);

// "0 B", "512 B", "4.0 KiB", "119 MiB", "1.2 GiB": binary units, as `du -h` counts (its 119M is
// 119 MiB), 3 significant digits at most.
std::string size_text(std::uintmax_t bytes);

}  // namespace ra::runner
