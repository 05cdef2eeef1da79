// Progress on stderr, as a rewritten line or whole lines (see the header).
#include "util/progress_line.h"

#include <unistd.h>

#include <cstdio>

namespace ra::util {

ProgressLine::ProgressLine() : terminal_(::isatty(2)) {}

ProgressLine::ProgressLine(bool terminal) : terminal_(terminal) {}

std::string ProgressLine::text_of_show(const std::string& text) const {
  // "\033[K" erases to the end of the line: a shorter line leaves nothing of the longer one.
  return terminal_ ? "\r" + text + "\033[K" : text + "\n";
}

void ProgressLine::show(const std::string& text) {
  std::fputs(text_of_show(text).c_str(), stderr);
  shown_ = terminal_;
}

void ProgressLine::end() {
  if (shown_) std::fputc('\n', stderr);
  shown_ = false;
}

}  // namespace ra::util
