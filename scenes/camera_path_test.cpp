// Camera paths: generated walks and flights stay where a camera may be; recorded CSV paths.
#include "scenes/camera_path.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>

#include "util/errors.h"
#include "scenes/city_scene.h"
#include "scenes/forest_scene.h"
#include "scenes/terrain_scene.h"

namespace ra::scenes {
namespace {

double horizontal(geometry::Vec3 a) { return std::hypot(a.x, a.y); }

void expect_inside_box(const Scene& s, const std::vector<Viewpoint>& path) {
  for (const Viewpoint& v : path) {
    ASSERT_TRUE(geometry::is_finite(v.eye) && geometry::is_finite(v.target));
    EXPECT_GE(v.eye.x, s.layout.box_min.x);
    EXPECT_LE(v.eye.x, s.layout.box_max.x);
    EXPECT_GE(v.eye.y, s.layout.box_min.y);
    EXPECT_LE(v.eye.y, s.layout.box_max.y);
    EXPECT_EQ(v.up.z, 1);
  }
}

// Evenly spaced (chords of equal arcs) and smooth (the heading turns a little per frame).
void expect_smooth(const std::vector<Viewpoint>& path, double max_turn_deg) {
  std::vector<double> steps;
  for (size_t k = 1; k < path.size(); ++k) steps.push_back(horizontal(path[k].eye - path[k - 1].eye));
  const double mx = *std::max_element(steps.begin(), steps.end());
  const double mn = *std::min_element(steps.begin(), steps.end());
  EXPECT_GT(mn, 0.9 * mx) << "min step " << mn << " max step " << mx;
  for (size_t k = 1; k < path.size(); ++k) {
    const geometry::Vec3 a = path[k - 1].target - path[k - 1].eye, b = path[k].target - path[k].eye;
    const double c = (a.x * b.x + a.y * b.y) / (horizontal(a) * horizontal(b));
    EXPECT_LT(std::acos(std::clamp(c, -1.0, 1.0)) * 180 / 3.14159265358979, max_turn_deg) << "frame " << k;
  }
}

// Off the streets the heading turns at most 1 / R radians per metre: per frame step / R.
double max_turn_deg(const Scene& s, const std::vector<Viewpoint>& path) {
  double step = 0;
  for (size_t k = 1; k < path.size(); ++k) step = std::max(step, horizontal(path[k].eye - path[k - 1].eye));
  const double bound = step / free_flight_turn_radius(s.layout) * 180 / 3.14159265358979;
  EXPECT_LT(bound, 30) << "the test's path is too coarse to tell smooth from not";
  return 1.05 * bound + 0.5;
}

CityParams small_city() {
  CityParams p;
  p.blocks_x = 6;
  p.blocks_y = 5;
  p.texture_size = 2;
  return p;
}

// City: walking at eye height on the streets: always within half a street width of a centre
// line, never inside a building's footprint.
TEST(CameraPath, CityWalkStaysOnTheStreets) {
  const CityParams cp = small_city();
  const Scene s = generate_city(cp);
  CameraPathParams p;
  p.frames = 400;
  p.waypoints = 20;
  const std::vector<Viewpoint> path = generate_camera_path(s, p);
  ASSERT_EQ(path.size(), 400u);
  expect_inside_box(s, path);
  expect_smooth(path, 45);  // corners are quarter circles of 6.75 m, one frame every ~3.6 m
  const SceneLayout& l = s.layout;
  const std::vector<CityBuilding> plan = plan_city(cp);
  for (const Viewpoint& v : path) {
    EXPECT_DOUBLE_EQ(v.eye.z, p.eye_height);
    const double fx = std::fmod(v.eye.x - l.street_x0 + 0.5 * l.street_pitch, l.street_pitch) - 0.5 * l.street_pitch;
    const double fy = std::fmod(v.eye.y - l.street_y0 + 0.5 * l.street_pitch, l.street_pitch) - 0.5 * l.street_pitch;
    EXPECT_LE(std::min(std::fabs(fx), std::fabs(fy)), l.street_width / 2 + 1e-9)
        << "eye (" << v.eye.x << ", " << v.eye.y << ") off the streets";
    for (const CityBuilding& b : plan) {
      const CityTier& t = b.tiers[0];
      EXPECT_FALSE(v.eye.x > t.x0 && v.eye.x < t.x1 && v.eye.y > t.y0 && v.eye.y < t.y1);
    }
  }
}

// Terrain: flying at least flight_height above the highest ground of the cell below, looking
// ahead and down; inside the terrain.
TEST(CameraPath, TerrainFlightStaysAboveTheGround) {
  TerrainParams tp;
  tp.size = 65;
  tp.texture_size = 2;
  const Scene s = generate_terrain(tp);
  CameraPathParams p;
  p.frames = 300;
  p.flight_height = 25;
  const std::vector<Viewpoint> path = generate_camera_path(s, p);
  ASSERT_EQ(path.size(), 300u);
  expect_inside_box(s, path);
  expect_smooth(path, max_turn_deg(s, path));
  for (const Viewpoint& v : path) {
    EXPECT_GE(v.eye.z, s.layout.ground_ceiling(v.eye.x, v.eye.y) + p.flight_height - 1e-6);
    // and above the height field itself, which the mesh interpolates
    EXPECT_GT(v.eye.z, terrain_height(tp, v.eye.x, v.eye.y));
    EXPECT_LT(v.target.z, v.eye.z);
  }
  // continuous altitude: no frame-to-frame jump larger than twice the horizontal step
  for (size_t k = 1; k < path.size(); ++k)
    EXPECT_LE(std::fabs(path[k].eye.z - path[k - 1].eye.z), 2 * horizontal(path[k].eye - path[k - 1].eye));
}

// Forest: walking at eye height among the trees, inside the forest.
TEST(CameraPath, ForestWalkAtEyeHeight) {
  ForestParams fp;
  fp.texture_size = 2;
  const Scene s = generate_forest(fp);
  const std::vector<Viewpoint> path = generate_camera_path(s, CameraPathParams{});
  ASSERT_EQ(path.size(), 500u);
  expect_inside_box(s, path);
  expect_smooth(path, max_turn_deg(s, path));
  for (const Viewpoint& v : path) {
    EXPECT_DOUBLE_EQ(v.eye.z, 1.7);
    EXPECT_DOUBLE_EQ(v.target.z, 1.7);
    EXPECT_NEAR(horizontal(v.target - v.eye), 20, 1e-9);
  }
}

TEST(CameraPath, DeterministicPerSeed) {
  const Scene s = generate_city(small_city());
  CameraPathParams p;
  p.frames = 50;
  const std::vector<Viewpoint> a = generate_camera_path(s, p), b = generate_camera_path(s, p);
  for (size_t k = 0; k < a.size(); ++k) {
    EXPECT_EQ(a[k].eye.x, b[k].eye.x);
    EXPECT_EQ(a[k].eye.y, b[k].eye.y);
    EXPECT_EQ(a[k].target.x, b[k].target.x);
  }
  p.seed = 2;
  const std::vector<Viewpoint> c = generate_camera_path(s, p);
  bool differs = false;
  for (size_t k = 0; k < a.size(); ++k) differs |= a[k].eye.x != c[k].eye.x || a[k].eye.y != c[k].eye.y;
  EXPECT_TRUE(differs);
}

TEST(CameraPath, OneFrameAndBadParameters) {
  const Scene s = generate_forest([] { ForestParams f; f.trees = 3; f.texture_size = 2; return f; }());
  CameraPathParams p;
  p.frames = 1;
  EXPECT_EQ(generate_camera_path(s, p).size(), 1u);
  p.frames = 0;
  EXPECT_THROW(generate_camera_path(s, p), std::invalid_argument);
  p = CameraPathParams{};
  p.waypoints = 1;
  EXPECT_THROW(generate_camera_path(s, p), std::invalid_argument);
  EXPECT_THROW(generate_camera_path(Scene{}, CameraPathParams{}), std::invalid_argument);
}

std::string temp_file(const std::string& name, const std::string& text) {
  const std::string path = testing::TempDir() + name;
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

TEST(CameraPath, CsvRoundTripsExactly) {
  const Scene s = generate_city(small_city());
  CameraPathParams p;
  p.frames = 37;
  const std::vector<Viewpoint> path = generate_camera_path(s, p);
  const std::string file = testing::TempDir() + "scenes_path_roundtrip.csv";
  write_camera_path_csv(path, file);
  const std::vector<Viewpoint> back = read_camera_path_csv(file);
  ASSERT_EQ(back.size(), path.size());
  for (size_t k = 0; k < path.size(); ++k) {
    EXPECT_EQ(back[k].eye.x, path[k].eye.x);
    EXPECT_EQ(back[k].eye.y, path[k].eye.y);
    EXPECT_EQ(back[k].eye.z, path[k].eye.z);
    EXPECT_EQ(back[k].target.x, path[k].target.x);
    EXPECT_EQ(back[k].target.y, path[k].target.y);
    EXPECT_EQ(back[k].target.z, path[k].target.z);
  }
  std::remove(file.c_str());
}

// Comments, blank lines, spaces and CRLF line ends are accepted.
TEST(CameraPath, CsvToleratesCommentsAndCrlf) {
  const std::vector<Viewpoint> v = parse_camera_path_csv(
      "# recorded 2003\r\nframe, eye_x, eye_y, eye_z, target_x, target_y, target_z\r\n\r\n"
      "0, 1, 2, 3, 4, 5, 6\r\n1,1.5,2,3,4,5,6e0\r\n",
      "walk.csv");
  ASSERT_EQ(v.size(), 2u);
  EXPECT_EQ(v[1].eye.x, 1.5);
  EXPECT_EQ(v[0].target.z, 6);
}

void expect_error(const std::string& text, const std::string& message) {
  try {
    parse_camera_path_csv(text, "walk.csv");
    ADD_FAILURE() << "no error for: " << text;
  } catch (const UserError& e) {
    EXPECT_EQ(std::string(e.what()), message);
  }
}

const char* kHeader = "frame,eye_x,eye_y,eye_z,target_x,target_y,target_z\n";

TEST(CameraPath, CsvErrorsNameFileAndLine) {
  expect_error("frame,x,y,z\n0,1,2,3\n",
               "walk.csv:1: expected the header 'frame,eye_x,eye_y,eye_z,target_x,target_y,target_z', "
               "found 'frame,x,y,z'");
  expect_error(std::string(kHeader) + "0,0,0,0,1,0,0\n1,0,0,0,1,0\n",
               "walk.csv:3: expected 7 comma-separated values "
               "(frame,eye_x,eye_y,eye_z,target_x,target_y,target_z), found 6");
  expect_error(std::string(kHeader) + "0,0,abc,0,1,0,0\n", "walk.csv:2: eye_y = 'abc' is not a number");
  expect_error(std::string(kHeader) + "0,0,0,0,1,0,\n", "walk.csv:2: target_z = '' is not a number");
  expect_error(std::string(kHeader) + "0,0,0,0,inf,0,0\n", "walk.csv:2: target_x = 'inf' is not finite");
  expect_error(std::string(kHeader) + "0,0,0,0,1,0,0\n2,0,0,0,1,0,0\n",
               "walk.csv:3: frame = 2 is out of sequence (expected 1)");
  expect_error(std::string(kHeader) + "0,1,2,3,1,2,3\n", "walk.csv:2: the target equals the eye: no viewing direction");
  expect_error(kHeader, "walk.csv:1: no frames after the header");
  expect_error("", "walk.csv:1: no header line 'frame,eye_x,eye_y,eye_z,target_x,target_y,target_z'");
  try {
    read_camera_path_csv("/nonexistent/dir/walk.csv");
    ADD_FAILURE();
  } catch (const UserError& e) {
    EXPECT_EQ(std::string(e.what()), "/nonexistent/dir/walk.csv:1: cannot open the camera path file");
  }
  const std::string f = temp_file("scenes_bad_path.csv", std::string(kHeader) + "0,0,0,0,1,0,0\n1,x,0,0,1,0,0\n");
  try {
    read_camera_path_csv(f);
    ADD_FAILURE();
  } catch (const UserError& e) {
    EXPECT_EQ(std::string(e.what()), f + ":3: eye_x = 'x' is not a number");
  }
  std::remove(f.c_str());
}

}  // namespace
}  // namespace ra::scenes
