// A command's standard output, and how a failed write to it ends the command. A reader that stops
// early (`renderaudit records RUN | head -3`, `| grep -m1`, a pager quit) is normal use: the
// command ends quietly, keeping its exit code, as `cat` and `grep` end when their reader is gone.
// Any other failed write (a full disk, ENOSPC; an I/O error) is an error that names its cause:
// the output is not what the command meant to write.
//
// The process ignores SIGPIPE (app/main.cpp), so a closed pipe reaches the writer as EPIPE rather
// than killing it (exit 141), and the two cases are told apart here.
#pragma once

#include <exception>
#include <string>
#include <string_view>

namespace ra::util {

// Thrown by write_stdout when the reader of standard output has gone: nothing more can reach it,
// so a streaming command stops at once instead of producing the rest for nobody.
class StdoutReaderGone : public std::exception {
 public:
  const char* what() const noexcept override { return "the reader of standard output has gone"; }
};

// Writes all of `bytes` to file descriptor 1 (short writes and EINTR retried), after flushing C's
// `stdout` and std::cout so that what they hold comes first. Throws StdoutReaderGone on EPIPE and
// UserError "cannot write `what` to standard output (STRERROR)" on any other failure.
void write_stdout(std::string_view bytes, const std::string& what = "the output");

// How the writes to standard output went, checked once at the end of a command: C's `stdout` and
// std::cout flushed, and their error flags read.
enum class StdoutState { kWritten, kReaderGone, kFailed };
struct StdoutOutcome {
  StdoutState state = StdoutState::kWritten;
  // kFailed: the errno of the failed flush; when an earlier write failed (its errno is lost), the
  // cause found after the fact (ENOSPC on a device or file system that takes nothing more), else 0
  int error = 0;
};
StdoutOutcome finish_stdout();

// True when file descriptor 1 is a pipe or socket whose reading end is closed (poll reports
// POLLERR or POLLHUP on it): a write there fails with EPIPE.
bool stdout_reader_gone();

}  // namespace ra::util
