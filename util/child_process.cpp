#include "util/child_process.h"

#include <fcntl.h>
#include <poll.h>
#include <pthread.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

#include "util/interrupt.h"

extern char** environ;

namespace ra::util {

void die_with_parent(pid_t parent, int sig) {
  ::prctl(PR_SET_PDEATHSIG, sig);
  if (::getppid() != parent) ::_exit(127);  // the parent died before prctl took effect
}

Child start_child(const ChildSpec& spec) {
  if (spec.argv.empty()) throw std::logic_error("start_child: empty argument list");
  // Everything the child needs, prepared before fork.
  std::vector<std::string> env;
  for (char** e = environ; e && *e; ++e) {
    const char* eq = std::strchr(*e, '=');
    const size_t len = eq ? size_t(eq - *e) + 1 : std::strlen(*e);
    bool replaced = std::strncmp(*e, "RA_MESSAGE_FD=", 14) == 0;  // set below, or not at all
    for (const auto& s : spec.set_env)
      if (s.compare(0, len, *e, len) == 0) replaced = true;
    if (!replaced) env.emplace_back(*e);
  }
  for (const auto& s : spec.set_env) env.push_back(s);
  if (spec.message_pipe) env.push_back("RA_MESSAGE_FD=3");
  std::vector<char*> argv, envp;
  for (const auto& a : spec.argv) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  for (const auto& e : env) envp.push_back(const_cast<char*>(e.c_str()));
  envp.push_back(nullptr);

  int out_pipe[2] = {-1, -1}, msg_pipe[2] = {-1, -1}, cmd_pipe[2] = {-1, -1};
  auto close_all = [&] {
    for (int fd : {out_pipe[0], out_pipe[1], msg_pipe[0], msg_pipe[1], cmd_pipe[0], cmd_pipe[1]})
      if (fd >= 0) ::close(fd);
  };
  if ((spec.capture_output && ::pipe2(out_pipe, O_CLOEXEC) != 0) ||
      (spec.message_pipe && ::pipe2(msg_pipe, O_CLOEXEC) != 0) ||
      (spec.command_pipe && ::pipe2(cmd_pipe, O_CLOEXEC) != 0)) {
    const std::string why = std::strerror(errno);
    close_all();
    throw std::runtime_error("cannot create a pipe: " + why);
  }
  const pid_t parent = ::getpid();
  // The stop signals held from fork until the child has dropped the parent's handlers: one sent
  // to the child before its exec (an interrupt forwarded to its group) would be caught by a copy
  // of the parent's handler and lost, and the child would run on.
  sigset_t stop, before;
  sigemptyset(&stop);
  for (int sig : StopSignals::kSignals) sigaddset(&stop, sig);
  ::pthread_sigmask(SIG_BLOCK, &stop, &before);
  const pid_t pid = ::fork();
  if (pid != 0) ::pthread_sigmask(SIG_SETMASK, &before, nullptr);
  if (pid < 0) {
    close_all();
    throw std::runtime_error(std::string("cannot start ") + spec.argv[0] + ": fork failed: " +
                             std::strerror(errno));
  }
  if (pid == 0) {  // only async-signal-safe calls from here to exec
    for (int sig : StopSignals::kSignals) {
      struct sigaction now {};
      ::sigaction(sig, nullptr, &now);
      if (now.sa_handler == SIG_IGN) continue;  // ignored stays ignored, as through exec
      now.sa_handler = SIG_DFL;
      ::sigaction(sig, &now, nullptr);
    }
    ::pthread_sigmask(SIG_SETMASK, &before, nullptr);  // a signal held now stops the child
    die_with_parent(parent, spec.death_signal);
    if (spec.own_process_group) ::setpgid(0, 0);
    if (spec.command_pipe) {
      if (cmd_pipe[0] == 0)
        ::fcntl(0, F_SETFD, 0);
      else
        ::dup2(cmd_pipe[0], 0);  // the copy is not close-on-exec
    } else if (spec.stdin_null) {
      const int in = ::open("/dev/null", O_RDONLY);
      if (in >= 0) ::dup2(in, 0), ::close(in);
    }
    if (spec.capture_output) {
      ::dup2(out_pipe[1], 1);
      ::dup2(out_pipe[1], 2);
    }
    if (!spec.stdout_path.empty()) {
      const int out = ::open(spec.stdout_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      if (out >= 0) {
        ::dup2(out, 1);
        if (spec.stderr_path == spec.stdout_path) ::dup2(out, 2);
        ::close(out);
      }
    }
    if (!spec.stderr_path.empty() && spec.stderr_path != spec.stdout_path) {
      const int err = ::open(spec.stderr_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      if (err >= 0) ::dup2(err, 2), ::close(err);
    }
    if (spec.message_pipe) {
      if (msg_pipe[1] == 3)
        ::fcntl(3, F_SETFD, 0);
      else
        ::dup2(msg_pipe[1], 3);  // dup2 clears close-on-exec on the copy
    }
    for (int fd : spec.inherit_fds) ::fcntl(fd, F_SETFD, 0);
    if (!spec.working_dir.empty() && ::chdir(spec.working_dir.c_str()) != 0) ::_exit(127);
    ::execvpe(argv[0], argv.data(), envp.data());
    ::_exit(127);
  }
  // The group made on both sides of the fork: a kill(-pid) right after start_child returns (a
  // signal that came meanwhile) must not find the group missing while the child runs on.
  if (spec.own_process_group) ::setpgid(pid, pid);
  Child child;
  child.pid = pid;
  if (spec.capture_output) {
    ::close(out_pipe[1]);
    child.output_fd = out_pipe[0];
  }
  if (spec.message_pipe) {
    ::close(msg_pipe[1]);
    ::fcntl(msg_pipe[0], F_SETFL, O_NONBLOCK);
    child.message_fd = msg_pipe[0];
  }
  if (spec.command_pipe) {
    ::close(cmd_pipe[0]);
    child.command_fd = cmd_pipe[1];
  }
  return child;
}

pid_t fork_child(const std::function<int()>& body) {
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid < 0) throw std::runtime_error(std::string("fork failed: ") + std::strerror(errno));
  if (pid == 0) {
    die_with_parent(parent);
    ::_exit(body());
  }
  return pid;
}

int wait_child(pid_t pid) {
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) return 0;
  }
  return status;
}

