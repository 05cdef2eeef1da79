// `renderaudit builds list` and `builds remove` on a temporary cache of two fake builds (a
// build.json and a library-sized file each; nothing draws): the size column, the total, a removal
// that leaves the other build, an unknown name answered with the names the cache holds, and a
// folder renamed by hand.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "builds/build_cache.h"
#include "tests/cli_harness.h"

namespace {

namespace fs = std::filesystem;
using ra::testing_cli::fresh_dir;
using ra::testing_cli::Outcome;
using ra::testing_cli::run_renderaudit;

void fake_build(const std::string& cache, const std::string& name, std::size_t bytes) {
  fs::create_directories(cache + "/" + name + "/lib");
  std::ofstream(cache + "/" + name + "/lib/libOSMesa.so.8") << std::string(bytes, 'x');
  std::ofstream(cache + "/" + name + "/build.json")
      << R"({"name": ")" << name
      << R"(", "origin": "Debian", "suite": "bookworm", "debian_version": "1", "files": []})";
}

TEST(BuildsCommand, ListGivesSizesAndATotalAndRemoveLeavesTheOther) {
  const std::string cache = fresh_dir("builds_command_two") + "/cache";
  fake_build(cache, "mesa-big", 2'000'000);
  fake_build(cache, "mesa-small", 300'000);
  const std::string big = ra::builds::size_text(ra::builds::disk_usage(cache + "/mesa-big"));
  const std::string small = ra::builds::size_text(ra::builds::disk_usage(cache + "/mesa-small"));

  const Outcome list = run_renderaudit("builds list --cache " + cache);
  ASSERT_EQ(list.exit_code, 0) << list.output;
  const auto column = [](std::string size) { return std::string(7 - size.size(), ' ') + size; };
  EXPECT_NE(list.output.find("mesa-big    " + column(big) + "  (Debian 1, suite bookworm"),
            std::string::npos)
      << list.output;
  EXPECT_NE(list.output.find("mesa-small  " + column(small) + "  (Debian 1"), std::string::npos)
      << list.output;
  const std::string total_before = ra::builds::size_text(ra::builds::cache_usage(cache).total);
  EXPECT_NE(list.output.find("total " + total_before + " in " + cache + ": 2 builds "),
            std::string::npos)
      << list.output;

  const Outcome removed = run_renderaudit("builds remove mesa-big --cache " + cache);
  ASSERT_EQ(removed.exit_code, 0) << removed.output;
  EXPECT_NE(removed.output.find("removed mesa-big (" + big + ")"), std::string::npos)
      << removed.output;
  EXPECT_FALSE(fs::exists(cache + "/mesa-big"));
  EXPECT_TRUE(fs::exists(cache + "/mesa-small/lib/libOSMesa.so.8"));

  const Outcome after = run_renderaudit("builds list --cache " + cache);
  ASSERT_EQ(after.exit_code, 0) << after.output;
  EXPECT_EQ(after.output.find("mesa-big"), std::string::npos) << after.output;
  const std::string total_after = ra::builds::size_text(ra::builds::cache_usage(cache).total);
  EXPECT_NE(after.output.find("total " + total_after + " in " + cache + ": 1 build " + small),
            std::string::npos)
      << after.output;
}

TEST(BuildsCommand, RemovingAnUnknownNameNamesTheBuildsThereAndRemovesNothing) {
  const std::string cache = fresh_dir("builds_command_unknown") + "/cache";
  fake_build(cache, "mesa-a", 1000);
  fake_build(cache, "mesa-b", 1000);
  const Outcome o = run_renderaudit("builds remove mesa-a mesa-25.0.7 --cache " + cache);
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_NE(o.output.find("no build 'mesa-25.0.7' in " + cache + "; it holds mesa-a, mesa-b"),
            std::string::npos)
      << o.output;
  EXPECT_TRUE(fs::exists(cache + "/mesa-a/build.json"));
  EXPECT_TRUE(fs::exists(cache + "/mesa-b/build.json"));
}

// A folder renamed by hand is the build of its new name: listed and removed by it (exit 0, each
// removal said); a request naming what build.json says removes nothing at all (exit 2).
TEST(BuildsCommand, ABuildRenamedByHandIsItsFolderAndARemovalThatSucceededExits0) {
  const std::string cache = fresh_dir("builds_command_renamed") + "/cache";
  fake_build(cache, "mesa-aaa", 1000);
  fake_build(cache, "mesa-bbb", 1000);
  fs::rename(cache + "/mesa-aaa", cache + "/mesa-ccc");
  const Outcome list = run_renderaudit("builds list --cache " + cache);
  ASSERT_EQ(list.exit_code, 0) << list.output;
  EXPECT_NE(list.output.find("mesa-ccc "), std::string::npos) << list.output;
  EXPECT_NE(list.output.find("renamed by hand: its build.json calls it mesa-aaa"),
            std::string::npos)
      << list.output;
  const Outcome partial = run_renderaudit("builds remove mesa-bbb mesa-aaa --cache " + cache);
  EXPECT_EQ(partial.exit_code, 2) << partial.output;
  EXPECT_NE(partial.output.find("no build 'mesa-aaa'"), std::string::npos) << partial.output;
  EXPECT_TRUE(fs::exists(cache + "/mesa-bbb/build.json")) << "removed part of the request";
  const Outcome both = run_renderaudit("builds remove mesa-bbb mesa-ccc --cache " + cache);
  EXPECT_EQ(both.exit_code, 0) << both.output;
  EXPECT_NE(both.output.find("removed mesa-bbb ("), std::string::npos) << both.output;
  EXPECT_NE(both.output.find("removed mesa-ccc ("), std::string::npos) << both.output;
  EXPECT_FALSE(fs::exists(cache + "/mesa-ccc"));
}

}  // namespace
