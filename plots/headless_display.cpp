// HeadlessDisplay: a private Xvfb when this process has no usable X display (see the header).
#include "plots/headless_display.h"

#include <X11/Xlib.h>
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <fstream>
#include <sstream>
#include <thread>
#include <vector>

#include "util/child_process.h"
#include "util/errors.h"
#include "util/interrupt.h"
#include "util/path_search.h"

namespace ra::plots {
namespace {

constexpr const char* kInstallHint =
    "VTK (Debian's libvtk9 is built for X11 only) needs an X display to draw figures, and none is "
    "usable: DISPLAY is unset or no X server with GLX answers there, and no private server could "
    "be started. Install Debian's Xvfb and Mesa's GLX: `apt-get install xvfb libgl1-mesa-dri` (or "
    "run scripts/install-deps.sh), or set DISPLAY to a working X server";

// The private server of this process, for the exit and signal handlers (async-signal-safe).
volatile pid_t g_server_pid = -1;
// The handlers that stop it on SIGINT, SIGTERM and SIGHUP: installed once, for the process's life.
util::StopSignals* g_stop_signals = nullptr;

// Stops the server and reaps it (up to 2 s), using async-signal-safe calls only.
void kill_server_now() {
  const pid_t pid = g_server_pid;
  if (pid > 0) {
    g_server_pid = -1;
    ::kill(pid, SIGTERM);
    struct timespec tick {0, 10 * 1000 * 1000};
    for (int i = 0; i < 200; ++i) {
      int status = 0;
      const pid_t r = ::waitpid(pid, &status, WNOHANG);
      if (r == pid || r < 0) return;
      ::nanosleep(&tick, nullptr);
    }
    ::kill(pid, SIGKILL);
    ::waitpid(pid, nullptr, 0);
  }
}

void on_signal(int sig) {
  kill_server_now();
  // The previous handler back, and the signal again: the process ends as it would have.
  if (g_stop_signals) g_stop_signals->restore(sig);
  ::raise(sig);
}

void install_handlers_once() {
  if (g_stop_signals) return;
  std::atexit(kill_server_now);
  g_stop_signals = new util::StopSignals(on_signal);  // never restored as a whole: see above
}

std::string read_tail(const std::string& path, std::size_t max_chars = 2000) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  std::string s = ss.str();
  if (s.size() > max_chars) s = "..." + s.substr(s.size() - max_chars);
  while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
  return s;
}

bool wait_exit(pid_t pid, double seconds, int* status) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < end) {
    const pid_t r = ::waitpid(pid, status, WNOHANG);
    if (r == pid || (r < 0 && errno == ECHILD)) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return false;
}

}  // namespace

bool x_display_usable(const std::string& display) {
  if (display.empty()) return false;
  Display* dpy = XOpenDisplay(display.c_str());
  if (!dpy) return false;
  int opcode = 0, event = 0, error = 0;
  const bool glx = XQueryExtension(dpy, "GLX", &opcode, &event, &error);
  XCloseDisplay(dpy);
  return glx;
}