std::string describe_exit_status(int status) {
  if (WIFSIGNALED(status)) {
    const int sig = WTERMSIG(status);
    return "crashed (signal " + std::to_string(sig) + ", " + strsignal(sig) + ")";
  }
  return "exited with status " + std::to_string(WEXITSTATUS(status));
}

std::string drain_fd(int fd) {
  std::string out;
  if (fd < 0) return out;
  const int flags = ::fcntl(fd, F_GETFL);
  ::fcntl(fd, F_SETFL, flags | O_NONBLOCK);
  char buf[4096];
  for (;;) {
    const ssize_t n = ::read(fd, buf, sizeof buf);
    if (n > 0) {
      out.append(buf, size_t(n));
      continue;
    }
    if (n < 0 && errno == EINTR) continue;
    break;
  }
  ::fcntl(fd, F_SETFL, flags);
  return out;
}

bool ProgramResult::exited_ok() const { return WIFEXITED(status) && WEXITSTATUS(status) == 0; }

int ProgramResult::exit_code() const {
  return WIFSIGNALED(status) ? 128 + WTERMSIG(status) : WEXITSTATUS(status);
}

ProgramResult run_program(const ChildSpec& spec) {
  ChildSpec s = spec;
  s.capture_output = true;
  const Child c = start_child(s);
  // An interrupt (util/interrupt.h) stops a child of its own group with everything it started.
  if (s.own_process_group) set_interruptible_group(c.pid);
  ProgramResult r;
  char buf[4096];
  for (;;) {
    const ssize_t n = ::read(c.output_fd, buf, sizeof buf);
    if (n > 0) {
      r.output.append(buf, size_t(n));
    } else if (n < 0 && errno == EINTR) {
      continue;
    } else {
      break;
    }
  }
  ::close(c.output_fd);
  r.status = wait_child(c.pid);
  if (s.own_process_group) set_interruptible_group(0);
  return r;
}

void send_message_to_parent(const std::string& message) {
  const char* fd_text = std::getenv("RA_MESSAGE_FD");
  if (!fd_text) return;
  const int fd = std::atoi(fd_text);
  if (fd <= 2) return;
  size_t done = 0;
  while (done < message.size()) {
    const ssize_t n = ::write(fd, message.data() + done, message.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    done += size_t(n);
  }
}

}  // namespace ra::util
