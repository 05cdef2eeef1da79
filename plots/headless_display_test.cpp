// HeadlessDisplay: with no DISPLAY it starts a private Xvfb, names it in DISPLAY, and stops it
// (process stopped and reaped, DISPLAY restored); without Xvfb it says what to install.
#include "plots/headless_display.h"

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "util/errors.h"
#include "util/path_search.h"

namespace ra::plots {
namespace {

// Sets (or unsets, for nullptr) an environment variable for the scope of a test.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const char* value) : name_(name) {
    const char* old = std::getenv(name);
    had_ = old != nullptr;
    if (old) old_ = old;
    if (value)
      ::setenv(name, value, 1);
    else
      ::unsetenv(name);
  }
  ~ScopedEnv() {
    if (had_)
      ::setenv(name_.c_str(), old_.c_str(), 1);
    else
      ::unsetenv(name_.c_str());
  }

 private:
  std::string name_, old_;
  bool had_ = false;
};

bool process_alive(pid_t pid) { return ::kill(pid, 0) == 0; }

// Why: CI has no display; VTK would segfault. The private server must come up, be usable, and be
// gone afterwards (no Xvfb left behind by a test or by `renderaudit plot`).
TEST(HeadlessDisplay, StartsAPrivateXvfbWhenThereIsNoDisplayAndStopsIt) {
  if (util::find_on_path("Xvfb").empty())
    GTEST_SKIP() << "Xvfb is not installed (apt-get install xvfb)";
  ScopedEnv no_display("DISPLAY", nullptr);
  pid_t pid = -1;
  std::string socket;
  {
    HeadlessDisplay d;
    ASSERT_TRUE(d.private_server());
    pid = d.server_pid();
    ASSERT_EQ(d.display().rfind(':', 0), 0u) << d.display();
    socket = "/tmp/.X11-unix/X" + d.display().substr(1);
    EXPECT_TRUE(std::filesystem::exists(socket)) << socket;
    ASSERT_NE(std::getenv("DISPLAY"), nullptr);
    EXPECT_EQ(std::string(std::getenv("DISPLAY")), d.display());
    EXPECT_TRUE(x_display_usable(d.display()));
    EXPECT_TRUE(process_alive(pid));
  }
  EXPECT_FALSE(process_alive(pid));  // stopped and reaped (its display number may be reused at
                                     // once by a test running beside this one)
  EXPECT_EQ(std::getenv("DISPLAY"), nullptr);  // restored: it was unset
}

// Why: the private server must not be open to every local user (issue: no access control). Only a
// client holding its cookie (the 0600 file named in XAUTHORITY) connects.
TEST(HeadlessDisplay, OnlyAClientHoldingTheCookieConnects) {
  if (util::find_on_path("Xvfb").empty())
    GTEST_SKIP() << "Xvfb is not installed (apt-get install xvfb)";
  ScopedEnv no_display("DISPLAY", nullptr);
  HeadlessDisplay d;
  ASSERT_TRUE(d.private_server());
  const std::string cookie = d.authority_file();
  ASSERT_FALSE(cookie.empty());
  struct stat st {};
  ASSERT_EQ(::stat(cookie.c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 0777, 0600u);
  EXPECT_TRUE(x_display_usable(d.display()));  // XAUTHORITY names the cookie
  {
    const std::string empty = cookie + ".empty";
    std::ofstream(empty).close();
    ScopedEnv stranger("XAUTHORITY", empty.c_str());
    EXPECT_FALSE(x_display_usable(d.display())) << "a client without the cookie was let in";
    ::unlink(empty.c_str());
  }
  EXPECT_TRUE(x_display_usable(d.display()));
  d.stop();
  EXPECT_FALSE(std::filesystem::exists(cookie));
}

// Why: a DISPLAY that names no server (a stale ssh forward, say) must not reach VTK either.
TEST(HeadlessDisplay, ReplacesADisplayWhereNoServerAnswers) {
  if (util::find_on_path("Xvfb").empty())
    GTEST_SKIP() << "Xvfb is not installed (apt-get install xvfb)";
  ScopedEnv bad_display("DISPLAY", ":987");
  HeadlessDisplay d;
  EXPECT_TRUE(d.private_server());
  EXPECT_NE(d.display(), ":987");
  EXPECT_TRUE(x_display_usable(std::getenv("DISPLAY")));
  d.stop();
  EXPECT_EQ(std::string(std::getenv("DISPLAY")), ":987");  // restored
}

// Why: with no display and no Xvfb, the message must say what to install (never a segfault).
TEST(HeadlessDisplay, WithoutXvfbSaysWhatToInstall) {
  ScopedEnv no_display("DISPLAY", nullptr);
  const auto empty = std::filesystem::temp_directory_path() / "renderaudit_no_xvfb_here";
  std::filesystem::create_directories(empty);
  ScopedEnv path("PATH", empty.c_str());
  try {
    HeadlessDisplay d;
    FAIL() << "a display was made without Xvfb: " << d.display();
  } catch (const ra::util::UserError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("apt-get install xvfb"), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace ra::plots
