// `builds fetch --mirror` takes one archive address: nothing else can reach apt's sources list.
#include "builds/build_fetch.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "util/errors.h"

namespace ra::builds {
namespace {

TEST(BuildFetch, MirrorIsOneArchiveAddress) {
  for (const char* ok : {"http://deb.debian.org/debian", "https://mirror.example.org/debian/",
                         "http://127.0.0.1:9/debian", "file:/srv/debian"})
    EXPECT_TRUE(is_mirror_url(ok)) << ok;
  for (const char* bad :
       {"", "deb.debian.org/debian", "ftp://deb.debian.org/debian", "http://", "http:///debian",
        "http://deb.debian.org/debian bookworm main\ndeb [trusted=yes] http://evil.example/x",
        "http://deb.debian.org/debian\ndeb [trusted=yes] http://evil.example/x",
        "[trusted=yes] http://evil.example/x", "http://a b/debian", "http://host/de\tbian",
        "http://user@host/debian", "file:/", "http://host/\"x"})
    EXPECT_FALSE(is_mirror_url(bad)) << bad;
}

TEST(BuildFetch, AMirrorWithASecondSourceLineIsRefusedBeforeAnythingIsWritten) {
  FetchOptions o;
  o.suite = "bookworm-backports";
  o.mirror = "http://deb.debian.org/debian\ndeb [trusted=yes] http://127.0.0.1:9/x";
  o.cache = "/nonexistent/renderaudit-cache-never-created";
  try {
    fetch_build(o);
    FAIL() << "an injected source line was accepted";
  } catch (const util::UserError& e) {
    EXPECT_NE(std::string(e.what()).find("is not one Debian archive address"), std::string::npos);
  }
}

}  // namespace
}  // namespace ra::builds

namespace ra::builds {
namespace {

TEST(BuildFetch, ACacheThatIsAFileIsNamed) {
  const std::string file = ::testing::TempDir() + "renderaudit-cache-file-" + std::to_string(::getpid());
  { std::FILE* f = std::fopen(file.c_str(), "w"); ASSERT_NE(f, nullptr); std::fclose(f); }
  for (auto call : {+[](const std::string& c) { rundir::list_cached_builds(c); },
                    +[](const std::string& c) {
                      FetchOptions o;
                      o.suite = "bookworm-backports";
                      o.cache = c;
                      fetch_build(o);
                    }}) {
    try {
      call(file);
      ADD_FAILURE() << "a cache that is a file was accepted";
    } catch (const util::UserError& e) {
      EXPECT_NE(std::string(e.what()).find("is not a folder"), std::string::npos) << e.what();
    }
  }
  std::remove(file.c_str());
}

// A build whose build.json is not JSON, or holds a wrong type, is listed as damaged with the file
// and the reason, beside the good ones.
TEST(BuildFetch, ABuildWithABadBuildJsonIsListedAsDamaged) {
  namespace fs = std::filesystem;
  const fs::path cache =
      fs::path(::testing::TempDir()) / ("renderaudit-damaged-cache-" + std::to_string(::getpid()));
  fs::remove_all(cache);
  const auto write = [&](const std::string& name, const std::string& text) {
    fs::create_directories(cache / name);
    std::ofstream(cache / name / "build.json") << text;
  };
  write("good", R"({"name": "good", "suite": "bookworm", "files": []})");
  write("cut", R"({"name": "cut", "sui)");
  write("typed", R"({"name": 7})");
  const std::vector<rundir::BuildRecord> builds = rundir::list_cached_builds(cache.string());
  ASSERT_EQ(builds.size(), 3u);
  EXPECT_EQ(builds[0].name, "cut");
  EXPECT_EQ(builds[0].damaged.rfind((cache / "cut" / "build.json").string() + ": ", 0), 0u)
      << builds[0].damaged;
  EXPECT_NE(builds[0].damaged.find("parse error"), std::string::npos) << builds[0].damaged;
  EXPECT_EQ(builds[1].name, "good");
  EXPECT_EQ(builds[1].damaged, "");
  EXPECT_EQ(builds[1].suite, "bookworm");
  EXPECT_EQ(builds[2].name, "typed");
  EXPECT_NE(builds[2].damaged.find("\"name\" must be a string, not 7"), std::string::npos)
      << builds[2].damaged;
  fs::remove_all(cache);
}

}  // namespace
}  // namespace ra::builds
