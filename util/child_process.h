// Starting other programs: the one place that forks and execs. A child is started from an argument
// list (never through a shell), with everything it needs prepared before fork so that only
// async-signal-safe calls run between fork and exec, and it dies with its parent (prctl
// PR_SET_PDEATHSIG, checked against the race with getppid): no worker, Xvfb or re-render outlives
// the command that started it, however that command ends.
#pragma once

#include <sys/types.h>

#include <csignal>
#include <functional>
#include <string>
#include <vector>

namespace ra::util {

struct ChildSpec {
  std::vector<std::string> argv;     // argv[0]: a path, or a program name looked up in PATH
  std::vector<std::string> set_env;  // "NAME=value": replaces or adds to this process's environment
  std::string stdout_path;           // non-empty: stdout goes to this file (truncated)
  std::string stderr_path;           // non-empty: stderr goes to this file (may equal stdout_path)
  bool capture_output = false;       // stdout and stderr not sent to files go to a pipe
                                     // (Child::output_fd)
  // Both streams to one file (a log).
  void log_to(const std::string& path) { stdout_path = stderr_path = path; }
  std::string working_dir;           // non-empty: the child starts there (exit 127 if it cannot)
  bool stdin_null = false;           // stdin from /dev/null
  bool command_pipe = false;         // stdin from a pipe whose write end is Child::command_fd
  bool own_process_group = false;    // setpgid(0, 0): kill(-pid, ...) reaches all it starts
  int death_signal = SIGKILL;        // what the child gets when this process dies
  std::vector<int> inherit_fds;      // descriptors kept open across exec (others are close-on-exec)
  // A pipe for the child's last words: its write end is fd 3 in the child, announced as
  // RA_MESSAGE_FD=3, so an error reaches the parent even when the disk of its log is full.
  bool message_pipe = false;
};

struct Child {
  pid_t pid = -1;
  int output_fd = -1;   // read end of the capture pipe (capture_output), close-on-exec
  int message_fd = -1;  // read end of the message pipe (message_pipe), non-blocking
  int command_fd = -1;  // write end of the child's stdin (command_pipe), close-on-exec; writes to
                        // a child that is gone fail with EPIPE (SIGPIPE must be ignored)
};

// Starts the program; throws std::runtime_error when fork or the pipes fail. A program that
// cannot be executed exits with status 127.
Child start_child(const ChildSpec& spec);

// In a child that was forked without exec: dies with `parent` (signal `sig`), or exits now when
// the parent is already gone. Async-signal-safe.
void die_with_parent(pid_t parent, int sig = SIGKILL);

// Forks a child that runs `body` and leaves with _exit(status it returns): for work that must run
// in a process of its own without exec (a GL measurement: Mesa picks its driver once per process).
// The child dies with this process. Throws std::runtime_error when fork fails.
pid_t fork_child(const std::function<int()>& body);

// Waits for `pid` (retrying on EINTR) and returns its wait status.
int wait_child(pid_t pid);

// "exited with status N" / "crashed (signal N, Segmentation fault)".
std::string describe_exit_status(int status);

// What is in `fd` now (non-blocking read to EOF or until it would block); closes nothing.
std::string drain_fd(int fd);

// Runs a program to its end with its stdout and stderr captured: for short commands whose output
// is parsed (benchmarks, tests). `status` is the wait status.
struct ProgramResult {
  int status = 0;
  std::string output;
  bool exited_ok() const;  // exited normally with status 0
  int exit_code() const;   // the exit status, or 128 + signal
};
ProgramResult run_program(const ChildSpec& spec);

// The child side of ChildSpec::message_pipe: writes `message` to RA_MESSAGE_FD if it is set.
void send_message_to_parent(const std::string& message);

}  // namespace ra::util
