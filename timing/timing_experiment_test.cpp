// Tests of the timing study's experiment file (timing_experiment.h).
#include "timing/timing_experiment.h"

#include <gtest/gtest.h>

#include <cmath>

#include "util/errors.h"

namespace ra::timing {
namespace {

const char* kScene = R"(
[[scene]]
kind = "forest"
trees = 3
)";

TEST(TimingExperiment, DefaultsAndValues) {
  const TimingSettings s = parse_timing_experiment(
      std::string("[timing]\nwindow = [320, 240]\nrepetitions = 7\ncache_size = 24\n"
                  "platforms = [\"osmesa-llvmpipe\", \"osmesa-softpipe\"]\n"
                  "[timing.platform.osmesa-softpipe]\nobject_samples = 100\n") + kScene,
      "dir/exp.toml");
  EXPECT_EQ(s.name, "exp");
  EXPECT_EQ(s.camera.width, 320);
  EXPECT_EQ(s.camera.height, 240);
  EXPECT_EQ(s.cache_size, 24u);
  EXPECT_EQ(s.work_for("osmesa-llvmpipe").repetitions, 7);
  EXPECT_EQ(s.work_for("osmesa-llvmpipe").object_samples, 10000);
  EXPECT_EQ(s.work_for("osmesa-softpipe").object_samples, 100);
  EXPECT_EQ(s.work_for("osmesa-softpipe").repetitions, 7);
  EXPECT_EQ(s.work.system_task_renders, 10000);
  ASSERT_EQ(s.scenes.size(), 1u);
  EXPECT_EQ(s.scenes[0].kind, "forest");
  const TimingSettings d = parse_timing_experiment(kScene, "d.toml");
  EXPECT_EQ(d.camera.width, 640);
  EXPECT_EQ(d.camera.height, 480);
  EXPECT_EQ(d.cache_size, 16u);
  EXPECT_EQ(d.platforms, std::vector<std::string>{"osmesa-llvmpipe"});
  EXPECT_EQ(d.system_task_scene, "");
  EXPECT_EQ(d.system_task_frame, -1);
  const TimingSettings t = parse_timing_experiment(
      std::string("[timing]\nsystem_task_scene = \"forest\"\nsystem_task_frame = 3\n") + kScene,
      "t.toml");
  EXPECT_EQ(t.system_task_scene, "forest");
  EXPECT_EQ(t.system_task_frame, 3);
}

std::string error_of(const std::string& text) {
  try {
    parse_timing_experiment(text, "bad.toml");
  } catch (const util::UserError& e) {
    return e.what();
  }
  return "";
}

// Bad input names the file, line and column, the key and what is allowed.
TEST(TimingExperiment, BadInputIsLocated) {
  EXPECT_EQ(error_of(std::string("[timing]\nrepetitions = 0\n") + kScene),
            "bad.toml:2:15: 'timing.repetitions' = 0 is out of range (allowed: 1 to 1000)");
  EXPECT_NE(error_of(std::string("[timing]\nrepetition = 3\n") + kScene)
                .find("bad.toml:2:1: unknown key 'timing.repetition'"),
            std::string::npos);
  EXPECT_NE(error_of(std::string("[timing]\nplatforms = [\"reference\"]\n") + kScene)
                .find("allowed: osmesa-llvmpipe, osmesa-softpipe"),
            std::string::npos);
  EXPECT_NE(error_of("[timing]\nrepetitions = 3\n").find("no [[scene]]"), std::string::npos);
  EXPECT_NE(error_of(std::string("[timing]\nwindow = [640]\n") + kScene).find("[width, height]"),
            std::string::npos);
  EXPECT_NE(error_of(std::string("[timing]\nfov_deg = 180\n") + kScene).find("0 < fov_deg < 180"),
            std::string::npos);
  EXPECT_NE(error_of(std::string("[timing.platform.osmesa-softpipe]\nrepetitions = 2\n") + kScene)
                .find("not in timing.platforms"),
            std::string::npos);
  EXPECT_EQ(error_of(std::string("[timing]\nsystem_task_scene = \"city\"\n") + kScene),
            "bad.toml:2:21: 'timing.system_task_scene' must name a scene of the file (allowed: forest)");
  EXPECT_NE(error_of(std::string("[timing]\nsystem_task_frame = 100000\n") + kScene)
                .find("'timing.system_task_frame' = 100000 is out of range (allowed: 0 to "),
            std::string::npos);
  EXPECT_NE(error_of("[[scene]]\nkind = \"castle\"\n").find("bad.toml:2"), std::string::npos);
}

// study_runs (timing/repeated_runs.h): independent repeated runs of the whole study.
TEST(TimingExperiment, StudyRuns) {
  EXPECT_EQ(parse_timing_experiment(kScene, "d.toml").study_runs, 1);  // the single study
  const TimingSettings s =
      parse_timing_experiment(std::string("[timing]\nstudy_runs = 3\nrepetitions = 7\n") + kScene,
                              "e.toml");
  EXPECT_EQ(s.study_runs, 3);
  EXPECT_EQ(s.work.repetitions, 7);  // a separate knob: timed draws per measurement
  EXPECT_EQ(parse_timing_experiment(std::string("[timing]\nstudy_runs = 100\n") + kScene, "e.toml")
                .study_runs,
            100);
  EXPECT_EQ(error_of(std::string("[timing]\nstudy_runs = 0\n") + kScene),
            "bad.toml:2:14: 'timing.study_runs' = 0 is out of range (allowed: 1 to 100)");
  EXPECT_EQ(error_of(std::string("[timing]\nstudy_runs = 101\n") + kScene),
            "bad.toml:2:14: 'timing.study_runs' = 101 is out of range (allowed: 1 to 100)");
  EXPECT_NE(error_of(std::string("[timing]\nstudy_runs = \"3\"\n") + kScene).find("bad.toml:2:14"),
            std::string::npos);
  // a study-wide key: not one of the per-platform overrides
  EXPECT_NE(error_of(std::string("[timing.platform.osmesa-llvmpipe]\nstudy_runs = 2\n") + kScene)
                .find("unknown key 'timing.platform.osmesa-llvmpipe.study_runs'"),
            std::string::npos);
}

}  // namespace
}  // namespace ra::timing
