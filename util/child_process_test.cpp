// Tests of util/child_process.h: argument lists reach the program untouched (no shell), children
// die with their parent, the environment is replaced, the message pipe carries a child's last words.
#include "util/child_process.h"

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

namespace ra::util {
namespace {

// True while `pid` exists and is not a zombie.
bool alive(pid_t pid) {
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  std::string text;
  if (!std::getline(stat, text)) return false;
  const auto close = text.rfind(')');
  return close != std::string::npos && close + 2 < text.size() && text[close + 2] != 'Z';
}

TEST(ChildProcess, AnArgumentIsPassedAsItIsNeverThroughAShell) {
  const std::string marker = std::filesystem::temp_directory_path() /
                             ("ra_pwned_" + std::to_string(::getpid()));
  std::filesystem::remove(marker);
  ChildSpec spec;
  spec.argv = {"echo", "x;touch " + marker + ";#", "$(id)"};
  const ProgramResult r = run_program(spec);
  EXPECT_TRUE(r.exited_ok());
  EXPECT_EQ(r.output, "x;touch " + marker + ";# $(id)\n");
  EXPECT_FALSE(std::filesystem::exists(marker));
}

TEST(ChildProcess, AMissingProgramExitsWith127) {
  ChildSpec spec;
  spec.argv = {"/nonexistent/renderaudit-no-such-program"};
  const ProgramResult r = run_program(spec);
  EXPECT_EQ(r.exit_code(), 127);
  EXPECT_EQ(describe_exit_status(r.status), "exited with status 127");
}

TEST(ChildProcess, SetEnvReplacesAVariableOnce) {
  ::setenv("RA_CHILD_TEST", "parent", 1);
  ChildSpec spec;
  spec.argv = {"env"};
  spec.set_env = {"RA_CHILD_TEST=child"};
  const std::string out = run_program(spec).output;
  EXPECT_NE(out.find("RA_CHILD_TEST=child\n"), std::string::npos);
  EXPECT_EQ(out.find("RA_CHILD_TEST=parent"), std::string::npos);
  ::unsetenv("RA_CHILD_TEST");
  // A message pipe is never inherited by name: a child without one must not write to our fd 3.
  ::setenv("RA_MESSAGE_FD", "3", 1);
  EXPECT_EQ(run_program(spec).output.find("RA_MESSAGE_FD"), std::string::npos);
  ::unsetenv("RA_MESSAGE_FD");
}

// A middle process starts `sleep 60` and is killed: the sleep must go too (PR_SET_PDEATHSIG).
TEST(ChildProcess, AChildDiesWithItsParent) {
  int pipefd[2];
  ASSERT_EQ(::pipe(pipefd), 0);
  const pid_t middle = fork_child([&] {
    ChildSpec spec;
    spec.argv = {"sleep", "60"};
    const pid_t sleeper = start_child(spec).pid;
    (void)!::write(pipefd[1], &sleeper, sizeof sleeper);
    ::pause();
    return 0;
  });
  pid_t sleeper = -1;
  ASSERT_EQ(::read(pipefd[0], &sleeper, sizeof sleeper), ssize_t(sizeof sleeper));
  EXPECT_TRUE(alive(sleeper));
  ::kill(middle, SIGKILL);
  wait_child(middle);
  bool gone = false;
  for (int i = 0; i < 200 && !gone; ++i) {
    gone = !alive(sleeper);
    if (!gone) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  EXPECT_TRUE(gone) << "sleep " << sleeper << " outlived its parent";
  ::close(pipefd[0]);
  ::close(pipefd[1]);
}

// A stop signal sent to a child the moment it starts (the parent's interrupt handler forwarding
// one, util/interrupt.h) stops it, even while it runs the parent's code between fork and exec,
// where the parent's handler would have caught and lost it.
TEST(ChildProcess, AStopSignalAtStartStopsTheChild) {
  struct sigaction caught {}, old {};
  caught.sa_handler = [](int) {};
  sigemptyset(&caught.sa_mask);
  ASSERT_EQ(::sigaction(SIGTERM, &caught, &old), 0);
  int survived = 0;
  for (int i = 0; i < 100 && survived < 3; ++i) {
    ChildSpec spec;
    spec.argv = {"sleep", "30"};
    spec.own_process_group = true;
    const pid_t pid = start_child(spec).pid;
    ::kill(-pid, SIGTERM);
    int status = 0;
    pid_t done = 0;
    for (int wait_ms = 0; wait_ms < 3000 && done == 0; wait_ms += 5) {
      done = ::waitpid(pid, &status, WNOHANG);
      if (done == 0) std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    if (done == 0) {  // still sleeping: the signal was lost
      ++survived;
      ::kill(pid, SIGKILL);
      wait_child(pid);
    } else {
      EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGTERM) << "status " << status;
    }
  }
  ::sigaction(SIGTERM, &old, nullptr);
  EXPECT_EQ(survived, 0) << "children outlived a SIGTERM sent at their start";
}

// The worker program's error reaches the parent through the message pipe, not only its log.
TEST(ChildProcess, TheMessagePipeCarriesTheChildsError) {
  ChildSpec spec;
  spec.argv = {RA_BINARY, "worker", "/nonexistent-run-dir", "reference", "point", "1", "0", "1"};
  spec.stdout_path = spec.stderr_path = "/dev/null";
  spec.message_pipe = true;
  const Child c = start_child(spec);
  const int status = wait_child(c.pid);
  const std::string words = drain_fd(c.message_fd);
  ::close(c.message_fd);
  EXPECT_EQ(WEXITSTATUS(status), 2);
  EXPECT_NE(words.find("/nonexistent-run-dir/experiment.toml"), std::string::npos) << words;
}

TEST(ChildProcess, OutputToFilesSeparately) {
  const auto dir = std::filesystem::temp_directory_path() / ("ra_cp_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  ChildSpec spec;
  spec.argv = {"ls", "/", "/nonexistent-ra-path"};
  spec.stdout_path = (dir / "out").string();
  spec.stderr_path = (dir / "err").string();
  const int status = wait_child(start_child(spec).pid);
  EXPECT_NE(WEXITSTATUS(status), 0);
  std::ifstream out(dir / "out"), err(dir / "err");
  const std::string o((std::istreambuf_iterator<char>(out)), {}), e((std::istreambuf_iterator<char>(err)), {});
  EXPECT_NE(o.find("usr"), std::string::npos);
  EXPECT_NE(e.find("nonexistent-ra-path"), std::string::npos);
  EXPECT_EQ(o.find("nonexistent-ra-path"), std::string::npos);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace ra::util
