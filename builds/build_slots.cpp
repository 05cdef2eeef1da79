// Worktrees for builds at once (see the header).
#include "builds/build_slots.h"

#include <filesystem>

#include "builds/git_command.h"
#include "util/errors.h"

namespace fs = std::filesystem;

namespace ra::builds {
namespace {

// A slot unregistered from git and its files gone, whatever state it was left in.
void remove_slot(const std::string& source, const std::string& path) {
  std::error_code ec;
  git(source, {"worktree", "unlock", path});
  if (!git(source, {"worktree", "remove", "--force", "--force", path}).ok) fs::remove_all(path, ec);
}

}  // namespace

BuildSlots::BuildSlots(const std::string& source) : source_(source) {
  const GitResult dir = git(source, {"rev-parse", "--absolute-git-dir"});
  if (!dir.ok || dir.out.empty())
    throw util::UserError("bisect: " + source + " is not a git checkout; --ways builds in git worktrees");
  folder_ = dir.out + "/renderaudit-bisect";
  std::error_code ec;
  if (fs::is_directory(folder_, ec))
    for (const fs::directory_entry& e : fs::directory_iterator(folder_, ec))
      if (e.path().filename().string().rfind("slot-", 0) == 0) remove_slot(source_, e.path().string());
  git(source_, {"worktree", "prune"});
  fs::create_directories(folder_, ec);
  if (ec) throw util::UserError("bisect: cannot create " + folder_ + " (" + ec.message() + ")");
}

BuildSlots::~BuildSlots() { remove_all(); }

std::string BuildSlots::path(std::size_t i) const { return folder_ + "/slot-" + std::to_string(i + 1); }

std::string BuildSlots::check_out(std::size_t i, const std::string& commit) {
  if (made_.size() <= i) made_.resize(i + 1, false);
  const std::string p = path(i);
  if (!made_[i]) {
    const GitResult r = git(source_, {"worktree", "add", "--quiet", "--detach", "--lock", "--reason",
                                      "renderaudit bisect", p, commit});
    if (!r.ok) throw util::UserError("bisect: git worktree add " + p + " failed:\n" + r.out);
    made_[i] = true;
    return p;
  }
  const GitResult r = git(p, {"checkout", "--quiet", "--detach", commit, "--"});
  if (!r.ok) throw util::UserError("bisect: cannot check out " + commit + " in " + p + ":\n" + r.out);
  return p;
}

void BuildSlots::remove_all() {
  for (std::size_t i = 0; i < made_.size(); ++i)
    if (made_[i]) remove_slot(source_, path(i));
  made_.clear();
  git(source_, {"worktree", "prune"});
}

}  // namespace ra::builds
