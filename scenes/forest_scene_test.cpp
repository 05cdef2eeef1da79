// The forest generator: per-tree triangle formula, varying complexity, closed outward shapes.
#include "scenes/forest_scene.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>

#include "scenes/scene_statistics.h"
#include "scenes/scene_test_util.h"
#include "scenes/scene_validation.h"

namespace ra::scenes {
namespace {

using scene_test::cross3;
using scene_test::norm3;

ForestParams tiny() {
  ForestParams p;
  p.seed = 5;
  p.trees = 12;
  p.area = 60;
  p.texture_size = 4;
  return p;
}

TEST(ForestScene, ObjectsAndTrianglesFollowThePlan) {
  const ForestParams p = tiny();
  const Scene s = generate_forest(p);
  const std::vector<TreePlan> plan = plan_forest(p);
  ASSERT_EQ(s.objects.size(), 13u);
  EXPECT_EQ(s.objects[0].name, "ground");
  EXPECT_EQ(s.objects[12].name, "tree 11");
  EXPECT_EQ(static_cast<int64_t>(s.objects[0].mesh.triangle_count()), forest_ground_triangles());
  EXPECT_EQ(forest_ground_triangles(), 512);
  for (size_t k = 0; k < plan.size(); ++k) {
    const StripMesh& m = s.objects[k + 1].mesh;
    EXPECT_EQ(static_cast<int64_t>(m.triangle_count()), tree_triangles(plan[k]));
    // trunk: 2 bands; crown: stacks bands and 2 caps
    EXPECT_EQ(m.strips.size(), static_cast<size_t>(2 + plan[k].stacks + 2));
  }
  ASSERT_EQ(s.textures.size(), 2u);
  EXPECT_TRUE(scene_problems(s).empty()) << scene_problems(s)[0];
}

// A hand-checked tree: slices 8, stacks 4 -> trunk 2 x 2 x 4 = 16, crown 4 x 16 + 2 x 6 = 76.
TEST(ForestScene, TreeTriangleFormulaByHand) {
  TreePlan t;
  t.slices = 8;
  t.stacks = 4;
  EXPECT_EQ(tree_triangles(t), 16 + 64 + 12);
  t.slices = 3;  // the trunk never drops below 3 slices
  t.stacks = 2;
  EXPECT_EQ(tree_triangles(t), 12 + 12 + 2);
}

// The default forest: 157 trees whose triangle counts span more than 10x, bark and leaves
// alternating (two binds per tree: 314, as the paper's Table 5).
TEST(ForestScene, DefaultForestVariesInComplexity) {
  const Scene s = generate_forest(ForestParams{});
  ASSERT_EQ(s.objects.size(), 158u);
  size_t lo = SIZE_MAX, hi = 0;
  for (size_t k = 1; k < s.objects.size(); ++k) {
    lo = std::min(lo, s.objects[k].mesh.triangle_count());
    hi = std::max(hi, s.objects[k].mesh.triangle_count());
  }
  EXPECT_GT(hi, 10 * lo) << "lo " << lo << " hi " << hi;
  EXPECT_EQ(scene_texture_binds(s), 314);
  bool sphere = false, cone = false;
  for (const TreePlan& t : plan_forest(ForestParams{})) (t.shape == CrownShape::kSphere ? sphere : cone) = true;
  EXPECT_TRUE(sphere && cone);
}

// Trees stand in the area on the ground; every triangle has an area (caps are zig-zag strips,
// not fans around a pole) and faces outward: trunk away from the axis, crown away from its
// centre (both shapes are convex).
TEST(ForestScene, TreesAreClosedOutwardShapes) {
  const ForestParams p = tiny();
  const Scene s = generate_forest(p);
  const std::vector<TreePlan> plan = plan_forest(p);
  for (size_t k = 0; k < plan.size(); ++k) {
    const TreePlan& t = plan[k];
    EXPECT_GE(t.x, 0);
    EXPECT_LE(t.x, p.area);
    EXPECT_GE(t.height, p.height_min);
    EXPECT_LE(t.height, p.height_max);
    EXPECT_GE(t.slices, p.slices_min);
    EXPECT_LE(t.slices, p.slices_max);
    const StripMesh& m = s.objects[k + 1].mesh;
    for (size_t i = 0; i < m.vertex_count(); ++i) {
      EXPECT_GE(m.vertex(i).z, 0);
      EXPECT_LE(m.vertex(i).z, t.height + 1e-4);
    }
    const geometry::Vec3 crown_centre{t.x, t.y, (t.trunk_height + t.height) / 2};
    scene_test::for_each_triangle(
        m, [&](geometry::Vec3 a, geometry::Vec3 b, geometry::Vec3 c, size_t strip) {
          const geometry::Vec3 n = cross3(b - a, c - a);
          ASSERT_GT(norm3(n), 1e-7) << "tree " << k << " strip " << strip;
          const geometry::Vec3 g = (1.0 / 3) * (a + b + c);
          const geometry::Vec3 inside =
              m.strips[strip].texture == 0 ? geometry::Vec3{t.x, t.y, g.z} : crown_centre;
          EXPECT_GT(geometry::dot(n, g - inside), 0) << "tree " << k << " strip " << strip;
        });
  }
}

TEST(ForestScene, DeterministicPerSeed) {
  ForestParams p = tiny();
  const uint64_t h = scene_hash(generate_forest(p));
  EXPECT_EQ(scene_hash(generate_forest(p)), h);
  p.seed = 6;
  EXPECT_NE(scene_hash(generate_forest(p)), h);
}

TEST(ForestScene, RejectsParametersOutOfRange) {
  ForestParams p = tiny();
  p.trees = 0;
  try {
    generate_forest(p);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "forest trees = 0 is out of range (allowed: 1 to 100000)");
  }
  p = tiny();
  p.slices_min = 20;
  p.slices_max = 10;
  EXPECT_THROW(generate_forest(p), std::invalid_argument);
  p = tiny();
  p.slices_max = 2;
  EXPECT_THROW(generate_forest(p), std::invalid_argument);
  p = tiny();
  p.height_max = 1;
  EXPECT_THROW(generate_forest(p), std::invalid_argument);
}

// One tree with the coarsest tessellation works (3 slices: triangular prisms and caps).
TEST(ForestScene, CoarsestTree) {
  ForestParams p = tiny();
  p.trees = 1;
  p.slices_min = p.slices_max = 3;
  const Scene s = generate_forest(p);
  ASSERT_EQ(s.objects.size(), 2u);
  EXPECT_EQ(s.objects[1].mesh.triangle_count(), 26u);
  EXPECT_TRUE(scene_problems(s).empty());
}

}  // namespace
}  // namespace ra::scenes
