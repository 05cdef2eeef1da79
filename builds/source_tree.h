// A Mesa source tree that builds come from (builds/source_build.h): where it stands (a git commit,
// clean or with changes and untracked files, or the content of a tree without git), its
// one-writer lock, and its checkout at a commit for a build of that commit alone.
//
// One writer per tree: a build, bisection or night holds the tree's lock (util/dir_lock.h on the
// git folder, or on the tree itself without git) from checkout to install, so a second one is
// refused, naming the holder, rather than checking out commits under the first.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "util/dir_lock.h"

namespace ra::builds {

// Takes the one-writer lock of a source tree for `what` ("bisect", "builds build", "watch"), or
// throws UserError naming the process that holds it.
std::unique_ptr<util::DirLock> lock_source_tree(const std::string& source, const std::string& what);

// Where a source tree stands: git commit (and whether uncommitted changes make it another
// source), or the version of an unpacked source package.
struct SourceIdentity {
  std::string source;        // the tree's folder, canonical
  bool git = false;
  bool dirty = false;        // git: tracked files differ from the commit
  std::vector<std::string> untracked;  // git: files it does not track nor ignore (the first 4)
  std::size_t untracked_count = 0;     // all of them
  bool clean() const { return git && !dirty && untracked.empty(); }  // the tree is its commit
  std::string commit;        // full hash ("" when not git)
  std::string subject, date; // the commit's
  std::string version;       // the tree's VERSION file ("25.1.0-devel")
  std::string debian_version;  // debian/changelog's first entry, when present
  std::string patches;       // debian/patches/series (the patches a source package applies)
  std::string content_hash;  // not git: FNV-1a 64 of every file's path and bytes (hex)
};
SourceIdentity identify_source(const std::string& source_dir);

// FNV-1a 64 (hex) of every regular file and symbolic link under `dir` (relative path and bytes,
// in path order), leaving out `.git` and the lock file: the identity of a tree without git, so
// that applying a patch makes it another source.
std::string tree_content_hash(const std::string& dir);

// Checks the git tree `source` (standing at `id`) out at `ref` for a build of that commit alone
// and returns where to check it out again after the build: its branch, else its commit. A tree
// that is not git, has uncommitted changes or untracked files, or lacks `ref` is refused
// (UserError) before anything changes. `id` is then the commit's.
std::string check_out_for_build(const std::string& source, const std::string& ref,
                                SourceIdentity& id);

// A text file of a tree (VERSION, meson.options) with its trailing white space off; "" when it is
// not a regular file.
std::string read_tree_file(const std::string& path);

}  // namespace ra::builds
