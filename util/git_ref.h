// Commits and branch names read from a state file (bisect.json, watch.json) before they reach git:
// a value that git would read as an option (`--orphan=x`, `--output=FILE`) or as something other
// than the commit or branch it stands for is refused here, and what passes still goes to git after
// `--end-of-options` or before `--`, so that no check has to be perfect on its own.
#pragma once

#include <string>

namespace ra::util {

// Empty when `s` is a full commit hash as git prints it: 40 (SHA-1) or 64 (SHA-256) lower-case
// hexadecimal digits; else what is wrong, in words ("must be a full commit hash ...").
std::string commit_hash_problem(const std::string& s);

// Empty when `s` is a branch name `git check-ref-format --branch` accepts and that no git command
// reads as an option: not empty, no leading '-', no component starting with '.' or ending with
// ".lock", no "..", "@{", "//", no space, control character or any of ~ ^ : ? * [ \, not ending
// with '/' or '.', not "@"; else what is wrong, in words.
std::string branch_name_problem(const std::string& s);

}  // namespace ra::util
