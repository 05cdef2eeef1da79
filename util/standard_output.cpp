// Standard output's writes and how they ended (see the header).
#include "util/standard_output.h"

#include <poll.h>
#include <sys/stat.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <iostream>

#include "util/errors.h"

namespace ra::util {
namespace {

[[noreturn]] void write_failed(int error, const std::string& what) {
  if (error == EPIPE || (error == 0 && stdout_reader_gone())) throw StdoutReaderGone();
  throw UserError("cannot write " + what + " to standard output (" +
                  std::strerror(error ? error : EIO) + ")");
}

// The cause of a write that failed before the last flush, when its errno is lost (C's stdio keeps
// only a flag): a write of nothing still fails on a device that refuses every write (/dev/full:
// ENOSPC), and a file on a file system without a free block was cut by a full disk. 0 when
// neither tells.
int stdout_failure_cause() {
  errno = 0;
  if (::write(STDOUT_FILENO, "", 0) < 0) return errno;
  struct stat st {};
  struct statvfs fs {};
  if (::fstat(STDOUT_FILENO, &st) == 0 && S_ISREG(st.st_mode) &&
      ::fstatvfs(STDOUT_FILENO, &fs) == 0 && fs.f_bavail == 0)
    return ENOSPC;
  return 0;
}

}  // namespace

bool stdout_reader_gone() {
  struct stat st {};
  if (::fstat(STDOUT_FILENO, &st) != 0 || !(S_ISFIFO(st.st_mode) || S_ISSOCK(st.st_mode)))
    return false;
  pollfd p{STDOUT_FILENO, POLLOUT, 0};
  return ::poll(&p, 1, 0) == 1 && (p.revents & (POLLERR | POLLHUP));
}

void write_stdout(std::string_view bytes, const std::string& what) {
  std::cout.flush();
  errno = 0;
  if (std::fflush(stdout) != 0 || std::ferror(stdout)) write_failed(errno, what);
  while (!bytes.empty()) {
    const ssize_t n = ::write(STDOUT_FILENO, bytes.data(), bytes.size());
    if (n < 0) {
      if (errno == EINTR) continue;
      write_failed(errno, what);
    }
    bytes.remove_prefix(std::size_t(n));
  }
}

StdoutOutcome finish_stdout() {
  std::cout.flush();
  errno = 0;
  const bool flushed = std::fflush(stdout) == 0;
  const int error = flushed ? 0 : errno;
  if (flushed && !std::ferror(stdout) && std::cout.good()) return {};
  if (error == EPIPE || stdout_reader_gone()) return {StdoutState::kReaderGone, EPIPE};
  return {StdoutState::kFailed, error ? error : stdout_failure_cause()};
}

}  // namespace ra::util
