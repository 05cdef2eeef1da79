// The shard cost model ranks shards as their measured times do, and the largest-first order is a
// permutation of the plan that keeps plan order among equal costs.
#include "rundir/shard_cost.h"

#include <gtest/gtest.h>

#include <set>

namespace ra::rundir {
namespace {

geometry::View window(int id, int size, double fov) {
  geometry::View v;
  v.id = id;
  v.width = v.height = size;
  v.fov_deg = fov;
  return v;
}

TEST(ShardCost, RanksShardsAsTheirMeasuredTimesDo) {
  // measured on the nist2008 views (mean render_us per primitive): softpipe triangle
  // 907: 5,719; llvmpipe triangle 907: 403; softpipe line 907: 322; llvmpipe triangle 128: 43;
  // llvmpipe point 128: 35; reference point 128: 0.1
  const geometry::View big = window(1, 907, 150), small = window(2, 128, 30);
  const auto cost = [](const char* platform, geometry::Kind kind, const geometry::View& v) {
    return expected_shard_cost_us(Shard{platform, kind, v.id, 0, 1000}, v);
  };
  const double order[] = {cost("osmesa-softpipe", geometry::Kind::kTriangle, big),
                          cost("egl-llvmpipe", geometry::Kind::kTriangle, big),
                          cost("osmesa-softpipe", geometry::Kind::kLine, big),
                          cost("osmesa-llvmpipe", geometry::Kind::kTriangle, small),
                          cost("osmesa-llvmpipe", geometry::Kind::kPoint, small),
                          cost("reference", geometry::Kind::kPoint, small)};
  for (std::size_t i = 1; i < std::size(order); ++i) EXPECT_GT(order[i - 1], order[i]) << i;
  // the same driver through OSMesa and EGL costs the same; a shard of half the size half as much
  EXPECT_EQ(cost("osmesa-llvmpipe", geometry::Kind::kLine, big),
            cost("egl-llvmpipe", geometry::Kind::kLine, big));
  EXPECT_DOUBLE_EQ(
      expected_shard_cost_us(Shard{"osmesa-llvmpipe", geometry::Kind::kLine, 1, 0, 500}, big),
      cost("osmesa-llvmpipe", geometry::Kind::kLine, big) / 2);
}

TEST(ShardCost, LargestFirstIsAPermutationThatKeepsPlanOrderAmongTies) {
  Experiment exp;
  exp.views = {window(1, 128, 30), window(2, 907, 150)};
  exp.platforms = {"reference", "osmesa-softpipe"};
  exp.counts = {2000, 2000, 2000};
  exp.shard_size = 1000;
  const std::vector<Shard> plan = plan_shards(exp);
  const std::vector<Shard> ordered = largest_expected_cost_first(plan, exp);
  ASSERT_EQ(ordered.size(), plan.size());
  std::set<std::string> a, b;
  for (const Shard& s : plan) a.insert(s.id());
  for (const Shard& s : ordered) b.insert(s.id());
  EXPECT_EQ(a, b);
  EXPECT_EQ(ordered.front().id(), "osmesa-softpipe.triangle.v2.0-1000");
  EXPECT_EQ(ordered[1].id(), "osmesa-softpipe.triangle.v2.1000-2000");  // the tie, in plan order
  EXPECT_EQ(ordered.back().platform, "reference");
  for (std::size_t i = 1; i < ordered.size(); ++i) {
    const geometry::View& vi = exp.views[std::size_t(ordered[i].view - 1)];
    const geometry::View& vp = exp.views[std::size_t(ordered[i - 1].view - 1)];
    EXPECT_GE(expected_shard_cost_us(ordered[i - 1], vp), expected_shard_cost_us(ordered[i], vi));
  }
}

}  // namespace
}  // namespace ra::rundir
