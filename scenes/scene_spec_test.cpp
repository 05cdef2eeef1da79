// [[scene]] declarations: values, defaults, and every error naming file, line, key and range.
#include "scenes/scene_spec.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>

#include "util/errors.h"

namespace ra::scenes {
namespace {

std::vector<SceneSpec> parse(const std::string& text, const std::string& file = "timing.toml") {
  const toml::table root = toml::parse(text, file);
  return parse_scene_specs(root, file);
}

std::string error_of(const std::string& text) {
  try {
    parse(text);
  } catch (const util::UserError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(SceneSpec, ParsesAllThreeKinds) {
  const std::vector<SceneSpec> s = parse(R"(
[[scene]]
kind = "city"
name = "downtown"
seed = 7
blocks_x = 10
blocks_y = 12
buildings_per_block = 2
street_width = 20.5
[scene.camera_path]
frames = 250
seed = 3
eye_height = 2

[[scene]]
kind = "terrain"
size = 129
spacing = 20

[[scene]]
kind = "forest"
trees = 50
slices_max = 30
[scene.camera_path]
file = "paths/walk.csv"
)", "experiments/timing.toml");
  ASSERT_EQ(s.size(), 3u);
  EXPECT_EQ(s[0].name, "downtown");
  EXPECT_EQ(s[0].kind, "city");
  EXPECT_EQ(s[0].city.seed, 7u);
  EXPECT_EQ(s[0].city.blocks_x, 10);
  EXPECT_EQ(s[0].city.blocks_y, 12);
  EXPECT_EQ(s[0].city.buildings_per_block, 2);
  EXPECT_DOUBLE_EQ(s[0].city.street_width, 20.5);
  EXPECT_EQ(s[0].city.textures, CityParams{}.textures);  // a default
  EXPECT_EQ(s[0].path.frames, 250);
  EXPECT_EQ(s[0].path.seed, 3u);
  EXPECT_DOUBLE_EQ(s[0].path.eye_height, 2);
  EXPECT_TRUE(s[0].path_file.empty());
  EXPECT_EQ(s[1].name, "terrain");  // the kind names an unnamed scene
  EXPECT_EQ(s[1].terrain.size, 129);
  EXPECT_DOUBLE_EQ(s[1].terrain.spacing, 20);
  EXPECT_EQ(s[1].terrain.seed, 1u);
  EXPECT_EQ(s[1].path.frames, 500);
  EXPECT_EQ(s[2].forest.trees, 50);
  EXPECT_EQ(s[2].forest.slices_max, 30);
  EXPECT_EQ(s[2].path_file, "experiments/paths/walk.csv");  // beside the experiment file
}

TEST(SceneSpec, NoScenesIsEmpty) { EXPECT_TRUE(parse("name = \"x\"\n").empty()); }

TEST(SceneSpec, OutOfRangeNamesFileLineKeyAndRange) {
  EXPECT_EQ(error_of("[[scene]]\nkind = \"city\"\nblocks_x = 0\n"),
            "timing.toml:3:12: scene[0].blocks_x = 0 is out of range (allowed: 1 to 1000)");
  EXPECT_EQ(error_of("[[scene]]\nkind = \"terrain\"\n[[scene]]\nkind = \"terrain\"\nname = \"b\"\nspacing = -1\n"),
            "timing.toml:6:11: scene[1].spacing = -1 is out of range (allowed: > 0 to 100000)");
  EXPECT_EQ(error_of("[[scene]]\nkind = \"forest\"\n[scene.camera_path]\nframes = 0\n"),
            "timing.toml:4:10: scene[0].camera_path.frames = 0 is out of range (allowed: 1 to 1000000)");
}

TEST(SceneSpec, UnknownKindsAndKeysAreErrors) {
  EXPECT_EQ(error_of("[[scene]]\nkind = \"ocean\"\n"),
            "timing.toml:2:8: scene[0].kind = \"ocean\" is not a scene kind (allowed: city, terrain, forest)");
  EXPECT_EQ(error_of("[[scene]]\nname = \"x\"\n"),
            "timing.toml:1:1: missing key scene[0].kind (allowed: city, terrain, forest)");
  // a key of another kind is as wrong as a typo
  const std::string e = error_of("[[scene]]\nkind = \"city\"\ntrees = 3\n");
  EXPECT_EQ(e.rfind("timing.toml:3:1: unknown key scene[0].trees for kind \"city\" (allowed: ", 0), 0u) << e;
  EXPECT_NE(e.find("blocks_x"), std::string::npos);
  const std::string p = error_of("[[scene]]\nkind = \"city\"\n[scene.camera_path]\nframs = 3\n");
  EXPECT_EQ(p.rfind("timing.toml:4:1: unknown key scene[0].camera_path.frams", 0), 0u) << p;
}

TEST(SceneSpec, WrongTypesAndShapes) {
  EXPECT_EQ(error_of("[[scene]]\nkind = \"city\"\nblocks_x = 2.5\n"),
            "timing.toml:3:12: scene[0].blocks_x must be an integer (allowed: 1 to 1000)");
  EXPECT_EQ(error_of("[[scene]]\nkind = \"city\"\nstreet_width = \"wide\"\n"),
            "timing.toml:3:16: scene[0].street_width must be a number");
  EXPECT_EQ(error_of("[[scene]]\nkind = \"city\"\nseed = -1\n"),
            "timing.toml:3:8: scene[0].seed = -1 is out of range (allowed: 0 to 9223372036854775807)");
  EXPECT_EQ(error_of("scene = 3\n"), "timing.toml:1:9: scene must be an array of tables ([[scene]])");
  EXPECT_EQ(error_of("[[scene]]\nkind = \"city\"\ncamera_path = 5\n"),
            "timing.toml:3:15: scene[0].camera_path must be a table (keys: eye_height, file, flight_height, "
            "frames, look_ahead, seed, waypoints)");
}

TEST(SceneSpec, ConstraintsBetweenKeys) {
  EXPECT_EQ(error_of("[[scene]]\nkind = \"city\"\nfloors_min = 9\nfloors_max = 3\n"),
            "timing.toml:1:1: scene[0]: city floors_min = 9 is out of range (allowed: 1 to 3)");
  EXPECT_EQ(error_of("[[scene]]\nkind = \"forest\"\n[scene.camera_path]\nfile = \"a.csv\"\nframes = 3\n"),
            "timing.toml:5:10: scene[0].camera_path.frames cannot be combined with scene[0].camera_path.file "
            "(a recorded path)");
  EXPECT_EQ(error_of("[[scene]]\nkind = \"forest\"\n[[scene]]\nkind = \"forest\"\n"),
            "timing.toml:3:1: scene[1].name = \"forest\" is already used by scene[0] (names must be unique; set name)");
}

TEST(SceneSpec, BuildsScenesAndPaths) {
  const std::vector<SceneSpec> s = parse(R"(
[[scene]]
kind = "city"
blocks_x = 2
blocks_y = 3
buildings_per_block = 1
texture_size = 2
[scene.camera_path]
frames = 20
[[scene]]
kind = "terrain"
size = 9
texture_size = 2
[[scene]]
kind = "forest"
trees = 4
texture_size = 2
)");
  ASSERT_EQ(s.size(), 3u);
  const Scene city = build_scene(s[0]);
  EXPECT_EQ(city.kind, "city");
  EXPECT_EQ(city.objects.size(), 7u);
  EXPECT_EQ(build_camera_path(s[0], city).size(), 20u);
  const Scene terrain = build_scene(s[1]);
  EXPECT_EQ(terrain.objects[0].mesh.triangle_count(), 128u);
  const Scene forest = build_scene(s[2]);
  EXPECT_EQ(forest.objects.size(), 5u);
  SceneSpec bad = s[0];
  bad.kind = "ocean";
  EXPECT_THROW(build_scene(bad), std::invalid_argument);
}

TEST(SceneSpec, RecordedPathFile) {
  const std::string dir = testing::TempDir();
  {
    std::ofstream(dir + "scenes_spec_walk.csv")
        << "frame,eye_x,eye_y,eye_z,target_x,target_y,target_z\n0,1,2,3,4,5,6\n1,1,2,3,4,5,7\n";
  }
  const std::vector<SceneSpec> s =
      parse("[[scene]]\nkind = \"forest\"\ntrees = 2\ntexture_size = 2\n[scene.camera_path]\nfile = \"scenes_spec_walk.csv\"\n",
            dir + "timing.toml");
  ASSERT_EQ(s.size(), 1u);
  const std::vector<Viewpoint> path = build_camera_path(s[0], build_scene(s[0]));
  ASSERT_EQ(path.size(), 2u);
  EXPECT_EQ(path[1].target.z, 7);
  std::remove((dir + "scenes_spec_walk.csv").c_str());
}

}  // namespace
}  // namespace ra::scenes
