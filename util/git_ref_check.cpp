#include "util/git_ref_check.h"

#include <algorithm>

namespace ra::util {

std::string commit_hash_problem(const std::string& s) {
  if (s.size() != 40 && s.size() != 64)
    return "must be a full commit hash (40 or 64 hexadecimal digits), not " +
           std::to_string(s.size()) + " characters";
  for (const char c : s)
    if (!((c >= '0' && c <= '9') || (c >= 'a' && c <= 'f')))
      return "must be a full commit hash (lower-case hexadecimal digits only)";
  return "";
}

std::string branch_name_problem(const std::string& s) {
  if (s.empty()) return "must be a branch name, not empty";
  if (s[0] == '-')
    return "must be a branch name, never starting with '-' (git would read an option)";
  if (s == "@") return "must be a branch name, not '@'";
  for (const char c : s) {
    const auto u = static_cast<unsigned char>(c);
    if (u < 0x20 || u == 0x7f) return "must be a branch name, without control characters";
    if (std::string(" ~^:?*[\\").find(c) != std::string::npos)
      return std::string("must be a branch name, without '") + c + "'";
  }
  if (s.find("..") != std::string::npos) return "must be a branch name, without '..'";
  if (s.find("@{") != std::string::npos) return "must be a branch name, without '@{'";
  if (s.find("//") != std::string::npos) return "must be a branch name, without '//'";
  if (s.back() == '/' || s.back() == '.')
    return "must be a branch name, not ending with '/' or '.'";
  for (std::size_t start = 0; start <= s.size();) {
    const std::size_t end = std::min(s.find('/', start), s.size());
    const std::string part = s.substr(start, end - start);
    if (part.empty() || part[0] == '.')
      return "must be a branch name, no part of it starting with '.'";
    if (part.size() >= 5 && part.compare(part.size() - 5, 5, ".lock") == 0)
      return "must be a branch name, no part of it ending with '.lock'";
    start = end + 1;
  }
  return "";
}

}  // namespace ra::util
