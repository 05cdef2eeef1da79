// Tests of the LOD chains (lod_chain.h) on real generated objects.
#include "regulation/lod_chain.h"

#include <gtest/gtest.h>

#include "scenes/forest_scene.h"
#include "scenes/vertex_cache.h"

namespace ra::regulation {
namespace {

// The most detailed tree of a small forest: many triangles to simplify.
const scenes::SceneObject& big_tree(const scenes::Scene& s) {
  std::size_t best = 1;
  for (std::size_t i = 1; i < s.objects.size(); ++i)
    if (s.objects[i].mesh.triangle_count() > s.objects[best].mesh.triangle_count()) best = i;
  return s.objects[best];
}

TEST(LodChain, MonotoneOnARealTree) {
  scenes::ForestParams p;
  p.trees = 6;
  p.slices_min = 40;
  p.slices_max = 64;
  const scenes::Scene scene = scenes::generate_forest(p);
  const scenes::SceneObject& tree = big_tree(scene);
  const LodChain c = build_lod_chain(tree, {1, 0.5, 0.25, 0.125}, 16);
  ASSERT_GE(c.levels.size(), 3u) << "the simplifier should reduce a 40+-slice tree at least twice";
  EXPECT_EQ(c.levels[0].error_m, 0.0);
  EXPECT_EQ(c.levels[0].transformed, scenes::transformed_vertices(tree.mesh, 16));
  for (std::size_t k = 1; k < c.levels.size(); ++k) {
    EXPECT_LT(c.levels[k].triangles, c.levels[k - 1].triangles) << "level " << k;
    EXPECT_GE(c.levels[k].error_m, c.levels[k - 1].error_m) << "level " << k;
    EXPECT_GT(c.levels[k].error_m, 0.0) << "a reduced level has an error";
    EXPECT_GT(c.levels[k].simplifier_error_m, 0.0);
    // below the object's size: an error larger than the tree would mean a unit mix-up
    EXPECT_LT(c.levels[k].error_m, 2 * tree.bounds.radius);
    EXPECT_LT(c.levels[k].transformed, c.levels[0].transformed);
    EXPECT_EQ(c.levels[k].vertices, int64_t(c.levels[k].mesh.vertex_count()));
    // each texture of the tree (bark, leaves) is still drawn
    EXPECT_EQ(c.levels[k].mesh.strips.size(), 2u);
  }
  // roughly the ratios asked for (the simplifier stops near the target)
  EXPECT_LT(double(c.levels[1].triangles), 0.6 * double(c.levels[0].triangles));
}

TEST(LodChain, RejectsBadRatios) {
  scenes::ForestParams p;
  p.trees = 1;
  const scenes::Scene scene = scenes::generate_forest(p);
  EXPECT_THROW(build_lod_chain(scene.objects[1], {0.5, 0.25}, 16), std::invalid_argument);
  EXPECT_THROW(build_lod_chain(scene.objects[1], {1, 0.5, 0.5}, 16), std::invalid_argument);
}

}  // namespace
}  // namespace ra::regulation
