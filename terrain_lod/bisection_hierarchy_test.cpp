// Tests of the bisection DAG and of the nested errors and radii (bisection_hierarchy.h).
#include "terrain_lod/bisection_hierarchy.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <map>
#include <set>

#include "terrain_lod/lod_test_util.h"

namespace ra::lod {
namespace {

// Every triangle of every level of the bisection, found independently of TileTopology's DAG:
// breadth-first from the two halves of the square, as (left, right, apex) in (i, j) coordinates.
struct T2 {
  int lx, ly, rx, ry, ax, ay;
};
std::vector<T2> all_bisection_triangles(int n) {
  std::vector<T2> out, queue = {{n - 1, n - 1, 0, 0, n - 1, 0}, {0, 0, n - 1, n - 1, 0, n - 1}};
  while (!queue.empty()) {
    T2 t = queue.back();
    queue.pop_back();
    if ((t.lx + t.rx) % 2 || (t.ly + t.ry) % 2) continue;
    out.push_back(t);
    const int mx = (t.lx + t.rx) / 2, my = (t.ly + t.ry) / 2;
    queue.push_back({t.ax, t.ay, t.lx, t.ly, mx, my});
    queue.push_back({t.rx, t.ry, t.ax, t.ay, mx, my});
  }
  return out;
}

// eps_hat from the definition, with floating-point geometry: the largest vertical distance of a
// grid point of either diamond triangle to that triangle's plane.
std::vector<double> brute_eps_hat(const HeightField& f, int n) {
  std::vector<double> e(size_t(n) * n, 0.0);
  for (const T2& t : all_bisection_triangles(n)) {
    const int m = ((t.ly + t.ry) / 2) * n + (t.lx + t.rx) / 2;
    // plane z = a x + b y + c through the three corners
    const double x0 = t.lx, y0 = t.ly, z0 = f.at(t.lx, t.ly), x1 = t.rx, y1 = t.ry, z1 = f.at(t.rx, t.ry);
    const double x2 = t.ax, y2 = t.ay, z2 = f.at(t.ax, t.ay);
    const double det = (x1 - x0) * (y2 - y0) - (x2 - x0) * (y1 - y0);
    const double a = ((z1 - z0) * (y2 - y0) - (z2 - z0) * (y1 - y0)) / det;
    const double b = ((x1 - x0) * (z2 - z0) - (x2 - x0) * (z1 - z0)) / det;
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        const double s = ((x1 - x) * (y2 - y) - (x2 - x) * (y1 - y)) / det;
        const double u = ((x2 - x) * (y0 - y) - (x0 - x) * (y2 - y)) / det;
        if (s < -1e-12 || u < -1e-12 || 1 - s - u < -1e-12) continue;
        const double zt = z0 + a * (x - x0) + b * (y - y0);
        e[size_t(m)] = std::max(e[size_t(m)], std::abs(f.at(x, y) - zt));
      }
  }
  return e;
}

TEST(TileTopology, RejectsSizesThatAreNotTwoToTheKPlusOne) {
  EXPECT_THROW(TileTopology(16), std::invalid_argument);
  EXPECT_THROW(TileTopology(18), std::invalid_argument);
  EXPECT_NO_THROW(TileTopology(17));
}

TEST(TileTopology, EveryNonCornerVertexIsSplitOnceAndChildrenComeFirst) {
  const int n = 17;
  TileTopology topo(n);
  EXPECT_EQ(topo.fine_to_coarse().size(), size_t(n * n - 4));
  EXPECT_EQ(topo.depth(8 * n + 8), 1);  // the centre is the first split
  EXPECT_TRUE(topo.parents(8 * n + 8).empty());
  EXPECT_EQ(topo.children(8 * n + 8).size(), 4u);  // the four edge midpoints
  EXPECT_EQ(topo.children(8).size(), 2u);          // the south edge midpoint: one triangle
  std::map<int, size_t> rank;
  for (size_t k = 0; k < topo.fine_to_coarse().size(); ++k) rank[topo.fine_to_coarse()[k]] = k;
  for (int v : topo.fine_to_coarse())
    for (int c : topo.children(v)) {
      EXPECT_LT(rank[c], rank[v]);
      EXPECT_EQ(topo.depth(c), topo.depth(v) + 1);
      const auto& p = topo.parents(c);
      EXPECT_NE(std::find(p.begin(), p.end(), v), p.end()) << "child " << c << " does not list parent " << v;
    }
}

TEST(TerrainHierarchy, ErrorsAndRadiiMatchBruteForceFromTheDefinitions) {
  const int n = 17;
  const HeightField f = testing::test_field(n, 1, 1);
  TerrainHierarchy h(f, n, ErrorPropagation::kNested);
  const TileErrors& e = h.errors(0, 0);
  const std::vector<double> hat = brute_eps_hat(f, n);
  // descendants by transitive closure of the children lists of the independent enumeration
  std::map<int, std::set<int>> kids;
  for (const T2& t : all_bisection_triangles(n)) {
    const int m = ((t.ly + t.ry) / 2) * n + (t.lx + t.rx) / 2;
    for (const T2& c : {T2{t.ax, t.ay, t.lx, t.ly, 0, 0}, T2{t.rx, t.ry, t.ax, t.ay, 0, 0}})
      if ((c.lx + c.rx) % 2 == 0 && (c.ly + c.ry) % 2 == 0) kids[m].insert(((c.ly + c.ry) / 2) * n + (c.lx + c.rx) / 2);
  }
  std::function<void(int, std::set<int>&)> descend = [&](int v, std::set<int>& out) {
    for (int c : kids[v])
      if (out.insert(c).second) descend(c, out);
  };
  std::function<double(int)> radius = [&](int v) {
    double r = 0;
    for (int c : kids[v]) {
      const geometry::Vec3 d = h.position(c) - h.position(v);
      r = std::max(r, std::sqrt(geometry::dot(d, d)) + radius(c));
    }
    return r;
  };
  int checked = 0;
  for (int v = 0; v < n * n; ++v) {
    EXPECT_NEAR(e.eps_hat[size_t(v)], hat[size_t(v)], 1e-9) << "vertex " << v;
    std::set<int> desc;
    descend(v, desc);
    double sat = hat[size_t(v)];
    for (int d : desc) sat = std::max(sat, hat[size_t(d)]);
    EXPECT_NEAR(e.eps[size_t(v)], sat, 1e-9) << "vertex " << v;
    // the ball holds every descendant, and its radius is the recursive definition's
    for (int d : desc) {
      const geometry::Vec3 dv = h.position(d) - h.position(v);
      EXPECT_LE(std::sqrt(geometry::dot(dv, dv)), e.radius[size_t(v)] + 1e-9);
    }
    if (v % 7 == 0) {
      EXPECT_NEAR(e.radius[size_t(v)], radius(v), 1e-9) << "vertex " << v;
    }
    checked += desc.empty() ? 0 : 1;
  }
  EXPECT_GT(checked, 100);
  EXPECT_GT(e.eps[size_t(8 * n + 8)], 1.0);  // a rough terrain has error at the top
}

TEST(TerrainHierarchy, NestedOnEveryDagEdgeAndEqualAcrossSeams) {
  const int n = 33;
  const HeightField f = testing::test_field(n, 2, 2);
  TerrainHierarchy h(f, n, ErrorPropagation::kNested);
  EXPECT_GT(h.seam_passes(), 1);  // the seams did change something
  const TileTopology& topo = h.topology();
  for (int ty = 0; ty < 2; ++ty)
    for (int tx = 0; tx < 2; ++tx) {
      const TileErrors& e = h.errors(tx, ty);
      for (int v : topo.fine_to_coarse())
        for (int c : topo.children(v)) {
          EXPECT_GE(e.eps[size_t(v)], e.eps[size_t(c)]);
          const geometry::Vec3 d =
              h.position(h.global_vertex(tx, ty, c)) - h.position(h.global_vertex(tx, ty, v));
          EXPECT_GE(e.radius[size_t(v)] + 1e-9,
                    std::sqrt(geometry::dot(d, d)) + e.radius[size_t(c)]);
        }
    }
  for (int j = 0; j < n; ++j) {  // east edge of tile (0, 0) = west edge of tile (1, 0)
    EXPECT_EQ(h.errors(0, 0).eps[size_t(j * n + n - 1)], h.errors(1, 0).eps[size_t(j * n)]);
    EXPECT_EQ(h.errors(0, 0).radius[size_t(j * n + n - 1)], h.errors(1, 0).radius[size_t(j * n)]);
  }
  // without equalisation the two sides disagree somewhere: the test above is not vacuous
  TerrainHierarchy raw(f, n, ErrorPropagation::kNested, false);
  int differ = 0;
  for (int j = 1; j + 1 < n; ++j) differ += raw.errors(0, 0).eps[size_t(j * n + n - 1)] != raw.errors(1, 0).eps[size_t(j * n)];
  EXPECT_GT(differ, 0);
}

TEST(TerrainHierarchy, UnnestedErrorsAreNotMonotone) {
  const int n = 33;
  const HeightField f = testing::test_field(n, 1, 1);
  TerrainHierarchy h(f, n, ErrorPropagation::kUnnested);
  int violations = 0;
  for (int v : h.topology().fine_to_coarse())
    for (int c : h.topology().children(v)) violations += h.errors(0, 0).eps[size_t(v)] < h.errors(0, 0).eps[size_t(c)];
  EXPECT_GT(violations, 10);
}

}  // namespace
}  // namespace ra::lod
