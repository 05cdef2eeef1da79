// The build cache's sizes and removal (build_cache.h), on a temporary cache of fake builds: a
// build.json and a file of known size each, nothing that draws.
#include "builds/build_cache.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/file.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

#include "builds/build_fetch.h"
#include "builds/source_build.h"
#include "util/errors.h"

namespace ra::builds {
namespace {

namespace fs = std::filesystem;

struct FakeCache {
  fs::path dir;
  explicit FakeCache(const std::string& tag)
      : dir(fs::path(::testing::TempDir()) /
            ("renderaudit-build-cache-" + tag + "-" + std::to_string(::getpid()))) {
    fs::remove_all(dir);
    fs::create_directories(dir);
  }
  ~FakeCache() { fs::remove_all(dir); }
  // A build of `bytes` bytes of library; `source`: a source build of that tree.
  void add(const std::string& name, std::size_t bytes, const std::string& source = "") const {
    fs::create_directories(dir / name / "lib");
    std::ofstream(dir / name / "lib" / "libOSMesa.so.8") << std::string(bytes, 'x');
    std::ofstream(dir / name / "build.json")
        << (source.empty()
                ? R"({"name": ")" + name +
                      R"(", "origin": "Debian", "suite": "bookworm", "files": []})"
                : R"({"name": ")" + name + R"(", "origin": "source", "suite": "", "files": [],
                     "source_build": {"source": ")" +
                      source + R"("}})");
  }
};

std::string error_of(const std::function<void()>& call) {
  try {
    call();
  } catch (const util::UserError& e) {
    return e.what();
  }
  return "";
}

