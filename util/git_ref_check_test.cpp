#include "util/git_ref_check.h"

#include <gtest/gtest.h>

namespace ra::util {
namespace {

TEST(GitRefCheck, AFullHashIsAccepted) {
  EXPECT_EQ(commit_hash_problem(std::string(40, 'a')), "");
  EXPECT_EQ(commit_hash_problem("0123456789abcdef0123456789abcdef01234567"), "");
  EXPECT_EQ(commit_hash_problem(std::string(64, '0')), "");
}

// A state file edited by hand or by an attacker: every one of these would reach git as an option
// or as a revision expression, not as the commit the night recorded.
TEST(GitRefCheck, AnythingButAFullHashIsRefused) {
  for (const std::string& bad :
       {std::string(), std::string("--output=/tmp/x"), std::string("HEAD"), std::string(39, 'a'),
        std::string(41, 'a'), std::string(40, 'g'), std::string(40, 'A'),
        std::string(39, 'a') + "\n", std::string("-") + std::string(39, 'a'), std::string(63, 'b')})
    EXPECT_NE(commit_hash_problem(bad), "") << bad;
}

TEST(GitRefCheck, OrdinaryBranchNamesAreAccepted) {
  for (const std::string ok : {"main", "staging/25.1", "feature-x", "v1.0_rc", "a@b", "x.y"})
    EXPECT_EQ(branch_name_problem(ok), "") << ok;
}

// What `git check-ref-format --branch` refuses, and names starting with '-' (options).
TEST(GitRefCheck, NamesGitRefusesOrReadsAsOptionsAreRefused) {
  for (const std::string bad : {"",       "-",          "--orphan=pwned",
                                "-b",     "@",          "a..b",
                                "a b",    "a\nb",       "a~1",
                                "a^",     "a:b",        "a?",
                                "a*",     "a[",         "a\\b",
                                "x@{1}",  "a//b",       "a/",
                                "a.",     ".a",         "a/.b",
                                "a.lock", "a/b.lock/c", "/a"})
    EXPECT_NE(branch_name_problem(bad), "") << bad;
}

}  // namespace
}  // namespace ra::util
