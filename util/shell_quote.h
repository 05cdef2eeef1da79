// Words of a command printed or written for a person to paste into a POSIX shell (bash, sh): every
// value that reaches such a command goes through shell_quote, so that a path holding spaces, a
// newline, quotes or `$(...)` is one word and runs nothing.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace ra::util {

// `word` as one shell word: bare when it holds only letters, digits and _ - . / = : , + @ % (none
// of them special to the shell where a word starts or inside one), else in single quotes, each '
// written as '\'' (a single-quoted string holds every other byte as it is, newlines included). The
// empty word is ''.
std::string shell_quote(std::string_view word);

// The words quoted and joined by spaces (a first word holding '=' always in quotes: bare, it would
// be an assignment). Every word is quoted, the first too: a program name that is already one
// shell word (program_for_commands()) goes before the result instead.
std::string shell_command(const std::vector<std::string>& words);

}  // namespace ra::util
