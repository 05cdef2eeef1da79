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

// SIGINT, SIGTERM and SIGHUP handled by `handler` while this lives; the handlers before come back
// at restore() or at the end. SIGHUP ignored before stays ignored (under nohup: whoever started the
// command asked for it to outlive the terminal). InterruptScope, a run's own signal
// handling and the plots' private X server (plots/headless_display.cpp) all stand on it.
class StopSignals {
 public:
  static constexpr int kSignals[3] = {SIGINT, SIGTERM, SIGHUP};

  explicit StopSignals(void (*handler)(int));
  ~StopSignals() { restore(); }
  StopSignals(const StopSignals&) = delete;
  StopSignals& operator=(const StopSignals&) = delete;
  void restore();
  // Puts back the handler `sig` had before, and only that one. Async-signal-safe: a handler that
  // cleans up and then ends the process as the signal would have calls it, then raises `sig`.
  void restore(int sig) const;

 private:
  struct sigaction old_[3] = {};
  bool restored_ = false;
};

class InterruptScope {
 public:
  InterruptScope();

 private:
  StopSignals signals_;
};

// The signal that interrupted the command (0: none yet).
int interrupt_signal();
// Throws Interrupted when a signal came.
void throw_if_interrupted();

// run_program's side: the process group that an interrupt stops (0: none); set while it waits.
void set_interruptible_group(pid_t group);

}  // namespace ra::util