TEST(BuildCache, SizeTextHasThreeDigitsAtMostAndBinaryUnits) {
  EXPECT_EQ(size_text(0), "0 B");
  EXPECT_EQ(size_text(999), "999 B");
  EXPECT_EQ(size_text(4096), "4.0 KiB");
  EXPECT_EQ(size_text(125'200'000), "119 MiB");    // du -h: 119M
  EXPECT_EQ(size_text(1'073'000'000), "1.0 GiB");  // not "1023 MiB"
  EXPECT_EQ(size_text(12'300'000'000), "11 GiB");
}

// Removing one of two builds leaves the other whole, nothing hidden behind, and the cache's
// total is what the other holds.
TEST(BuildCache, RemovingOneBuildLeavesTheOtherAndTheTotalFalls) {
  const FakeCache cache("two");
  cache.add("mesa-a", 300'000);
  cache.add("mesa-b", 100'000);
  const std::uintmax_t a = disk_usage((cache.dir / "mesa-a").string());
  const std::uintmax_t b = disk_usage((cache.dir / "mesa-b").string());
  EXPECT_GE(a, 300'000u);
  EXPECT_GE(b, 100'000u);
  const CacheUsage before = cache_usage(cache.dir.string());
  EXPECT_EQ(before.builds, a + b);
  EXPECT_GE(before.total, a + b);

  const std::vector<RemovedBuild> removed = remove_builds(cache.dir.string(), {"mesa-a"});
  ASSERT_EQ(removed.size(), 1u);
  EXPECT_EQ(removed[0].name, "mesa-a");
  EXPECT_EQ(removed[0].bytes, a);
  const std::vector<rundir::BuildRecord> left = rundir::list_cached_builds(cache.dir.string());
  ASSERT_EQ(left.size(), 1u);
  EXPECT_EQ(left[0].name, "mesa-b");
  EXPECT_TRUE(fs::exists(cache.dir / "mesa-b" / "lib" / "libOSMesa.so.8"));
  for (const auto& e : fs::directory_iterator(cache.dir))
    EXPECT_EQ(e.path().filename(), "mesa-b") << "left behind: " << e.path();
  const CacheUsage after = cache_usage(cache.dir.string());
  EXPECT_EQ(after.builds, b);
  EXPECT_EQ(after.total, before.total - a);
  EXPECT_EQ(after.unfinished, 0u);
}

// An unknown name removes nothing, even beside a good one, and the message names the builds the
// cache holds.
TEST(BuildCache, AnUnknownNameRemovesNothingAndNamesTheBuildsThere) {
  const FakeCache cache("unknown");
  cache.add("mesa-a", 1000);
  cache.add("mesa-b", 1000);
  const std::string e = error_of([&] {
    remove_builds(cache.dir.string(), {"mesa-a", "mesa-25.0.7"});
  });
  EXPECT_NE(e.find("no build 'mesa-25.0.7' in " + cache.dir.string()), std::string::npos) << e;
  EXPECT_NE(e.find("it holds mesa-a, mesa-b"), std::string::npos) << e;
  EXPECT_EQ(rundir::list_cached_builds(cache.dir.string()).size(), 2u);

  const FakeCache empty("empty");
  EXPECT_NE(
      error_of([&] { remove_builds(empty.dir.string(), {"x"}); }).find("the cache holds no builds"),
      std::string::npos);
}

// A source build whose tree a bisection holds is refused, naming the holder; once the bisection
// ends it goes.
TEST(BuildCache, ABuildWhoseSourceTreeIsHeldIsRefused) {
  const FakeCache cache("held");
  const FakeCache source("held-tree");  // a tree without git: it holds its own lock
  const fs::path tree = source.dir;
  cache.add("mesa-0123456789ab", 1000, tree.string());
  {
    const auto lock = lock_source_tree(tree.string(), "bisect");
    EXPECT_NE(build_in_use_by((cache.dir / "mesa-0123456789ab").string()).find("(bisect)"),
              std::string::npos);
    const std::string e =
        error_of([&] { remove_builds(cache.dir.string(), {"mesa-0123456789ab"}); });
    EXPECT_NE(e.find("mesa-0123456789ab is in use: its source tree " + tree.string() +
                     " is held by process " + std::to_string(::getpid()) + " (bisect)"),
              std::string::npos)
        << e;
    EXPECT_TRUE(fs::exists(cache.dir / "mesa-0123456789ab" / "build.json"));
  }
  EXPECT_EQ(build_in_use_by((cache.dir / "mesa-0123456789ab").string()), "");
  EXPECT_EQ(remove_builds(cache.dir.string(), {"mesa-0123456789ab"}).size(), 1u);
  EXPECT_FALSE(fs::exists(cache.dir / "mesa-0123456789ab"));
}

// What an interrupted removal left (a hidden .removing-* folder) is no build, counts as unfinished
// and goes with the next removal.
TEST(BuildCache, WhatAnInterruptedRemovalLeftIsNoBuildAndGoesNextTime) {
  const FakeCache cache("leftover");
  cache.add("mesa-a", 1000);
  cache.add("mesa-b", 1000);
  fs::rename(cache.dir / "mesa-a", cache.dir / ".removing-mesa-a-1");
  ASSERT_EQ(rundir::list_cached_builds(cache.dir.string()).size(), 1u);
  EXPECT_GT(cache_usage(cache.dir.string()).unfinished, 0u);
  remove_builds(cache.dir.string(), {"mesa-b"});
  EXPECT_TRUE(fs::is_empty(cache.dir));
}

// A build a process draws with (a watch night's two builds) is refused, and so is a request that
// names it beside another build; once the user ends, it goes.
TEST(BuildCache, ABuildDrawnWithIsRefusedUntilItsUserEnds) {
  const FakeCache cache("drawn");
  cache.add("mesa-a", 1000);
  cache.add("mesa-b", 1000);
  {
    const BuildInUse night((cache.dir / "mesa-a").string());
    const BuildInUse another_user((cache.dir / "mesa-a").string());  // users share the build
    const std::string e = error_of([&] { remove_builds(cache.dir.string(), {"mesa-b", "mesa-a"}); });
    EXPECT_NE(e.find("builds remove: mesa-a is in use: a process draws with it now"),
              std::string::npos)
        << e;
    EXPECT_NE(e.find("nothing was removed"), std::string::npos) << e;
    EXPECT_EQ(rundir::list_cached_builds(cache.dir.string()).size(), 2u);
  }
  EXPECT_EQ(remove_builds(cache.dir.string(), {"mesa-b", "mesa-a"}).size(), 2u);
  EXPECT_TRUE(fs::is_empty(cache.dir));
  // A build that is gone cannot be held: the user is told, not left to draw with nothing.
  EXPECT_NE(error_of([&] { BuildInUse gone((cache.dir / "mesa-a").string()); }).find("is gone"),
            std::string::npos);
}

// A removal running now (its folder renamed aside, its lock held) is not another removal's
// leftover: the second's clean-up leaves it to finish.
TEST(BuildCache, ARemovalRunningNowIsLeftAloneByAnotherOnesCleanUp) {
  const FakeCache cache("concurrent");
  cache.add("mesa-a", 1000);
  cache.add("mesa-b", 1000);
  const fs::path aside = cache.dir / ".removing-mesa-a-4242";
  fs::rename(cache.dir / "mesa-a", aside);
  const int fd = ::open(BuildInUse::lock_path(aside.string()).c_str(), O_RDWR | O_CREAT, 0644);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(::flock(fd, LOCK_EX | LOCK_NB), 0);
  EXPECT_EQ(remove_builds(cache.dir.string(), {"mesa-b"}).size(), 1u);
  EXPECT_TRUE(fs::exists(aside / "build.json")) << "the running removal's folder was deleted";
  ::close(fd);  // that removal died: its folder is a leftover now
  cache.add("mesa-c", 1000);
  remove_builds(cache.dir.string(), {"mesa-c"});
  EXPECT_TRUE(fs::is_empty(cache.dir));
}

// A build folder renamed by hand is listed and removed by its folder's name (what PLATFORM@NAME
// draws); a request naming what build.json says removes nothing at all.
TEST(BuildCache, ABuildRenamedByHandIsItsFolderAndAPartialRequestRemovesNothing) {
  const FakeCache cache("renamed");
  cache.add("mesa-aaa", 1000);
  cache.add("mesa-bbb", 1000);
  fs::rename(cache.dir / "mesa-aaa", cache.dir / "mesa-ccc");
  const std::vector<rundir::BuildRecord> listed = rundir::list_cached_builds(cache.dir.string());
  ASSERT_EQ(listed.size(), 2u);
  EXPECT_EQ(listed[0].name, "mesa-bbb");
  EXPECT_EQ(listed[1].name, "mesa-ccc");
  EXPECT_EQ(listed[1].recorded_name, "mesa-aaa");
  const std::string e = error_of([&] { remove_builds(cache.dir.string(), {"mesa-bbb", "mesa-aaa"}); });
  EXPECT_NE(e.find("no build 'mesa-aaa' in " + cache.dir.string() + "; it holds mesa-bbb, mesa-ccc"),
            std::string::npos)
      << e;
  EXPECT_TRUE(fs::exists(cache.dir / "mesa-bbb" / "build.json"));
  const std::vector<RemovedBuild> removed =
      remove_builds(cache.dir.string(), {"mesa-bbb", "mesa-ccc"});
  ASSERT_EQ(removed.size(), 2u);
  EXPECT_EQ(removed[1].name, "mesa-ccc");
  EXPECT_EQ(removed[1].left, "");
  EXPECT_TRUE(fs::is_empty(cache.dir));
}

}  // namespace
}  // namespace ra::builds
