// Table 5 values on a scene small enough to count by hand.
#include "scenes/scene_statistics.h"

#include <gtest/gtest.h>

#include "scenes/forest_scene.h"
#include "scenes/strip_builder.h"

namespace ra::scenes {
namespace {

// Two objects:
//   A: 6 vertices, strip [0 1 2 3] texture 0 (2 triangles), strip [2 3 4 5] texture 1 (2),
//      strip [4 5] texture 0 (draws nothing).
//   B: 4 vertices, strip [0 1 2 3] texture 1 (2), strip [1 2 3] texture 1 (1).
// #triangles 7. #tv with a cache of 16: A 6 (2 and 3 hit in the second strip), B 4: 10.
// With the cache reset per strip: A 4 + 4 = 8, B 4 + 3 = 7: 15.
// Binds in order: A: 0 (1), 1 (2); the empty strip binds nothing; B: still 1, no bind. #sw 2.
// Alone: A binds 2, B binds 1.
Scene hand_scene() {
  Scene s;
  s.kind = "test";
  s.textures.resize(2);
  SceneObject a, b;
  for (int i = 0; i < 6; ++i) add_vertex(a.mesh, {double(i), 0, 0}, 0, 0);
  a.mesh.strips = {{{0, 1, 2, 3}, 0}, {{2, 3, 4, 5}, 1}, {{4, 5}, 0}};
  for (int i = 0; i < 4; ++i) add_vertex(b.mesh, {double(i), 1, 0}, 0, 0);
  b.mesh.strips = {{{0, 1, 2, 3}, 1}, {{1, 2, 3}, 1}};
  s.objects = {a, b};
  return s;
}

TEST(SceneStatistics, HandCountedScene) {
  const Scene s = hand_scene();
  const SceneStatistics st = scene_statistics(s, 16);
  EXPECT_EQ(st.cache_size, 16u);
  EXPECT_EQ(st.objects, 2);
  EXPECT_EQ(st.triangles, 7);
  EXPECT_EQ(st.vertices, 10);
  EXPECT_EQ(st.transformed, 10);
  EXPECT_DOUBLE_EQ(st.tv_per_triangle, 10.0 / 7);
  EXPECT_EQ(st.textures, 2);
  EXPECT_EQ(st.state_switches, 2);
  EXPECT_DOUBLE_EQ(st.triangles_per_switch, 3.5);
  EXPECT_EQ(scene_statistics(s, 16, CacheReset::kPerStrip).transformed, 15);
  EXPECT_EQ(texture_binds(s.objects[0].mesh), 2);
  EXPECT_EQ(texture_binds(s.objects[1].mesh), 1);
  EXPECT_EQ(texture_binds(StripMesh{}), 0);
}

// Binds carry across objects: B after A starts with texture 1 bound; reversed, A's first strip
// (texture 0) needs a bind after B.
TEST(SceneStatistics, SwitchesCarryAcrossObjects) {
  Scene s = hand_scene();
  EXPECT_EQ(scene_texture_binds(s), 2);
  std::swap(s.objects[0], s.objects[1]);
  EXPECT_EQ(scene_texture_binds(s), 3);
}

TEST(SceneStatistics, EmptySceneHasZeroRatios) {
  const SceneStatistics st = scene_statistics(Scene{}, 16);
  EXPECT_EQ(st.triangles, 0);
  EXPECT_EQ(st.tv_per_triangle, 0);
  EXPECT_EQ(st.triangles_per_switch, 0);
}

// A bigger cache never transforms more on the forest (its strips only reuse the previous ring).
TEST(SceneStatistics, ForestCacheSizes) {
  ForestParams p;
  p.texture_size = 2;
  const Scene s = generate_forest(p);
  const SceneStatistics a = scene_statistics(s, 16), b = scene_statistics(s, 32);
  EXPECT_EQ(a.triangles, b.triangles);
  EXPECT_GE(a.transformed, b.transformed);
  EXPECT_EQ(a.state_switches, 314);
  EXPECT_NEAR(a.triangles_per_switch, double(a.triangles) / 314, 1e-9);
}

}  // namespace
}  // namespace ra::scenes
