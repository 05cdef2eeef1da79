// run_in_child (gl_child_process.h): a result crosses, an exception's message crosses, a crash is
// named by its signal, an early _exit by its status; the scratch file is gone afterwards each time.
#include "util/gl_child_process.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <limits>

#include "util/errors.h"

namespace ra::util {
namespace {

class RunInChild : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = ::testing::TempDir() + "gl_child_process_" + std::to_string(::getpid());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  // The scratch folder holds nothing (the result file and its .tmp removed).
  bool scratch_empty() const { return std::filesystem::is_empty(dir_); }
  // What run_in_child threw (a ChildProcessError), "" when it returned.
  std::string error_of(const std::function<nlohmann::json()>& work, bool* user_error = nullptr) {
    try {
      run_in_child(dir_, "child-test", work);
    } catch (const ChildProcessError& e) {
      if (user_error) *user_error = e.user_error();
      return e.what();
    }
    return "";
  }
  std::string dir_;
};

TEST_F(RunInChild, ReturnsTheChildsJson) {
  const int parent = ::getpid();
  const nlohmann::json j = run_in_child(dir_, "child-test", [&] {
    return nlohmann::json{{"pid", ::getpid()},
                          {"x", 0.1 + 0.2},
                          {"tiny", std::numeric_limits<double>::denorm_min()},
                          {"v", {1, 2, 3}},
                          {"s", "text"}};
  });
  EXPECT_NE(j.at("pid").get<int>(), parent);  // measured elsewhere
  EXPECT_EQ(j.at("x").get<double>(), 0.1 + 0.2);  // doubles cross exactly
  EXPECT_EQ(j.at("tiny").get<double>(), std::numeric_limits<double>::denorm_min());
  EXPECT_EQ(j.at("v"), nlohmann::json({1, 2, 3}));
  EXPECT_EQ(j.at("s"), "text");
  EXPECT_TRUE(scratch_empty());
}

TEST_F(RunInChild, TheChildsStateStaysInTheChild) {
  static int counter = 0;
  counter = 1;
  const nlohmann::json j = run_in_child(dir_, "child-test", [&] { return nlohmann::json(++counter); });
  EXPECT_EQ(j.get<int>(), 2);
  EXPECT_EQ(counter, 1);
  EXPECT_TRUE(scratch_empty());
}

TEST_F(RunInChild, AnExceptionsMessageCrosses) {
  bool user = true;
  EXPECT_EQ(error_of([]() -> nlohmann::json { throw std::runtime_error("no driver here"); }, &user),
            "no driver here");
  EXPECT_FALSE(user);
  EXPECT_TRUE(scratch_empty());
  EXPECT_EQ(error_of([]() -> nlohmann::json { throw UserError("x.toml:1:1: bad"); }, &user), "x.toml:1:1: bad");
  EXPECT_TRUE(user);
  EXPECT_TRUE(scratch_empty());
  EXPECT_EQ(error_of([]() -> nlohmann::json { throw 42; }), "an exception of unknown type");
  EXPECT_TRUE(scratch_empty());
}

TEST_F(RunInChild, ACrashIsNamedByItsSignal) {
  const std::string e = error_of([]() -> nlohmann::json {
    std::signal(SIGABRT, SIG_DFL);
    std::abort();
  });
  EXPECT_EQ(e, "the measuring process died of signal " + std::to_string(SIGABRT));
  EXPECT_TRUE(scratch_empty());
  const std::string segv = error_of([]() -> nlohmann::json {
    std::raise(SIGSEGV);
    return nullptr;
  });
  EXPECT_EQ(segv, "the measuring process died of signal " + std::to_string(SIGSEGV));
  EXPECT_TRUE(scratch_empty());
}

TEST_F(RunInChild, AnExitWithoutAResultIsNamedByItsStatus) {
  const std::string e = error_of([]() -> nlohmann::json { ::_exit(7); });
  EXPECT_EQ(e.rfind("the measuring process exited with status 7 without a result (", 0), 0u) << e;
  EXPECT_TRUE(scratch_empty());
}

TEST_F(RunInChild, AStaleScratchFileIsNotTakenForAResult) {
  {
    std::FILE* f = std::fopen((dir_ + "/.child-test.json").c_str(), "w");
    ASSERT_NE(f, nullptr);
    std::fputs("{\"result\": \"stale\"}", f);
    std::fclose(f);
  }
  const std::string e = error_of([]() -> nlohmann::json { ::_exit(0); });
  EXPECT_EQ(e.rfind("the measuring process exited with status 0 without a result (", 0), 0u) << e;
  EXPECT_TRUE(scratch_empty());
}

TEST_F(RunInChild, AnUnwritableScratchFolderIsReported) {
  const std::string e = error_of([] { return nlohmann::json(1); });
  EXPECT_EQ(e, "");  // sanity: it works here
  std::filesystem::remove_all(dir_);
  const std::string missing = error_of([] { return nlohmann::json(1); });
  EXPECT_EQ(missing.rfind("the measuring process exited with status 4 without a result (", 0), 0u) << missing;
  std::filesystem::create_directories(dir_);
}

}  // namespace
}  // namespace ra::util
