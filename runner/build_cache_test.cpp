// The build cache's sizes and removal (build_cache.h), on a temporary cache of fake builds: a
// build.json and a file of known size each, nothing that draws.
#include "runner/build_cache.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

#include "runner/build_fetch.h"
#include "runner/source_build.h"
#include "util/errors.h"

namespace ra::runner {
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
  const std::vector<BuildSummary> left = list_builds(cache.dir.string());
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
  EXPECT_EQ(list_builds(cache.dir.string()).size(), 2u);

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
  ASSERT_EQ(list_builds(cache.dir.string()).size(), 1u);
  EXPECT_GT(cache_usage(cache.dir.string()).unfinished, 0u);
  remove_builds(cache.dir.string(), {"mesa-b"});
  EXPECT_TRUE(fs::is_empty(cache.dir));
}

}  // namespace
}  // namespace ra::runner
