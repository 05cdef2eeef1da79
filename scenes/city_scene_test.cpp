// The city generator: counts from the parameters, layout on the street grid, determinism.
#include "scenes/city_scene.h"

#include <gtest/gtest.h>

#include <ctime>
#include <set>
#include <stdexcept>

#include "scenes/scene_statistics.h"
#include "scenes/scene_validation.h"

namespace ra::scenes {
namespace {

CityParams tiny() {
  CityParams p;
  p.seed = 42;
  p.blocks_x = 3;
  p.blocks_y = 2;
  p.buildings_per_block = 3;
  p.texture_size = 4;
  return p;
}

TEST(CityScene, ObjectsFollowTheParameters) {
  const CityParams p = tiny();
  const Scene s = generate_city(p);
  EXPECT_EQ(s.kind, "city");
  ASSERT_EQ(s.objects.size(), 1u + 3 * 2 * 3);
  EXPECT_EQ(s.objects[0].name, "ground");
  EXPECT_EQ(s.objects[1].name, "building 0");
  EXPECT_EQ(s.objects.back().name, "building 17");
  ASSERT_EQ(s.textures.size(), 8u);
  for (const Texture& t : s.textures) EXPECT_EQ(t.width, 4);
  EXPECT_TRUE(scene_problems(s).empty()) << scene_problems(s)[0];
}

// Every building's triangles follow the per-tier formula of its plan, the ground its own.
TEST(CityScene, TriangleCountsFollowThePlan) {
  const CityParams p = tiny();
  const Scene s = generate_city(p);
  const std::vector<CityBuilding> plan = plan_city(p);
  ASSERT_EQ(plan.size() + 1, s.objects.size());
  EXPECT_EQ(static_cast<int64_t>(s.objects[0].mesh.triangle_count()), city_ground_triangles(p));
  EXPECT_EQ(city_ground_triangles(p), 2 * 7 * 5);
  for (size_t k = 0; k < plan.size(); ++k) {
    EXPECT_EQ(static_cast<int64_t>(s.objects[k + 1].mesh.triangle_count()),
              city_building_triangles(plan[k]));
    // strips: one per storey per face, one roof per tier
    size_t strips = 0;
    for (const CityTier& t : plan[k].tiers) strips += 4 * t.floors + 1;
    EXPECT_EQ(s.objects[k + 1].mesh.strips.size(), strips);
  }
}

// A closed form: 4 storeys, one tier, bays of 1000 m (so one bay per face): each building is
// 4 faces x 4 storeys x 2 triangles + 2 roof triangles = 34, and 1 + 4 + ... binds.
TEST(CityScene, ClosedFormForUniformBuildings) {
  CityParams p = tiny();
  p.floors_min = p.floors_max = 4;
  p.tiers_max = 1;
  p.bay_width = 100;
  p.block_size = 50;  // 2 x 2 lots of 25 m: round(22.5 / 100) = 0 -> 1 bay
  const Scene s = generate_city(p);
  int64_t tris = 0;
  for (const SceneObject& o : s.objects) tris += static_cast<int64_t>(o.mesh.triangle_count());
  EXPECT_EQ(tris, 18 * 34 + city_ground_triangles(p));
  // a 2 x 5 vertex facade strip grid per face: 4 faces x 10 + roof 4 vertices
  for (size_t k = 1; k < s.objects.size(); ++k) EXPECT_EQ(s.objects[k].mesh.vertex_count(), 44u);
}

// Buildings stand inside their block (never on a street), tiers nest and stack, heights follow
// the storeys, textures: ground 0, roofs 1, facades 2..textures-1.
TEST(CityScene, BuildingsStayInTheirBlocks) {
  const CityParams p = tiny();
  const double pitch = p.block_size + p.street_width;
  const std::vector<CityBuilding> plan = plan_city(p);
  for (const CityBuilding& b : plan) {
    const double bx0 = p.street_width + b.block_x * pitch, by0 = p.street_width + b.block_y * pitch;
    ASSERT_FALSE(b.tiers.empty());
    int floors = 0;
    for (size_t t = 0; t < b.tiers.size(); ++t) {
      const CityTier& r = b.tiers[t];
      EXPECT_GE(r.x0, bx0);
      EXPECT_LE(r.x1, bx0 + p.block_size);
      EXPECT_GE(r.y0, by0);
      EXPECT_LE(r.y1, by0 + p.block_size);
      EXPECT_LT(r.x0, r.x1);
      EXPECT_LT(r.y0, r.y1);
      EXPECT_NEAR(r.z1 - r.z0, r.floors * p.floor_height, 1e-9);
      if (t > 0) {
        const CityTier& below = b.tiers[t - 1];
        EXPECT_DOUBLE_EQ(r.z0, below.z1);
        EXPECT_GE(r.x0, below.x0);
        EXPECT_LE(r.x1, below.x1);
        EXPECT_GE(r.y0, below.y0);
        EXPECT_LE(r.y1, below.y1);
      }
      EXPECT_GE(r.facade_texture, 2);
      EXPECT_LT(r.facade_texture, p.textures);
      EXPECT_EQ(r.roof_texture, 1);
      floors += r.floors;
    }
    EXPECT_GE(floors, p.floors_min);
    EXPECT_LE(floors, p.floors_max);
  }
  const Scene s = generate_city(p);
  for (const TriangleStrip& st : s.objects[0].mesh.strips) EXPECT_EQ(st.texture, 0);
  for (size_t k = 1; k < s.objects.size(); ++k)
    for (size_t i = 0; i < s.objects[k].mesh.vertex_count(); ++i) {
      const geometry::Vec3 v = s.objects[k].mesh.vertex(i);
      EXPECT_GE(v.z, 0);
      EXPECT_LE(v.z, p.floors_max * p.floor_height + 1e-4);
    }
  EXPECT_DOUBLE_EQ(s.layout.box_max.x, 3 * pitch + p.street_width);
  EXPECT_DOUBLE_EQ(s.layout.box_max.y, 2 * pitch + p.street_width);
  EXPECT_EQ(s.layout.streets_x, 4);
  EXPECT_EQ(s.layout.streets_y, 3);
  EXPECT_DOUBLE_EQ(s.layout.street_pitch, pitch);
}

TEST(CityScene, DeterministicPerSeed) {
  CityParams p = tiny();
  const uint64_t h = scene_hash(generate_city(p));
  EXPECT_EQ(scene_hash(generate_city(p)), h);
  p.seed = 43;
  EXPECT_NE(scene_hash(generate_city(p)), h);
  // a building's draws depend on its own index only: growing the city keeps the first block
  CityParams wider = tiny();
  wider.blocks_y = 3;
  const std::vector<CityBuilding> a = plan_city(tiny()), b = plan_city(wider);
  EXPECT_EQ(a[0].tiers.size(), b[0].tiers.size());
  EXPECT_DOUBLE_EQ(a[0].tiers[0].x0, b[0].tiers[0].x0);
}

// The paper's scale: thousands of objects, quickly; grid facades drawn row by row make the FIFO
// cache pay (under one transformed vertex per triangle).
TEST(CityScene, DefaultCityIsLargeFastAndCacheFriendly) {
  const std::clock_t start = std::clock();
  const Scene s = generate_city(CityParams{});
  const double cpu_s = double(std::clock() - start) / CLOCKS_PER_SEC;
  EXPECT_LT(cpu_s, 2.0);
  EXPECT_EQ(s.objects.size(), 40u * 40 * 4 + 1);
  const SceneStatistics st = scene_statistics(s, 16);
  EXPECT_GT(st.triangles, 1000000);
  EXPECT_LT(st.tv_per_triangle, 0.9);
  EXPECT_GT(st.state_switches, 2 * 6400);  // at least a facade and a roof per building
  EXPECT_EQ(st.textures, 8);
  EXPECT_TRUE(scene_problems(s).empty());
}

TEST(CityScene, RejectsParametersOutOfRange) {
  CityParams p = tiny();
  p.blocks_x = 0;
  try {
    generate_city(p);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "city blocks_x = 0 is out of range (allowed: 1 to 1000)");
  }
  p = tiny();
  p.textures = 2;
  EXPECT_THROW(generate_city(p), std::invalid_argument);
  p = tiny();
  p.floors_min = 9;
  p.floors_max = 8;
  EXPECT_THROW(generate_city(p), std::invalid_argument);
  p = tiny();
  p.street_width = std::nan("");
  EXPECT_THROW(generate_city(p), std::invalid_argument);
}

// Small cities work down to one block with one building.
TEST(CityScene, SmallestCity) {
  CityParams p = tiny();
  p.blocks_x = p.blocks_y = p.buildings_per_block = 1;
  const Scene s = generate_city(p);
  ASSERT_EQ(s.objects.size(), 2u);
  EXPECT_EQ(s.objects[0].mesh.triangle_count(), 18u);  // 3 x 3 cells
  EXPECT_TRUE(scene_problems(s).empty());
}

}  // namespace
}  // namespace ra::scenes
