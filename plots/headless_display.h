// An X display for VTK on machines that have none. Debian's VTK 9.1 is built for X11 only: a VTK
// render window made without a reachable X server segfaults. HeadlessDisplay makes sure that never
// happens: it uses $DISPLAY when an X server with GLX answers there, and otherwise starts a private
// Xvfb (Debian package xvfb) for this process.
//
// The private server:
// - picks a free display number itself (`Xvfb -displayfd`: the server takes the first free number
//   under its own lock files, so concurrent processes never collide) and listens on no TCP port
//   (`-nolisten tcp`), and accepts only clients holding a fresh MIT-MAGIC-COOKIE-1 (`-auth`, a
//   file of mode 0600 in a private directory, named in this process's XAUTHORITY), so another
//   local user cannot connect to it;
// - is ready when it has written its number and its socket /tmp/.X11-unix/X<n> exists;
// - is named in this process's DISPLAY before any VTK window is made;
// - is stopped (SIGTERM, then SIGKILL) when the HeadlessDisplay is destroyed, at exit(), on
//   SIGINT / SIGTERM / SIGHUP, and by the kernel when this process dies in any other way
//   (PR_SET_PDEATHSIG).
#pragma once

#include <string>
#include <sys/types.h>

namespace ra::plots {

class HeadlessDisplay {
 public:
  // Ensures an X display for this process (see above). Throws ra::util::UserError saying what to install
  // (or which DISPLAY to fix) when no display can be had. `log_path` (optional) receives the
  // private server's output; empty: a temporary file, removed when the server stops.
  explicit HeadlessDisplay(const std::string& log_path = "");
  ~HeadlessDisplay();
  HeadlessDisplay(const HeadlessDisplay&) = delete;
  HeadlessDisplay& operator=(const HeadlessDisplay&) = delete;

  // The display in use, e.g. ":0" or ":3".
  const std::string& display() const { return display_; }
  // True when this object started a private Xvfb (false: an existing DISPLAY is used).
  bool private_server() const { return pid_ > 0; }
  // Used by tests to check that the private server is stopped.
  pid_t server_pid() const { return pid_; }
  // The private server's authority file (empty when none was started).
  // Used by tests to check that the authority file is removed.
  const std::string& authority_file() const { return authority_path_; }

  // Stops the private server now (idempotent); DISPLAY is restored to what it was.
  void stop();

 private:
  std::string display_;
  std::string previous_display_;
  bool had_display_ = false;
  pid_t pid_ = -1;
  std::string log_path_;
  bool remove_log_ = false;
  std::string authority_dir_, authority_path_, previous_authority_;
  bool had_authority_ = false;
  void write_authority();
  void remove_authority();
};

// True when an X server with the GLX extension answers at `display` (e.g. ":0").
bool x_display_usable(const std::string& display);

}  // namespace ra::plots
