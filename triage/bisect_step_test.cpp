// What of a bisection's step stands without a compiler or a driver: the commit's short name, and
// the experiment a step draws with (the run's own, its build added as one more TOML table).
#include "triage/bisect_step.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <toml++/toml.h>

#include "rundir/run_folder.h"
#include "triage/bisect.h"
#include "util/atomic_file.h"
#include "util/errors.h"

namespace fs = std::filesystem;

namespace ra::triage {
namespace {

TEST(BisectStep, ShortHashIsTheFirstTwelveDigits) {
  EXPECT_EQ(short_hash("0123456789abcdef0123456789abcdef01234567"), "0123456789ab");
  EXPECT_EQ(short_hash("abc"), "abc");  // a short name stays whole
}

// A run directory holding only `text` as its experiment (no manifest: nothing to check against).
std::string run_with_experiment(const std::string& text) {
  const fs::path dir =
      fs::temp_directory_path() / ("bisect-step-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  util::write_file_atomic(rundir::run_folder::experiment(dir.string()), text);
  return dir.string();
}

// The run's experiment kept byte for byte, then the step's build as [builds.bisect-step]; its
// directory written so that TOML reads back the very path, quotes and backslashes included.
TEST(BisectStep, TheStepsExperimentIsTheRunsWithTheBuildAdded) {
  std::string quick = util::read_file(std::string(RA_SOURCE_DIR) + "/experiments/quick.toml");
  while (!quick.empty() && quick.back() == '\n') quick.pop_back();  // the line end is added back
  const std::string dir = run_with_experiment(quick);
  const std::string build = "/tmp/a \"quoted\" build\\dir";
  const std::string text = bisect_step_experiment(dir, build);
  ASSERT_EQ(text.substr(0, quick.size() + 1), quick + "\n");
  EXPECT_EQ(text.substr(quick.size() + 1),
            "\n[builds.bisect-step]   # added by renderaudit bisect\n"
            "dir = \"/tmp/a \\\"quoted\\\" build\\\\dir\"\n");
  const toml::table doc = toml::parse(text);
  EXPECT_EQ(doc["builds"][kStepBuild]["dir"].value<std::string>(), build);
  fs::remove_all(dir);
}

// A run whose experiment cannot be read makes no step: the user is told which file.
TEST(BisectStep, ARunWithoutItsExperimentIsAnError) {
  const std::string dir = run_with_experiment("");
  fs::remove(rundir::run_folder::experiment(dir));
  EXPECT_THROW(bisect_step_experiment(dir, "/b"), util::UserError);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace ra::triage
