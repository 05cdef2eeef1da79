// `run --expect-renderer` and the one-driver-per-run rule (renderer_check.cpp), on driver files
// written by hand into a temporary run directory: which platforms are checked, what the messages
// name, a file being written looked at again, and the refusals of require_run_driver.
#include "platforms/renderer_check.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <string>

#include "platforms/platform.h"
#include "rundir/run_folder.h"
#include "util/errors.h"

namespace ra::platforms {
namespace {

namespace fs = std::filesystem;

// A fresh run directory with an empty drivers/ folder, removed when the test ends.
class RunWithDrivers : public ::testing::Test {
 protected:
  void SetUp() override {
    static std::atomic<int> counter{0};
    dir_ = (fs::temp_directory_path() / ("ra_renderer_check_" + std::to_string(::getpid()) +
                                          "_" + std::to_string(counter++)))
               .string();
    fs::remove_all(dir_);
    fs::create_directories(rundir::run_folder::drivers(dir_));
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  void write_driver(const std::string& platform, const std::string& json) {
    std::ofstream(rundir::run_folder::driver(dir_, platform)) << json;
  }
  // The message of the UserError that require_run_driver throws, or "" when it throws none.
  std::string refusal(const std::string& platform, const DriverInfo& loaded) {
    try {
      require_run_driver(dir_, platform, loaded);
    } catch (const util::UserError& e) {
      return e.what();
    }
    return "";
  }
  std::string dir_;
};

DriverInfo loaded(const std::string& renderer, const std::string& version) {
  DriverInfo d;
  d.renderer = renderer;
  d.version = version;
  d.backend = "OSMesa (libOSMesa.so.8)";
  return d;
}

// Each driver platform's file is checked once; the first mismatch names the platform, the
// renderer found and the pattern.
TEST_F(RunWithDrivers, AMismatchNamesThePlatformTheRendererAndThePattern) {
  write_driver("osmesa-llvmpipe", R"j({"renderer": "llvmpipe (LLVM 15.0.6, 256 bits)"})j");
  write_driver("osmesa-softpipe", R"j({"renderer": "softpipe"})j");
  RendererCheck check(dir_, "llvmpipe");
  EXPECT_EQ(check.mismatch(),
            "osmesa-softpipe: GL_RENDERER 'softpipe' does not match --expect-renderer 'llvmpipe'");
  EXPECT_EQ(check.mismatch(), "");  // each file is judged once
  // A platform whose file appears later is checked when it appears.
  write_driver("egl-softpipe", R"j({"renderer": "softpipe"})j");
  EXPECT_EQ(check.mismatch(),
            "egl-softpipe: GL_RENDERER 'softpipe' does not match --expect-renderer 'llvmpipe'");
}

// The pattern is an ECMAScript regex searched anywhere in the renderer.
TEST_F(RunWithDrivers, ThePatternIsARegexSearchedInTheRenderer) {
  write_driver("osmesa-llvmpipe", R"j({"renderer": "llvmpipe (LLVM 15.0.6, 256 bits)"})j");
  EXPECT_EQ(RendererCheck(dir_, "LLVM 1[5-9]").mismatch(), "");
  EXPECT_EQ(RendererCheck(dir_, "^llvmpipe").mismatch(), "");
  EXPECT_EQ(RendererCheck(dir_, "^LLVM").mismatch(),
            "osmesa-llvmpipe: GL_RENDERER 'llvmpipe (LLVM 15.0.6, 256 bits)' does not match "
            "--expect-renderer '^LLVM'");
}

// An empty pattern checks nothing; the project's own platforms and unknown names are never
// checked; files other than *.json are ignored.
TEST_F(RunWithDrivers, OnlyDriverPlatformsAreChecked) {
  write_driver("osmesa-softpipe", R"j({"renderer": "softpipe"})j");
  EXPECT_EQ(RendererCheck(dir_, "").mismatch(), "");
  fs::remove(rundir::run_folder::driver(dir_, "osmesa-softpipe"));
  write_driver("reference", R"j({"renderer": "renderaudit reference rasterizer"})j");
  write_driver("faulty", R"j({"renderer": "renderaudit faulty test platform"})j");
  write_driver("no-such-platform", R"j({"renderer": "softpipe"})j");
  std::ofstream(rundir::run_folder::drivers(dir_) + "/osmesa-softpipe.txt") << "softpipe";
  EXPECT_EQ(RendererCheck(dir_, "llvmpipe").mismatch(), "");
  // No drivers folder at all: nothing to say yet.
  fs::remove_all(rundir::run_folder::drivers(dir_));
  EXPECT_EQ(RendererCheck(dir_, "llvmpipe").mismatch(), "");
}

// A file that does not parse yet (a worker is writing it) is looked at again next time.
TEST_F(RunWithDrivers, AFileBeingWrittenIsReadAgainLater) {
  write_driver("osmesa-softpipe", R"j({"renderer": "soft)j");
  RendererCheck check(dir_, "llvmpipe");
  EXPECT_EQ(check.mismatch(), "");
  write_driver("osmesa-softpipe", R"j({"renderer": "softpipe"})j");
  EXPECT_EQ(check.mismatch(),
            "osmesa-softpipe: GL_RENDERER 'softpipe' does not match --expect-renderer 'llvmpipe'");
}

TEST(RendererCheck, AnInvalidRegexIsAUserError) {
  try {
    RendererCheck("/nonexistent", "llvm(pipe");
    FAIL() << "no error";
  } catch (const util::UserError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("--expect-renderer 'llvm(pipe': not a valid regular "
                                          "expression (", 0),
              0u)
        << e.what();
  }
}

// The same renderer and version as the run's driver file: nothing to say. Another renderer or
// version: a driver mismatch naming both and the build folder. No file yet, or a platform without
// a driver: nothing is checked.
TEST_F(RunWithDrivers, ADifferentDriverThanTheRunsIsRefusedNamingBoth) {
  EXPECT_EQ(refusal("osmesa-llvmpipe", loaded("llvmpipe", "4.5 (Compatibility Profile) Mesa 22.3.6")),
            "");  // no driver file yet: the first worker writes it
  write_driver("osmesa-llvmpipe",
               R"j({"renderer": "llvmpipe", "version": "4.5 (Compatibility Profile) Mesa 22.3.6",
                   "build": {"folder": "/opt/mesa-22.3.6"}})j");
  EXPECT_EQ(refusal("osmesa-llvmpipe", loaded("llvmpipe", "4.5 (Compatibility Profile) Mesa 22.3.6")),
            "");
  const std::string other =
      refusal("osmesa-llvmpipe", loaded("llvmpipe", "4.5 (Compatibility Profile) Mesa 25.0.7"));
  EXPECT_EQ(other.rfind(std::string(rundir::kDriverMismatch) + ": osmesa-llvmpipe: this process "
                        "loaded GL_RENDERER 'llvmpipe' GL_VERSION '4.5 (Compatibility Profile) "
                        "Mesa 25.0.7' (OSMesa (libOSMesa.so.8)), but the run's records were made "
                        "with GL_RENDERER 'llvmpipe' GL_VERSION '4.5 (Compatibility Profile) Mesa "
                        "22.3.6' (",
                        0),
            0u)
      << other;
  EXPECT_NE(other.find(", build folder /opt/mesa-22.3.6); nothing was drawn"), std::string::npos)
      << other;
  EXPECT_NE(refusal("osmesa-llvmpipe", loaded("softpipe", "4.5 (Compatibility Profile) Mesa 22.3.6")),
            "");
  // The reference platform draws with no driver: its file, whatever it says, is not compared.
  write_driver("reference", R"j({"renderer": "something else", "version": "0"})j");
  EXPECT_EQ(refusal("reference", loaded("renderaudit reference rasterizer", "exact")), "");
}

// A driver file that is not JSON, or whose library list is malformed, is refused with its path.
TEST_F(RunWithDrivers, AnUnreadableOrMalformedDriverFileIsRefusedWithItsPath) {
  const std::string path = rundir::run_folder::driver(dir_, "osmesa-llvmpipe");
  write_driver("osmesa-llvmpipe", "{not json");
  const std::string unreadable = refusal("osmesa-llvmpipe", loaded("llvmpipe", "1"));
  EXPECT_EQ(unreadable.rfind(path + ": not a readable driver file (", 0), 0u) << unreadable;
  write_driver("osmesa-llvmpipe",
               R"j({"renderer": "llvmpipe", "version": "1", "build": {"libraries": [{"path": 3}]}})j");
  EXPECT_EQ(refusal("osmesa-llvmpipe", loaded("llvmpipe", "1")),
            path + ": build.libraries: each entry needs a \"path\" and an \"fnv1a64\" string");
  // A recorded library this process has not loaded cannot differ: accepted.
  write_driver("osmesa-llvmpipe",
               R"j({"renderer": "llvmpipe", "version": "1", "build": {"libraries":
                   [{"path": "/nowhere/libnot-a-driver-at-all.so.1", "fnv1a64": "0123456789abcdef"}]}})j");
  EXPECT_EQ(refusal("osmesa-llvmpipe", loaded("llvmpipe", "1")), "");
}

}  // namespace
}  // namespace ra::platforms
