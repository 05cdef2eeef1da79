// The terrain generator and its height field.
#include "scenes/terrain_scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "scenes/scene_statistics.h"
#include "scenes/scene_test_util.h"
#include "scenes/scene_validation.h"

namespace ra::scenes {
namespace {

TerrainParams tiny() {
  TerrainParams p;
  p.seed = 9;
  p.size = 17;
  p.spacing = 5;
  p.feature_size = 40;
  p.texture_size = 8;
  return p;
}

// One object of size^2 vertices and size - 1 strips of 2 size indices: 2 (size - 1)^2 triangles.
TEST(TerrainScene, CountsFollowTheSize) {
  for (int size : {2, 3, 17, 65}) {
    TerrainParams p = tiny();
    p.size = size;
    const Scene s = generate_terrain(p);
    ASSERT_EQ(s.objects.size(), 1u);
    const StripMesh& m = s.objects[0].mesh;
    EXPECT_EQ(m.vertex_count(), static_cast<size_t>(size * size));
    EXPECT_EQ(m.triangle_count(), static_cast<size_t>(2 * (size - 1) * (size - 1)));
    ASSERT_EQ(m.strips.size(), static_cast<size_t>(size - 1));
    for (const TriangleStrip& st : m.strips) {
      EXPECT_EQ(st.indices.size(), static_cast<size_t>(2 * size));
      EXPECT_EQ(st.texture, 0);
    }
    EXPECT_EQ(s.textures.size(), 1u);
    EXPECT_TRUE(scene_problems(s).empty()) << scene_problems(s)[0];
  }
}

// The vertices sit on the grid at the sampler's heights; the layout's grid holds the same floats.
TEST(TerrainScene, VerticesSampleTheHeightField) {
  const TerrainParams p = tiny();
  const Scene s = generate_terrain(p);
  const StripMesh& m = s.objects[0].mesh;
  for (int j = 0; j < p.size; ++j)
    for (int i = 0; i < p.size; ++i) {
      const geometry::Vec3 v = m.vertex(static_cast<size_t>(j * p.size + i));
      EXPECT_EQ(v.x, i * p.spacing);
      EXPECT_EQ(v.y, j * p.spacing);
      EXPECT_EQ(v.z, static_cast<float>(terrain_height(p, i * p.spacing, j * p.spacing)));
      EXPECT_EQ(v.z, s.layout.ground_z[static_cast<size_t>(j * p.size + i)]);
    }
  EXPECT_EQ(s.layout.ground_nx, p.size);
  EXPECT_DOUBLE_EQ(s.layout.ground_spacing, p.spacing);
  EXPECT_DOUBLE_EQ(s.layout.box_max.x, (p.size - 1) * p.spacing);
}

// Heights within [0, height_scale), continuous (small steps give small changes), and rough
// (not flat): a fractal, not a constant.
TEST(TerrainScene, HeightFieldIsBoundedContinuousAndRough) {
  const TerrainParams p = TerrainParams{};
  double lo = 1e300, hi = -1e300, sum = 0, sum2 = 0;
  int n = 0;
  for (double y = -500; y < 3000; y += 37.3)
    for (double x = -500; x < 3000; x += 41.1) {
      const double h = terrain_height(p, x, y);
      ASSERT_TRUE(std::isfinite(h));
      lo = std::min(lo, h);
      hi = std::max(hi, h);
      sum += h;
      sum2 += h * h;
      ++n;
      // a 1 mm step: the noise's steepest octave (wavelength 25 m) changes it by well under 1 m
      EXPECT_LT(std::fabs(terrain_height(p, x + 1e-3, y) - h), 0.1);
    }
  EXPECT_GE(lo, 0);
  EXPECT_LT(hi, p.height_scale);
  const double sd = std::sqrt(sum2 / n - (sum / n) * (sum / n));
  EXPECT_GT(sd, 0.05 * p.height_scale);
  EXPECT_GT(hi - lo, 0.3 * p.height_scale);
}

// Drawn as GL strips, every triangle faces up (counter-clockwise from above), none degenerate.
TEST(TerrainScene, TrianglesFaceUp) {
  const Scene s = generate_terrain(tiny());
  int n = 0;
  scene_test::for_each_triangle(s.objects[0].mesh,
                                [&](geometry::Vec3 a, geometry::Vec3 b, geometry::Vec3 c, size_t) {
                                  EXPECT_GT(scene_test::cross3(b - a, c - a).z, 0);
                                  ++n;
                                });
  EXPECT_EQ(n, 2 * 16 * 16);
}

TEST(TerrainScene, DeterministicPerSeed) {
  TerrainParams p = tiny();
  const uint64_t h = scene_hash(generate_terrain(p));
  EXPECT_EQ(scene_hash(generate_terrain(p)), h);
  EXPECT_EQ(terrain_height(p, 123.4, 567.8), terrain_height(p, 123.4, 567.8));
  p.seed = 10;
  EXPECT_NE(scene_hash(generate_terrain(p)), h);
}

// The paper's terrain: one texture, one state switch, about one transformed vertex per triangle
// (rows far wider than the cache: each strip transforms its 2 * size vertices).
TEST(TerrainScene, DefaultStatistics) {
  const Scene s = generate_terrain(TerrainParams{});
  const SceneStatistics st = scene_statistics(s, 16);
  EXPECT_EQ(st.objects, 1);
  EXPECT_EQ(st.triangles, 2 * 256 * 256);
  EXPECT_EQ(st.transformed, 256 * 2 * 257);
  EXPECT_EQ(st.state_switches, 1);
  EXPECT_EQ(st.textures, 1);
}

TEST(TerrainScene, RejectsParametersOutOfRange) {
  TerrainParams p = tiny();
  p.size = 1;
  try {
    generate_terrain(p);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "terrain size = 1 is out of range (allowed: 2 to 4097)");
  }
  p = tiny();
  p.spacing = 0;
  EXPECT_THROW(generate_terrain(p), std::invalid_argument);
  p = tiny();
  p.octaves = 17;
  EXPECT_THROW(generate_terrain(p), std::invalid_argument);
  p = tiny();
  p.persistence = std::nan("");
  EXPECT_THROW(generate_terrain(p), std::invalid_argument);
}

}  // namespace
}  // namespace ra::scenes