HeadlessDisplay::HeadlessDisplay(const std::string& log_path) {
  const char* env = std::getenv("DISPLAY");
  had_display_ = env != nullptr;
  previous_display_ = env ? env : "";
  if (env && *env && x_display_usable(env)) {
    display_ = env;
    return;
  }

  const std::string xvfb = util::find_on_path("Xvfb");
  if (xvfb.empty()) throw util::UserError(std::string(kInstallHint) + " (Xvfb is not installed).");

  if (log_path.empty()) {
    char tmpl[] = "/tmp/renderaudit-xvfb-XXXXXX";
    const int fd = ::mkstemp(tmpl);
    if (fd >= 0) ::close(fd);
    log_path_ = tmpl;
    remove_log_ = true;
  } else {
    log_path_ = log_path;
  }

  int pipefd[2];
  if (::pipe2(pipefd, O_CLOEXEC) != 0)
    throw util::UserError(std::string("cannot create a pipe for Xvfb: ") + std::strerror(errno));
  install_handlers_once();

  // Only holders of a fresh cookie may connect: another local user cannot reach the server.
  write_authority();
  util::ChildSpec spec;
  spec.argv = {xvfb, "-displayfd", std::to_string(pipefd[1]), "-nolisten", "tcp", "-auth",
               authority_path_, "-screen", "0", "1600x1200x24", "-noreset", "+extension", "GLX"};
  spec.log_to(log_path_);
  spec.stdin_null = true;
  spec.own_process_group = true;  // a Ctrl-C on the terminal goes to us; we stop the server
  spec.death_signal = SIGTERM;    // lets it remove its socket and lock file
  spec.inherit_fds = {pipefd[1]};
  pid_t pid = -1;
  try {
    pid = util::start_child(spec).pid;
  } catch (const std::exception& e) {
    ::close(pipefd[0]);
    ::close(pipefd[1]);
    remove_authority();
    throw util::UserError(std::string("cannot start Xvfb: ") + e.what());
  }
  ::close(pipefd[1]);
  pid_ = pid;
  g_server_pid = pid;

  // The server writes its display number when it accepts connections; EOF means it died.
  std::string number;
  bool ok = false;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (std::chrono::steady_clock::now() < deadline) {
    struct pollfd p {pipefd[0], POLLIN, 0};
    const int r = ::poll(&p, 1, 200);
    if (r < 0 && errno == EINTR) continue;
    if (r > 0) {
      char buf[32];
      const ssize_t n = ::read(pipefd[0], buf, sizeof buf);
      if (n <= 0) break;  // the server exited
      number.append(buf, buf + n);
      if (number.find('\n') != std::string::npos) {
        ok = true;
        break;
      }
    }
  }
  ::close(pipefd[0]);
  while (!number.empty() && (number.back() == '\n' || number.back() == ' ')) number.pop_back();

  // Its socket must exist before a client can connect.
  if (ok && !number.empty()) {
    const std::string socket = "/tmp/.X11-unix/X" + number;
    ok = false;
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(10);
    struct stat st {};
    while (std::chrono::steady_clock::now() < until) {
      if (::stat(socket.c_str(), &st) == 0) {
        ok = true;
        break;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
  }
  if (ok) {
    display_ = ":" + number;
    ::setenv("DISPLAY", display_.c_str(), 1);
    ::setenv("XAUTHORITY", authority_path_.c_str(), 1);
    if (x_display_usable(display_)) return;
    ok = false;
  }

  const std::string log = read_tail(log_path_);
  stop();
  throw util::UserError(std::string(kInstallHint) + ". A private Xvfb (" + xvfb +
                        ") did not start" + (log.empty() ? "." : ":\n" + log));
}

void HeadlessDisplay::stop() {
  if (pid_ > 0) {
    g_server_pid = -1;
    ::kill(pid_, SIGTERM);
    int status = 0;
    if (!wait_exit(pid_, 5.0, &status)) {
      ::kill(pid_, SIGKILL);
      wait_exit(pid_, 5.0, &status);
    }
    pid_ = -1;
    if (had_display_)
      ::setenv("DISPLAY", previous_display_.c_str(), 1);
    else
      ::unsetenv("DISPLAY");
    if (had_authority_)
      ::setenv("XAUTHORITY", previous_authority_.c_str(), 1);
    else
      ::unsetenv("XAUTHORITY");
  }
  remove_authority();
  if (remove_log_ && !log_path_.empty()) {
    ::unlink(log_path_.c_str());
    remove_log_ = false;
  }
}

HeadlessDisplay::~HeadlessDisplay() { stop(); }

// An Xauthority file (the format of libXau: big-endian 16-bit lengths before each field) holding
// one entry: family FamilyWild (any address), no display number (any display: -displayfd picks it
// later), MIT-MAGIC-COOKIE-1 with 16 bytes from /dev/urandom. In a fresh 0700 directory, mode 0600.
void HeadlessDisplay::write_authority() {
  char dir_template[] = "/tmp/renderaudit-xauth-XXXXXX";
  if (!::mkdtemp(dir_template))
    throw util::UserError(
        std::string("cannot create a private directory for Xvfb's authority file: ") +
        std::strerror(errno));
  authority_dir_ = dir_template;
  authority_path_ = authority_dir_ + "/Xauthority";
  unsigned char cookie[16];
  std::ifstream random("/dev/urandom", std::ios::binary);
  random.read(reinterpret_cast<char*>(cookie), sizeof cookie);
  if (random.gcount() != std::streamsize(sizeof cookie)) {
    remove_authority();
    throw util::UserError("cannot read /dev/urandom for Xvfb's authority cookie");
  }
  std::string entry;
  auto put16 = [&](unsigned v) { entry += char((v >> 8) & 0xff), entry += char(v & 0xff); };
  auto field = [&](const std::string& bytes) { put16(unsigned(bytes.size())), entry += bytes; };
  put16(0xffff);  // FamilyWild
  field("");      // address
  field("");      // display number
  field("MIT-MAGIC-COOKIE-1");
  field(std::string(reinterpret_cast<const char*>(cookie), sizeof cookie));
  const int fd = ::open(authority_path_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
  const bool ok = fd >= 0 && ::write(fd, entry.data(), entry.size()) == ssize_t(entry.size());
  if (fd >= 0) ::close(fd);
  if (!ok) {
    remove_authority();
    throw util::UserError("cannot write Xvfb's authority file in " + authority_dir_);
  }
  const char* previous = std::getenv("XAUTHORITY");
  had_authority_ = previous != nullptr;
  previous_authority_ = previous ? previous : "";
}

void HeadlessDisplay::remove_authority() {
  if (authority_dir_.empty()) return;
  if (!authority_path_.empty()) ::unlink(authority_path_.c_str());
  ::rmdir(authority_dir_.c_str());
  authority_dir_.clear();
  authority_path_.clear();
}

}  // namespace ra::plots
