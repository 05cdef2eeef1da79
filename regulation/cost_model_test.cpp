// Tests of the time and perceptual cost models (cost_model.h) against hand computations.
#include "regulation/cost_model.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "util/errors.h"

namespace ra::regulation {
namespace {

TEST(CostModel, H4ByHand) {
  CostModel m;
  m.c1_us_per_tv = 0.5;
  m.c2_us_per_pixel = 0.01;
  m.intercept_us = 20;
  m.pixel_factor = 2;
  // 20 + 0.5 * 1000 + 0.01 * 2 * 3000 = 580
  EXPECT_DOUBLE_EQ(predict_us(m, 1000, 3000), 580.0);
  m.cost_unit_us = 7;
  EXPECT_EQ(cost_units(m, 580.0), 83);  // 580 / 7 = 82.86, rounded up
  EXPECT_EQ(cost_units(m, 581.0), 83);  // exactly 83 units
  EXPECT_EQ(cost_units(m, 0.0), 0);
}

TEST(CostModel, FootprintOfASphereOnTheAxis) {
  scenes::CameraSettings cam;
  cam.width = 640;
  cam.height = 480;
  cam.fov_y_deg = 90;  // focal = 240 px
  const scenes::Viewpoint vp{{0, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const geometry::Mat4 view = scenes::look_at(vp);
  const scenes::Frustum fr = scenes::frustum_of(scenes::projection_of(cam) * view);
  const scenes::BoundingSphere s{{0, 100, 0}, 5};
  const Footprint f = footprint_of(s, view, fr, cam);
  ASSERT_TRUE(f.visible);
  EXPECT_NEAR(f.focal_px, 240.0, 1e-9);
  EXPECT_NEAR(f.distance_m, 100.0, 1e-9);
  const double r_px = 240.0 * 5 / std::sqrt(100.0 * 100 - 25);
  EXPECT_NEAR(f.pixels, M_PI / 4 * (2 * r_px) * (2 * r_px), 1e-6);
  EXPECT_NEAR(f.area_fraction, f.pixels / (640.0 * 480), 1e-12);
  // behind the camera: culled
  EXPECT_FALSE(footprint_of({{0, -100, 0}, 5}, view, fr, cam).visible);
  // a sphere around the eye covers the window
  EXPECT_DOUBLE_EQ(footprint_of({{0, 1, 0}, 5}, view, fr, cam).area_fraction, 1.0);
}

TEST(CostModel, PerceptualCostByHand) {
  // 0.01 of the window, 0.05 m error at 10 m with focal 500 px: 2.5 px; squared 6.25 -> 0.0625
  EXPECT_DOUBLE_EQ(perceptual_cost(0.01, 0.05, 10, 500, 2), 0.0625);
  EXPECT_DOUBLE_EQ(perceptual_cost(0.01, 0.05, 10, 500, 1), 0.025);
  EXPECT_EQ(perceptual_cost(0.5, 0.0, 10, 500, 2), 0.0);  // full detail costs nothing
}

TEST(CostModel, ReadsTheH4FitOfATimingStudy) {
  const std::string path = (std::filesystem::temp_directory_path() / "regulation_timing_test.json").string();
  std::ofstream(path) << R"({"platforms": [{"name": "osmesa-llvmpipe", "fits": [
      {"heuristic": "h2", "intercept": false, "parameters": [{"name": "c", "value": 9}]},
      {"heuristic": "h4", "intercept": false, "parameters": [{"name": "c1", "value": 0.25}, {"name": "c2", "value": 0.125}]},
      {"heuristic": "h4", "intercept": true, "parameters": [{"name": "b0", "value": 30}, {"name": "c1", "value": 0.5}, {"name": "c2", "value": 0.0625}]}]}]})";
  CostModel base;
  base.cost_unit_us = 3;
  const CostModel m = cost_model_from_timing_json(path, "osmesa-llvmpipe", false, base);
  EXPECT_DOUBLE_EQ(m.c1_us_per_tv, 0.25);
  EXPECT_DOUBLE_EQ(m.c2_us_per_pixel, 0.125);
  EXPECT_DOUBLE_EQ(m.intercept_us, 0);
  EXPECT_DOUBLE_EQ(m.cost_unit_us, 3);
  const CostModel b = cost_model_from_timing_json(path, "osmesa-llvmpipe", true, base);
  EXPECT_DOUBLE_EQ(b.intercept_us, 30);
  EXPECT_DOUBLE_EQ(b.c1_us_per_tv, 0.5);
  EXPECT_THROW(cost_model_from_timing_json(path, "osmesa-softpipe", false, base), UserError);
  std::filesystem::remove(path);
}

// A fit missing c1 or c2, or with a negative c2 (or c1), or an h4+b fit without b0: a UserError
// naming the file, the platform and the parameter (never the file's values kept silently).
TEST(CostModel, RejectsAFitMissingOrWithInvalidParameters) {
  const std::string path = (std::filesystem::temp_directory_path() / "regulation_timing_bad_test.json").string();
  auto expect_error = [&](const std::string& params, bool intercept, const std::string& param) {
    std::ofstream(path) << R"({"platforms": [{"name": "osmesa-llvmpipe", "fits": [{"heuristic": "h4", "intercept": )"
                        << (intercept ? "true" : "false") << R"(, "parameters": [)" << params << "]}]}]}";
    try {
      cost_model_from_timing_json(path, "osmesa-llvmpipe", intercept, CostModel{});
      ADD_FAILURE() << "accepted " << params;
    } catch (const UserError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(path), std::string::npos) << what;
      EXPECT_NE(what.find("osmesa-llvmpipe"), std::string::npos) << what;
      EXPECT_NE(what.find("'" + param + "'"), std::string::npos) << what;
    }
  };
  expect_error(R"({"name": "c2", "value": 0.1})", false, "c1");
  expect_error(R"({"name": "c1", "value": 0.1})", false, "c2");
  expect_error("", false, "c1");
  expect_error(R"({"name": "c1", "value": 0.1}, {"name": "c2", "value": -0.01})", false, "c2");
  expect_error(R"({"name": "c1", "value": -0.1}, {"name": "c2", "value": 0.01})", false, "c1");
  expect_error(R"({"name": "c1", "value": 0.1}, {"name": "c2", "value": "x"})", false, "c2");
  expect_error(R"({"name": "c1", "value": 0.1}, {"name": "c2", "value": 0.01})", true, "b0");
  // a negative intercept is a valid fit (the timing study's h4+b fits have one)
  std::ofstream(path) << R"({"platforms": [{"name": "osmesa-llvmpipe", "fits": [{"heuristic": "h4", "intercept": true,
      "parameters": [{"name": "b0", "value": -500}, {"name": "c1", "value": 0.1}, {"name": "c2", "value": 0}]}]}]})";
  const CostModel m = cost_model_from_timing_json(path, "osmesa-llvmpipe", true, CostModel{});
  EXPECT_DOUBLE_EQ(m.intercept_us, -500);
  EXPECT_DOUBLE_EQ(m.c2_us_per_pixel, 0);
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace ra::regulation
