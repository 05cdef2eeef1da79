// Checking a git commit hash or branch name read from a state file (a night's watch.json, a
// bisection's bisect.json) before it reaches git: such a file is input like any other, and a value
// such as `--output=FILE` or `--orphan=x` would be read by git as an option. A caller checks the
// value here and still passes it after `--end-of-options` (or `--`), so that neither a bad check
// nor a git that parses differently turns it into an option.
#pragma once

#include <string>

namespace ra::util {

// "" when `s` is a full commit hash: 40 (SHA-1) or 64 (SHA-256) hexadecimal digits, lower case as
// git writes them; else what is wrong, in words ("must be 40 or 64 hexadecimal digits").
std::string commit_hash_problem(const std::string& s);

// "" when `s` is a branch name git accepts (`git check-ref-format --branch`'s rules for a name
// without @{-N}): not empty, never starting with '-', no control character, space, ~ ^ : ? * [ \,
// no "..", "@{" or "//", no component starting with '.' or ending with ".lock", not ending with
// '/' or '.', not "@"; else what is wrong, in words.
std::string branch_name_problem(const std::string& s);

}  // namespace ra::util
