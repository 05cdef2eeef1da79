// The worktrees in which a bisection builds several commits at once (`bisect --ways K`).
//
// Slot N is a git worktree of the source at GIT_DIR/renderaudit-bisect/slot-N: it shares the
// source's object store (nothing copied) and lies on the same file system, so a Slurm node that
// sees the object store sees the slots. Each is added with --lock (`git worktree prune` never drops
// a slot while a build may use it) and detached at the commit it builds. A slot keeps its path for
// the whole bisection, so it keeps one incremental meson build folder (keyed by the tree's path,
// builds/source_build.h) and its next commit recompiles only what changed, as the tree itself
// does with --ways 1. The slots are removed when BuildSlots ends, however the bisection ends; a
// bisection killed with -9 leaves them, and the next BuildSlots of the tree removes them first.
// The caller holds the tree's one-writer lock (lock_source_tree) throughout.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace ra::builds {

class BuildSlots {
 public:
  // The slots' folder of `source` (a git checkout) emptied of an earlier bisection's slots.
  explicit BuildSlots(const std::string& source);
  ~BuildSlots();  // every slot removed and unregistered
  BuildSlots(const BuildSlots&) = delete;
  BuildSlots& operator=(const BuildSlots&) = delete;

  // Slot `i` (0-based), added on first use, detached at `commit`; its path. Throws UserError when
  // git refuses.
  std::string check_out(std::size_t i, const std::string& commit);
  // GIT_DIR/renderaudit-bisect: the slots, and the rounds' logs and scripts (runs/).
  const std::string& folder() const { return folder_; }
  // Removes every slot now (also done by the destructor).
  void remove_all();

 private:
  std::string path(std::size_t i) const;
  std::string source_, folder_;
  std::vector<bool> made_;
};

}  // namespace ra::builds
