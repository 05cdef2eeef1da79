// Progress on stderr, written for whoever reads it: on a terminal one line rewritten in place (a
// person watches it move), elsewhere (a log, a pipe, CI) whole lines, since a log keeps every
// carriage return and a rewritten line would pile up in it. The callers decide how often and
// what; this only decides how, so that a run's progress and a plot's read alike.
#pragma once

#include <string>

namespace ra::util {

class ProgressLine {
 public:
  ProgressLine();  // a terminal when stderr is one
  explicit ProgressLine(bool terminal);
  bool terminal() const { return terminal_; }
  // `text` (no line end) as the progress now: on a terminal it replaces the line shown, and the
  // rest of the old line is erased; elsewhere it is a line of its own.
  void show(const std::string& text);
  // On a terminal, ends the line shown so that what follows starts on a line of its own; nothing
  // elsewhere, or when nothing was shown.
  void end();
  // What show and end write, for the tests.
  std::string text_of_show(const std::string& text) const;

 private:
  bool terminal_;
  bool shown_ = false;  // a line is shown on the terminal and not ended yet
};

}  // namespace ra::util
