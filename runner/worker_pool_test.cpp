// Tests of runner/worker_pool.h with a stand-in worker: a shell script that behaves as its
// platform name says (hangs, crashes, or writes its records file and exits), so that the pool's
// time limit, crash detection and success are seen without a GL driver.
#include "runner/worker_pool.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>

namespace fs = std::filesystem;

namespace ra::runner {
namespace {

class WorkerPoolTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = (fs::temp_directory_path() / ("ra_pool_" + std::to_string(::getpid()))).string();
    fs::remove_all(dir_);
    fs::create_directories(dir_ + "/logs");
    fs::create_directories(dir_ + "/records");
    program_ = dir_ + "/fake-worker";
    // argv: worker DIR PLATFORM KIND VIEW BEGIN END --records-dir RECORDS
    std::ofstream(program_) << "#!/bin/sh\n"
                               "case \"$3\" in\n"
                               "  hang) exec sleep 60 ;;\n"
                               "  crash) kill -SEGV $$ ;;\n"
                               "  ok) echo x > \"$9/$3.$4.v$5.$6-$7.csv\" ;;\n"
                               "esac\n";
    ::chmod(program_.c_str(), 0755);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // Runs `items` to their end, one process each, and returns the events in order.
  std::vector<WorkerEvent> run(std::deque<WorkItem> todo, int jobs) {
    std::vector<WorkerEvent> events;
    WorkerPool pool({program_, dir_, jobs, false, false, ".csv"},
                    [&](const WorkItem&) { return dir_ + "/records"; },
                    [&](const WorkerEvent& e) { events.push_back(e); });
    const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(30);
    while ((!todo.empty() || !pool.empty()) && std::chrono::steady_clock::now() < give_up) {
      if (pool.serve(todo)) continue;
      pool.enforce_time_limits();
      pool.wait(5);
    }
    EXPECT_TRUE(pool.empty());
    EXPECT_EQ(pool.processes_started(), events.size());
    return events;
  }
  static WorkItem item(const std::string& platform, double timeout_s) {
    return WorkItem{rundir::Shard{platform, geometry::Kind::kPoint, 1, 0, 10}, "", 1, timeout_s};
  }
  std::string dir_, program_;
};

TEST_F(WorkerPoolTest, AWorkerPastItsTimeLimitIsKilledAndReportedAsTimedOut) {
  const auto t0 = std::chrono::steady_clock::now();
  const std::vector<WorkerEvent> events = run({item("hang", 0.3)}, 1);
  const double took = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].kind, WorkerEvent::Kind::kTimedOut);
  EXPECT_EQ(events[0].reason, "timed out after 0.3 s (killed)");
  EXPECT_EQ(events[0].item.shard.id(), "hang.point.v1.0-10");
  EXPECT_GE(took, 0.3);
  EXPECT_LT(took, 10.0);  // killed, not waited for (it sleeps 60 s)
}

TEST_F(WorkerPoolTest, ACrashAndASuccessAreToldApart) {
  const std::vector<WorkerEvent> events = run({item("crash", 20), item("ok", 20)}, 2);
  ASSERT_EQ(events.size(), 2u);
  for (const WorkerEvent& e : events) {
    if (e.item.shard.platform == "crash") {
      EXPECT_EQ(e.kind, WorkerEvent::Kind::kCrashed);
      EXPECT_NE(e.reason.find("signal 11"), std::string::npos) << e.reason;
      EXPECT_NE(e.reason.find("; log: " + dir_ + "/logs/crash.point.v1.0-10.log"),
                std::string::npos) << e.reason;
    } else {
      EXPECT_EQ(e.kind, WorkerEvent::Kind::kSucceeded);
      EXPECT_GE(e.item_s, 0.0);
    }
  }
}

TEST_F(WorkerPoolTest, NoMoreThanJobsRunAtOnce) {
  std::vector<WorkerEvent> events;
  WorkerPool pool({program_, dir_, 2, false, false, ".csv"},
                  [&](const WorkItem&) { return dir_ + "/records"; },
                  [&](const WorkerEvent& e) { events.push_back(e); });
  std::deque<WorkItem> todo = {item("hang", 60), item("hang", 60), item("hang", 60)};
  pool.serve(todo);
  EXPECT_EQ(pool.busy_shards().size(), 2u);
  EXPECT_EQ(todo.size(), 1u);
  pool.stop_all();  // kills them without an event
  EXPECT_TRUE(pool.empty());
  EXPECT_TRUE(events.empty());
}

}  // namespace
}  // namespace ra::runner
