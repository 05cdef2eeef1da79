// Commits and branch names from state files (git_ref.h): what git itself accepts passes, what git
// would read as an option or another thing is refused; compared with `git check-ref-format`.
#include "util/git_ref.h"

#include <gtest/gtest.h>

#include "util/child_process.h"

namespace ra::util {
namespace {

TEST(GitRef, FullHashesPassAndEverythingElseIsRefused) {
  EXPECT_EQ(commit_hash_problem(std::string(40, 'a')), "");
  EXPECT_EQ(commit_hash_problem("0123456789abcdef0123456789abcdef01234567"), "");
  EXPECT_EQ(commit_hash_problem(std::string(64, 'f')), "");
  for (const std::string bad :
       {std::string(), std::string(39, 'a'), std::string(41, 'a'), std::string(40, 'A'),
        std::string("--output=/tmp/x") + std::string(25, 'a'), std::string(39, 'a') + "g",
        std::string("HEAD"), std::string(40, 'a') + "\n"})
    EXPECT_NE(commit_hash_problem(bad), "") << bad;
}

// Whether git accepts `name` as a branch name.
bool git_accepts(const std::string& name) {
  ChildSpec spec;
  spec.argv = {"git", "check-ref-format", "--branch", name};
  spec.capture_output = true;
  spec.stdin_null = true;
  return run_program(spec).exited_ok();
}

TEST(GitRef, BranchNamesAgreeWithGitAndNeverLookLikeOptions) {
  for (const std::string good : {"main", "feature/x", "release-25.1", "a.b", "user@host", "v1_2"}) {
    EXPECT_EQ(branch_name_problem(good), "") << good;
    EXPECT_TRUE(git_accepts(good)) << good;
  }
  // Refused here; git refuses all but the ones that start with '-' (which git would take for an
  // option on a command line).
  for (const std::string bad :
       {"", "-x", "--orphan=pwned", "a..b", "a b", "a~1", "a^", "a:b", "a?", "a*", "a[", "a\\b",
        "a/", "a.", ".a", "a/.b", "a.lock", "a/b.lock", "a//b", "a@{1}", "@", "a\nb",
        "a\x7f" "b"}) {
    EXPECT_NE(branch_name_problem(bad), "") << bad;
    if (!bad.empty() && bad[0] != '-' && bad[0] != '@') EXPECT_FALSE(git_accepts(bad)) << bad;
  }
}

}  // namespace
}  // namespace ra::util
