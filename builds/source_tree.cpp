// A Mesa source tree: where it stands, its one-writer lock, its checkout for a build (see the
// header).
#include "builds/source_tree.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <memory>

#include "builds/git_command.h"
#include "util/atomic_file.h"
#include "util/errors.h"
#include "util/fnv1a.h"

namespace fs = std::filesystem;

namespace ra::builds {
namespace {

// git's output in `dir`, trimmed; `ok` (when given) says whether git exited 0.
std::string git_text(const std::string& dir, std::vector<std::string> args, bool* ok = nullptr) {
  const GitResult r = git(dir, std::move(args));
  if (ok) *ok = r.ok;
  return r.out;
}

// "1 untracked file (meson.options)", "5 untracked files (a, b, c, d, ...)".
std::string untracked_text(const std::vector<std::string>& files, std::size_t count) {
  std::string shown;
  for (const std::string& f : files) shown += (shown.empty() ? "" : ", ") + f;
  if (count > files.size()) shown += ", ...";
  return std::to_string(count) + (count == 1 ? " untracked file (" : " untracked files (") +
         shown + ")";
}

}  // namespace

std::string read_tree_file(const std::string& path) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) return "";
  std::string s = util::read_file(path);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.pop_back();
  return s;
}

SourceIdentity identify_source(const std::string& source_dir) {
  SourceIdentity id;
  id.source = source_dir;
  bool ok = false;
  const std::string top = git_text(source_dir, {"rev-parse", "--show-toplevel"}, &ok);
  std::error_code ec;
  if (ok && fs::equivalent(top, source_dir, ec)) {
    id.git = true;
    id.commit = git_text(source_dir, {"rev-parse", "HEAD"});
    const std::string info = git_text(source_dir, {"log", "-1", "--format=%cI%n%s", "HEAD"});
    id.date = info.substr(0, info.find('\n'));
    id.subject = info.find('\n') == std::string::npos ? "" : info.substr(info.find('\n') + 1);
    id.dirty = !git_text(source_dir, {"status", "--porcelain", "--untracked-files=no"}).empty();
    // What meson reads besides the commit's files: anything git neither tracks nor ignores.
    const std::string others =
        git_text(source_dir, {"ls-files", "--others", "--exclude-standard", "--directory",
                              "--no-empty-directory"});
    id.untracked_count = 0;
    for (std::size_t at = 0; at < others.size();) {
      const std::size_t nl = std::min(others.find('\n', at), others.size());
      if (nl > at && id.untracked.size() < 4) id.untracked.push_back(others.substr(at, nl - at));
      if (nl > at) ++id.untracked_count;
      at = nl + 1;
    }
  }
  id.version = read_tree_file(source_dir + "/VERSION");
  const std::string changelog = read_tree_file(source_dir + "/debian/changelog");
  if (const auto open = changelog.find('('); open != std::string::npos)
    id.debian_version = changelog.substr(open + 1, changelog.find(')', open) - open - 1);
  id.patches = read_tree_file(source_dir + "/debian/patches/series");
  if (!id.git) id.content_hash = tree_content_hash(source_dir);
  return id;
}

std::string tree_content_hash(const std::string& dir) {
  std::vector<std::string> files;
  std::error_code ec;
  for (fs::recursive_directory_iterator
           it(dir, fs::directory_options::skip_permission_denied, ec), end;
       !ec && it != end; it.increment(ec)) {
    const fs::path rel = it->path().lexically_relative(dir);
    if (rel == ".git" || rel == fs::path(util::DirLock::lock_path(dir)).filename()) {
      if (it->is_directory(ec)) it.disable_recursion_pending();
      continue;
    }
    if (it->is_symlink(ec) || it->is_regular_file(ec)) files.push_back(rel.string());
  }
  std::sort(files.begin(), files.end());
  util::Fnv1a64 h;
  std::vector<char> buf(1 << 16);
  for (const std::string& f : files) {
    h.add(f.data(), f.size());
    h.add("\0", 1);
    const fs::path path = fs::path(dir) / f;
    if (fs::is_symlink(path, ec)) {
      const std::string target = fs::read_symlink(path, ec).string();
      h.add("link ", 5);
      h.add(target.data(), target.size());
      continue;
    }
    std::ifstream in(path, std::ios::binary);
    while (in) {
      in.read(buf.data(), std::streamsize(buf.size()));
      if (in.gcount() > 0) h.add(buf.data(), std::size_t(in.gcount()));
    }
    h.add("\0", 1);
  }
  return util::hex64(h.value);
}

std::unique_ptr<util::DirLock> lock_source_tree(const std::string& source,
                                                const std::string& what) {
  bool ok = false;
  const std::string git_dir = git_text(source, {"rev-parse", "--absolute-git-dir"}, &ok);
  // The git folder holds the lock of a checkout (no untracked file in the tree); a tree without
  // git holds its own.
  return std::make_unique<util::DirLock>(
      ok && !git_dir.empty() ? git_dir : source, what,
      "one build or bisection at a time checks out commits in " + source +
          "; wait for it to finish");
}

std::string check_out_for_build(const std::string& source, const std::string& ref,
                                SourceIdentity& id) {
  if (!id.git)
    throw util::UserError("builds build: --ref needs a git checkout; " + source + " is not one");
  if (id.dirty)
    throw util::UserError("builds build: " + source +
                          " has uncommitted changes; commit or stash them before --ref");
  // A build of a commit is that commit's files and nothing else.
  if (!id.untracked.empty())
    throw util::UserError("builds build: " + source + " has " +
                          untracked_text(id.untracked, id.untracked_count) +
                          "; a build of " + ref +
                          " would see it and be kept as that commit's: `git -C " + source +
                          " clean -n -d` lists them, `git stash -u` or `git clean -fd` removes "
                          "them");
  bool ok = false;
  const std::string commit = git_text(
      source, {"rev-parse", "--verify", "--quiet", "--end-of-options", ref + "^{commit}"}, &ok);
  if (!ok || commit.empty())
    throw util::UserError("builds build: '" + ref + "' is not a commit of " + source);
  bool on_branch = false;
  std::string restore_ref = git_text(source, {"symbolic-ref", "-q", "--short", "HEAD"}, &on_branch);
  if (!on_branch) restore_ref = id.commit;
  if (commit != id.commit) {
    git_text(source, {"checkout", "-q", "--detach", commit}, &ok);
    if (!ok) throw util::UserError("builds build: cannot check out " + ref + " in " + source);
  }
  id = identify_source(source);
  return restore_ref;
}

}  // namespace ra::builds
