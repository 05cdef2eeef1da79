// Stopping a long command on SIGINT, SIGTERM or SIGHUP so that it can clean up: while an
// InterruptScope lives, these signals are caught, the program it is waiting for through
// run_program (a child in its own process group: a build's compiler, a build command) is sent
// SIGTERM with its whole group, and interrupt_signal() says which signal came. The command then
// throws Interrupted at its next check, so that destructors restore what it changed (a source
// tree's branch, a lock) and it exits 128 + the signal. A second signal is not needed and not
// special: the first one already stops the child.
#pragma once

#include <sys/types.h>

#include <csignal>
#include <stdexcept>
#include <string>

namespace ra::util {

struct Interrupted : std::runtime_error {
  explicit Interrupted(int sig);
  int signal;
};

class InterruptScope {
 public:
  InterruptScope();
  ~InterruptScope();
  InterruptScope(const InterruptScope&) = delete;
  InterruptScope& operator=(const InterruptScope&) = delete;

 private:
  struct sigaction old_int_ {}, old_term_ {}, old_hup_ {};
};

// The signal that interrupted the command (0: none yet).
int interrupt_signal();
// Throws Interrupted when a signal came.
void throw_if_interrupted();

// run_program's side: the process group that an interrupt stops (0: none); set while it waits.
void set_interruptible_group(pid_t group);

}  // namespace ra::util
