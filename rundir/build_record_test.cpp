// build.json's one reader and the walk of the build cache: the fields as written, hidden and
// half-made folders skipped, a renamed folder named by its folder, damage named by file and key.
#include "rundir/build_record.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "util/errors.h"

namespace ra::rundir {
namespace {

namespace fs = std::filesystem;

struct TempCache {
  fs::path path;
  TempCache() {
    path = fs::temp_directory_path() / ("ra-build-record-" + std::to_string(::getpid()) + "-" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~TempCache() { fs::remove_all(path); }
  std::string build(const std::string& folder, const std::string& json) const {
    fs::create_directories(path / folder);
    std::ofstream((path / folder / "build.json").string()) << json;
    return (path / folder).string();
  }
};

const char* kHeader = R"("schema": "renderaudit-driver-build", "schema_version": 1)";

TEST(BuildRecord, ReadsWhatTheWritersWrite) {
  TempCache c;
  const std::string fetched = c.build("mesa-25.0.7", std::string("{") + kHeader + R"(,
    "name": "mesa-25.0.7", "suite": "bookworm-backports", "origin": "Debian",
    "debian_version": "25.0.7-2~bpo12+1", "fetched_utc": "2026-01-02T03:04:05Z",
    "gl": {"osmesa": {"version": "4.5 (Compatibility Profile) Mesa 25.0.7"},
           "egl": {"error": "no EGL"}},
    "files": ["usr/lib/x86_64-linux-gnu/libOSMesa.so.8"]})");
  const BuildRecord f = read_build_record(fetched);
  EXPECT_EQ(f.name, "mesa-25.0.7");
  EXPECT_EQ(f.suite, "bookworm-backports");
  EXPECT_EQ(f.origin, "Debian");
  EXPECT_EQ(f.debian_version, "25.0.7-2~bpo12+1");
  EXPECT_EQ(f.osmesa_version, "4.5 (Compatibility Profile) Mesa 25.0.7");
  EXPECT_EQ(f.egl_version, "");
  ASSERT_EQ(f.files.size(), 1u);
  EXPECT_EQ(f.files[0], "usr/lib/x86_64-linux-gnu/libOSMesa.so.8");
  EXPECT_TRUE(f.commit.empty());
  EXPECT_FALSE(f.from_git);

  const std::string built = c.build("mesa-abc", std::string("{") + kHeader + R"(,
    "name": "mesa-abc", "origin": "source", "suite": "",
    "source_build": {"source": "/src/mesa", "git": true, "clean": true, "commit": "abc123",
                     "version": "25.1.0-devel", "key": "k1"}})");
  const BuildRecord s = read_build_record(built);
  EXPECT_EQ(s.origin, "source");
  EXPECT_EQ(s.source, "/src/mesa");
  EXPECT_EQ(s.commit, "abc123");
  EXPECT_EQ(s.version, "25.1.0-devel");
  EXPECT_EQ(s.key, "k1");
  EXPECT_TRUE(s.from_git);
  EXPECT_TRUE(s.clean);
}

TEST(BuildRecord, DamageIsNamedByFileAndKey) {
  TempCache c;
  const auto message = [](const std::string& dir) {
    try {
      read_build_record(dir);
    } catch (const util::UserError& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  const std::string cut = c.build("cut", "{\"name\": \"mesa");
  EXPECT_EQ(message(cut).rfind(cut + "/build.json: ", 0), 0u) << message(cut);
  const std::string typed = c.build("typed", R"({"name": "x", "source_build": {"clean": "yes"}})");
  EXPECT_NE(message(typed).find("\"clean\" must be true or false"), std::string::npos)
      << message(typed);
  const std::string other = c.build("other", R"({"schema": "renderaudit-audit", "schema_version": 2})");
  EXPECT_NE(message(other).find("expected schema renderaudit-driver-build version 1"),
            std::string::npos)
      << message(other);
  EXPECT_NE(message((c.path / "none").string()).find("none/build.json"), std::string::npos);
}

TEST(BuildRecord, TheCacheListsBuildFoldersOnly) {
  TempCache c;
  c.build("mesa-b", std::string("{") + kHeader + R"(, "name": "mesa-b", "suite": "s"})");
  c.build("renamed", std::string("{") + kHeader + R"(, "name": "mesa-old", "suite": "s"})");
  c.build(".source-123", std::string("{") + kHeader + R"(, "name": "half-made"})");
  c.build("damaged", "not json");
  fs::create_directories(c.path / "no-record");
  const std::vector<BuildRecord> listed = list_cached_builds(c.path.string());
  ASSERT_EQ(listed.size(), 3u);
  EXPECT_EQ(listed[0].name, "damaged");
  EXPECT_FALSE(listed[0].damaged.empty());
  EXPECT_EQ(listed[1].name, "mesa-b");
  EXPECT_EQ(listed[1].recorded_name, "");
  EXPECT_EQ(listed[2].name, "renamed");
  EXPECT_EQ(listed[2].recorded_name, "mesa-old");
  EXPECT_TRUE(list_cached_builds((c.path / "absent").string()).empty());
  std::ofstream((c.path / "a-file").string()) << "x";
  EXPECT_THROW(list_cached_builds((c.path / "a-file").string()), util::UserError);
}

TEST(BuildRecord, TheNewestBuildOfASuite) {
  TempCache c;
  const std::string older = c.build("mesa-1", std::string("{") + kHeader + R"(, "suite": "s"})");
  const std::string newer = c.build("mesa-2", std::string("{") + kHeader + R"(, "suite": "s"})");
  c.build("mesa-3", std::string("{") + kHeader + R"(, "suite": "t"})");
  const auto now = fs::file_time_type::clock::now();
  fs::last_write_time(fs::path(older) / "build.json", now - std::chrono::hours(2));
  fs::last_write_time(fs::path(newer) / "build.json", now - std::chrono::hours(1));
  ::setenv("RENDERAUDIT_BUILD_CACHE", c.path.c_str(), 1);
  EXPECT_EQ(cached_build_of_suite("s"), newer);
  EXPECT_EQ(cached_build_of_suite("u"), "");
  ::unsetenv("RENDERAUDIT_BUILD_CACHE");
}

}  // namespace
}  // namespace ra::rundir
