// Stopping on SIGINT, SIGTERM and SIGHUP: which handlers are installed and restored, what a signal
// leaves behind, and the child's process group that it stops. A signal that comes is remembered
// for the life of the process (interrupt.cpp), so the tests that send one run in a child of
// their own (EXPECT_EXIT) and say what went wrong by the exit code.
#include "util/interrupt.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <string>

namespace ra::util {
namespace {

void handler_a(int) {}
void handler_b(int) {}

void (*handler_of(int sig))(int) {
  struct sigaction now {};
  sigaction(sig, nullptr, &now);
  return now.sa_handler;
}

// Sets `sig`'s handler for a test and puts the old one back at the end.
struct Handler {
  Handler(int sig, void (*h)(int)) : sig(sig) {
    struct sigaction sa {};
    sa.sa_handler = h;
    sigemptyset(&sa.sa_mask);
    sigaction(sig, &sa, &old);
  }
  ~Handler() { sigaction(sig, &old, nullptr); }
  int sig;
  struct sigaction old {};
};

TEST(Interrupt, InterruptedNamesTheSignal) {
  EXPECT_STREQ(Interrupted(SIGINT).what(), "interrupted by SIGINT");
  EXPECT_STREQ(Interrupted(SIGHUP).what(), "interrupted by SIGHUP");
  EXPECT_STREQ(Interrupted(SIGUSR1).what(), "interrupted by a signal");
  EXPECT_EQ(Interrupted(SIGTERM).signal, SIGTERM);
}

TEST(Interrupt, StopSignalsInstallsAndRestoresTheHandlersBefore) {
  const Handler i(SIGINT, handler_a), t(SIGTERM, SIG_DFL), h(SIGHUP, handler_a);
  {
    StopSignals stop(handler_b);
    for (int sig : StopSignals::kSignals) EXPECT_EQ(handler_of(sig), handler_b) << sig;
    stop.restore(SIGTERM);  // one signal back, the others still handled
    EXPECT_EQ(handler_of(SIGTERM), SIG_DFL);
    EXPECT_EQ(handler_of(SIGINT), handler_b);
  }
  EXPECT_EQ(handler_of(SIGINT), handler_a);
  EXPECT_EQ(handler_of(SIGTERM), SIG_DFL);
  EXPECT_EQ(handler_of(SIGHUP), handler_a);
}

// Under nohup SIGHUP is ignored: the command is to outlive its terminal, so it stays ignored.
TEST(Interrupt, StopSignalsLeavesAnIgnoredSignalIgnored) {
  const Handler h(SIGHUP, SIG_IGN), t(SIGTERM, SIG_DFL);
  StopSignals stop(handler_b);
  EXPECT_EQ(handler_of(SIGHUP), SIG_IGN);
  EXPECT_EQ(handler_of(SIGTERM), handler_b);
  stop.restore();
  EXPECT_EQ(handler_of(SIGHUP), SIG_IGN);
  EXPECT_EQ(handler_of(SIGTERM), SIG_DFL);
}

// Inside a scope a signal does not end the process: it is remembered, and the next check throws
// it. After the scope the default handling is back. Exit codes: 0 all as said, else the step.
TEST(InterruptDeathTest, AScopeTurnsASignalIntoInterrupted) {
  EXPECT_EXIT(
      {
        signal(SIGTERM, SIG_DFL);
        {
          InterruptScope scope;
          if (interrupt_signal() != 0) std::_Exit(2);
          throw_if_interrupted();  // nothing came yet: no throw
          raise(SIGTERM);
          if (interrupt_signal() != SIGTERM) std::_Exit(3);
          try {
            throw_if_interrupted();
            std::_Exit(4);
          } catch (const Interrupted& e) {
            if (e.signal != SIGTERM) std::_Exit(5);
          }
        }
        if (handler_of(SIGTERM) != SIG_DFL) std::_Exit(6);
        std::_Exit(0);
      },
      testing::ExitedWithCode(0), "");
}

// The child a command waits for gets SIGTERM with its group when the signal comes, and at once
// when the signal came before its group was known. Exit codes: 0 both stopped, else the step.
TEST(InterruptDeathTest, ASignalStopsTheWaitedForGroup) {
  EXPECT_EXIT(
      {
        // A `sleep` in a group of its own, returned once it runs: before its exec it would
        // still have this process's handler and take the SIGTERM as a signal to remember.
        const auto sleeper = [] {
          int ready[2];
          if (pipe2(ready, O_CLOEXEC) != 0) std::_Exit(10);
          const pid_t pid = fork();
          if (pid == 0) {
            setpgid(0, 0);
            execlp("sleep", "sleep", "30", static_cast<char*>(nullptr));
            std::_Exit(127);
          }
          setpgid(pid, pid);
          close(ready[1]);
          char c;
          while (read(ready[0], &c, 1) > 0) {
          }
          close(ready[0]);  // end of file: the exec closed the child's copy
          return pid;
        };
        const auto ended_by_sigterm = [](pid_t pid) {
          int status = 0;
          return waitpid(pid, &status, 0) == pid && WIFSIGNALED(status) &&
                 WTERMSIG(status) == SIGTERM;
        };
        InterruptScope scope;
        const pid_t first = sleeper();
        set_interruptible_group(first);
        raise(SIGINT);
        if (!ended_by_sigterm(first)) std::_Exit(2);
        set_interruptible_group(0);
        const pid_t second = sleeper();
        set_interruptible_group(second);  // the signal already came: stopped now
        if (!ended_by_sigterm(second)) std::_Exit(3);
        std::_Exit(interrupt_signal() == SIGINT ? 0 : 4);
      },
      testing::ExitedWithCode(0), "");
}

}  // namespace
}  // namespace ra::util
