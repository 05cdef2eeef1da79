#include "util/interrupt.h"

#include <signal.h>

#include <atomic>

namespace ra::util {
namespace {

volatile std::sig_atomic_t g_signal = 0;
std::atomic<pid_t> g_group{0};

void on_signal(int sig) {
  if (g_signal == 0) g_signal = sig;
  const pid_t group = g_group.load();
  if (group > 0) ::kill(-group, SIGTERM);
}

}  // namespace

Interrupted::Interrupted(int sig)
    : std::runtime_error(std::string("interrupted by ") + (sig == SIGINT    ? "SIGINT"
                                                           : sig == SIGTERM ? "SIGTERM"
                                                           : sig == SIGHUP  ? "SIGHUP"
                                                                            : "a signal")),
      signal(sig) {}

StopSignals::StopSignals(void (*handler)(int)) {
  struct sigaction sa {};
  sa.sa_handler = handler;
  sigemptyset(&sa.sa_mask);
  for (int i = 0; i < 3; ++i) {
    sigaction(kSignals[i], nullptr, &old_[i]);
    // SIGHUP ignored stays ignored (nohup); SIGINT ignored is a shell's doing for a background
    // job, and the user's Ctrl-C or kill -INT must still stop the command.
    if (kSignals[i] != SIGHUP || old_[i].sa_handler != SIG_IGN) sigaction(kSignals[i], &sa, nullptr);
  }
}

void StopSignals::restore() {
  if (restored_) return;
  restored_ = true;
  for (int sig : kSignals) restore(sig);
}

void StopSignals::restore(int sig) const {
  for (int i = 0; i < 3; ++i)
    if (kSignals[i] == sig) sigaction(sig, &old_[i], nullptr);
}

// g_signal is not reset: a scope inside another (a bisection inside a night) keeps a signal that
// came before it.
InterruptScope::InterruptScope() : signals_(on_signal) {}

int interrupt_signal() { return g_signal; }

void throw_if_interrupted() {
  if (g_signal != 0) throw Interrupted(g_signal);
}

void set_interruptible_group(pid_t group) {
  g_group.store(group);
  // A signal that came before the child's group existed still stops it.
  if (group > 0 && g_signal != 0) ::kill(-group, SIGTERM);
}

}  // namespace ra::util
