// Checks of commits and branch names before they reach git (see the header).
#include "util/git_ref.h"

#include <algorithm>

namespace ra::util {

std::string commit_hash_problem(const std::string& s) {
  const bool hex = !s.empty() && s.find_first_not_of("0123456789abcdef") == std::string::npos;
  if (hex && (s.size() == 40 || s.size() == 64)) return "";
  return "must be a full commit hash (40 or 64 lower-case hexadecimal digits)";
}

std::string branch_name_problem(const std::string& s) {
  const std::string rule = "must be a branch name (git check-ref-format --branch)";
  if (s.empty()) return rule + ", not empty";
  if (s[0] == '-') return rule + " that does not start with '-'";
  if (s == "@") return rule + ", not '@'";
  for (const unsigned char c : s)
    if (c < 0x20 || c == 0x7f || c == ' ' || c == '~' || c == '^' || c == ':' || c == '?' ||
        c == '*' || c == '[' || c == '\\')
      return rule + ": no spaces, control characters or any of ~ ^ : ? * [ \\";
  if (s.find("..") != std::string::npos || s.find("@{") != std::string::npos ||
      s.find("//") != std::string::npos)
    return rule + ": no '..', '@{' or '//'";
  if (s.back() == '/' || s.back() == '.') return rule + ": no '/' or '.' at the end";
  // Each slash-separated component: not starting with '.', not ending with ".lock".
  for (std::size_t at = 0; at <= s.size();) {
    const std::size_t end = std::min(s.find('/', at), s.size());
    const std::string part = s.substr(at, end - at);
    if (part.empty() || part[0] == '.' ||
        (part.size() >= 5 && part.compare(part.size() - 5, 5, ".lock") == 0))
      return rule + ": no part that is empty, starts with '.' or ends with '.lock'";
    at = end + 1;
  }
  return "";
}

}  // namespace ra::util
