// Tests of the camera geometry of the timing study (timing_geometry.h) and of its experiment file
// (timing_experiment.h).
#include "timing/timing_geometry.h"

#include <gtest/gtest.h>

#include <cmath>

#include "util/errors.h"
#include "timing/timing_experiment.h"

namespace ra::timing {
namespace {

// A sphere straight ahead, wholly in view: the clipped alpha is the unclipped 2 asin(r / d).
TEST(TimingGeometry, ClippedAlphaOnAxis) {
  CameraSettings cam;
  const BoundingSphere s{{0, 0, 0}, 2.0};
  Viewpoint vp;
  vp.eye = {20, 0, 0};
  vp.target = {0, 0, 0};
  EXPECT_NEAR(clipped_alpha(look_at(vp), cam, s), 2 * std::asin(2.0 / 20.0), 1e-12);
  // eye inside the sphere: the whole window
  vp.eye = {1, 0, 0};
  EXPECT_NEAR(clipped_alpha(look_at(vp), cam, s), max_clipped_alpha(cam), 1e-12);
  // behind the camera: not in view
  vp.eye = {20, 0, 0};
  vp.target = {40, 0, 0};
  EXPECT_EQ(clipped_alpha(look_at(vp), cam, s), 0.0);
}

// viewpoint_for is the inverse of clipped_alpha on the axis, for small and window-filling sizes.
TEST(TimingGeometry, ViewpointForRoundTrips) {
  CameraSettings cam;
  const BoundingSphere s{{100, 50, 10}, 7.5};
  for (double alpha : {0.01, 0.2, 0.9, 1.1, max_clipped_alpha(cam) * 0.999})
    for (double gamma : {0.0, 2.0, 5.5})
      for (double phi : {-0.3, 0.0, 1.2}) {
        const Viewpoint vp = viewpoint_for(s, cam, alpha, gamma, phi);
        EXPECT_NEAR(clipped_alpha(look_at(vp), cam, s), alpha, 1e-6 * alpha + 1e-9)
            << alpha << " " << gamma << " " << phi;
        double g, p;
        view_direction_angles(vp.eye, s.centre, &g, &p);
        EXPECT_NEAR(g, gamma, 1e-9);
        EXPECT_NEAR(p, phi, 1e-9);
      }
}

// Frustum culling of bounding spheres: in front kept, behind / beyond far / far aside dropped,
// straddling a side plane kept.
TEST(TimingGeometry, FrustumCulling) {
  CameraSettings cam;
  cam.near = 1, cam.far = 1000;
  Viewpoint vp;
  vp.eye = {0, 0, 0};
  vp.target = {1, 0, 0};
  const Frustum f = frustum_of(projection_of(cam) * look_at(vp));
  EXPECT_TRUE(f.intersects({{50, 0, 0}, 1}));
  EXPECT_FALSE(f.intersects({{-50, 0, 0}, 1}));
  EXPECT_FALSE(f.intersects({{1100, 0, 0}, 10}));
  EXPECT_FALSE(f.intersects({{10, 100, 0}, 1}));
  // the left plane at 10 m ahead is at y = 10 * tan(half fov x); a sphere centred 1 m outside it
  // with radius 2 crosses it
  const double edge = 10 * std::tan(cam.half_fov_x());
  EXPECT_TRUE(f.intersects({{10, edge + 1, 0}, 2}));
  EXPECT_FALSE(f.intersects({{10, edge + 5, 0}, 2}));
}

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
  } catch (const UserError& e) {
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
