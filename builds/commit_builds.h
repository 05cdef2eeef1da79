// Several commits built at once, each by `renderaudit builds build SLOT` (builds/source_build.h)
// in a worktree of its own (builds/build_slots.h), into the one build cache: the builds of a
// bisection round (`bisect --ways K`). Where they run is the implementation's: here, as child
// processes that share this machine's cores (local_commit_builds), or as the tasks of a Slurm job
// array (builds/slurm_builds.h). The caller starts the round, takes the builds as they end, and
// cancels those another result made needless; the build itself is then read from the cache
// (cached_source_build).
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "builds/source_build.h"

namespace ra::builds {

// How one build of the round ended.
struct CommitBuildEnd {
  std::size_t index = 0;  // in the list given to start()
  bool ok = false;
  std::string error;      // why it failed, in the build's words
  double seconds = 0;     // from the start of the round to its end
  int attempts = 1;       // Slurm: 2 when the task was run again
};

class CommitBuilds {
 public:
  virtual ~CommitBuilds() = default;
  // Starts a build of each slot (a worktree at its commit), as round `round` of the bisection.
  virtual void start(const std::vector<std::string>& slots, std::size_t round) = 0;
  // The next build to end (waiting for it), in the order they end; none when all have ended or
  // were cancelled. Throws util::Interrupted on a signal, every build of the round stopped first.
  virtual std::optional<CommitBuildEnd> wait_next() = 0;
  // Stops build `index` (its whole process group, or its Slurm task); it is never returned.
  virtual void cancel(std::size_t index) = 0;
  // Stops every build still running (also done when the object ends).
  virtual void cancel_all() = 0;
};

// The `renderaudit builds build` command line that builds `slot` as `o` asks, with `jobs` ninja
// jobs, unprobed (the bisection draws with it), incremental when `o.incremental`.
std::vector<std::string> builds_build_argv(const std::string& program, const SourceBuildOptions& o,
                                           const std::string& slot, unsigned jobs);

// The builds as child processes of this one, each in its own process group with ninja -j `jobs`
// (the machine's cores shared out: max(1, cores / K)); logs in `log_dir`.
std::unique_ptr<CommitBuilds> local_commit_builds(const SourceBuildOptions& o, unsigned jobs,
                                                  const std::string& log_dir);

// The number of ninja jobs each of `k` builds gets of `cores`: max(1, cores / k).
unsigned jobs_per_build(unsigned cores, std::size_t k);

}  // namespace ra::builds
