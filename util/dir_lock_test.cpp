// Tests of util/dir_lock.h: one writer per directory, named when refused, released by death.
#include "util/dir_lock.h"

#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <thread>

#include "util/child_process.h"
#include "util/errors.h"

namespace ra::util {
namespace {

std::string fresh(const std::string& tag) {
  const auto d = std::filesystem::temp_directory_path() /
                 ("ra_lock_" + tag + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  return d.string();
}

TEST(DirLock, ASecondWriterIsRefusedWithTheHoldersPidAndWhat) {
  const std::string dir = fresh("second");
  DirLock first(dir, "run");
  try {
    DirLock second(dir, "audit");  // flock conflicts between open files, even in one process
    FAIL() << "a second lock was granted";
  } catch (const UserError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find(dir + " is being written by process " + std::to_string(::getpid()) +
                       " (run) on host"),
              std::string::npos)
        << msg;
    EXPECT_NE(msg.find(" since 20"), std::string::npos) << msg;  // a UTC time
  }
  EXPECT_NE(DirLock::current_holder(dir).find(std::to_string(::getpid())), std::string::npos);
}

TEST(DirLock, TheKernelReleasesTheLockOfAKilledHolder) {
  const std::string dir = fresh("killed");
  int ready[2];
  ASSERT_EQ(::pipe(ready), 0);
  const pid_t holder = fork_child([&] {
    DirLock lock(dir, "run");
    (void)!::write(ready[1], "x", 1);
    ::pause();
    return 0;
  });
  char c;
  ASSERT_EQ(::read(ready[0], &c, 1), 1);
  EXPECT_NE(DirLock::current_holder(dir).find(std::to_string(holder)), std::string::npos);
  EXPECT_THROW(DirLock(dir, "run"), UserError);
  ::kill(holder, SIGKILL);
  wait_child(holder);
  EXPECT_EQ(DirLock::current_holder(dir), "");
  EXPECT_NO_THROW(DirLock(dir, "run"));
  ::close(ready[0]);
  ::close(ready[1]);
}

TEST(DirLock, ReleasedWhenTheObjectDies) {
  const std::string dir = fresh("scope");
  { DirLock a(dir, "run"); }
  EXPECT_NO_THROW(DirLock(dir, "run"));
  EXPECT_EQ(DirLock::current_holder(dir), "");
}

}  // namespace
}  // namespace ra::util
