// Shell words for printed commands (see the header).
#include "util/shell_quote.h"

namespace ra::util {
namespace {

std::string single_quoted(std::string_view word) {
  std::string out = "'";
  for (char c : word) {
    if (c == '\'')
      out += "'\\''";
    else
      out += c;
  }
  return out + "'";
}

}  // namespace

std::string shell_quote(std::string_view word) {
  constexpr std::string_view kBare =
      "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-./=:,+@%";
  if (!word.empty() && word.find_first_not_of(kBare) == std::string_view::npos)
    return std::string(word);
  return single_quoted(word);
}

std::string shell_command(const std::vector<std::string>& words) {
  std::string out;
  for (const std::string& w : words) {
    if (out.empty() && w.find('=') != std::string::npos) {
      out = single_quoted(w);  // a first word NAME=VALUE would be an assignment
      continue;
    }
    if (!out.empty()) out += ' ';
    out += shell_quote(w);
  }
  return out;
}

}  // namespace ra::util
