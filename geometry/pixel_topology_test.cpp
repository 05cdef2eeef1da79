// Connectivity of lit pixel sets: hand-built shapes and a flood-fill cross-check.
#include "geometry/pixel_topology.h"

#include <gtest/gtest.h>

#include <queue>
#include <random>

namespace ra::geometry {
namespace {

PixelSet from_rows(const std::vector<std::string>& rows) {  // rows[0] is the top row; '#' = lit
  PixelSet s;
  const int h = int(rows.size());
  for (int r = 0; r < h; ++r)
    for (int x = 0; x < int(rows[r].size()); ++x)
      if (rows[r][x] == '#') s.insert({x, h - 1 - r});
  return s;
}

// Runs: consecutive pixels of a row merge; a gap splits.
TEST(PixelTopology, Runs) {
  const std::vector<PixelRun> r = from_rows({"##.###", "######"}).runs();
  ASSERT_EQ(r.size(), 3u);
  EXPECT_EQ(r[0].y, 0);
  EXPECT_EQ(r[0].x_end, 6);
  EXPECT_EQ(r[1].x_end, 2);
  EXPECT_EQ(r[2].x_begin, 3);
}

// A diagonal staircase is one 8-connected piece (it would be several 4-connected ones).
TEST(PixelTopology, DiagonalIsOneComponent) {
  const PixelSet s = from_rows({"...#", "..#.", ".#..", "#..."});
  EXPECT_EQ(count_components8(s), 1);
  EXPECT_TRUE(pixel_topology(s).simply_connected());
  EXPECT_TRUE(is_simple_chain8(s));
}

// A ring encloses one hole; a diagonal diamond of lit pixels also encloses (background is
// 4-connected, so it cannot slip between diagonal neighbours).
TEST(PixelTopology, Holes) {
  const PixelTopology ring = pixel_topology(from_rows({"###", "#.#", "###"}));
  EXPECT_EQ(ring.components, 1);
  EXPECT_EQ(ring.holes, 1);
  EXPECT_FALSE(ring.simply_connected());
  const PixelTopology diamond = pixel_topology(from_rows({".#.", "#.#", ".#."}));
  EXPECT_EQ(diamond.components, 1);
  EXPECT_EQ(diamond.holes, 1);
  const PixelTopology notch = pixel_topology(from_rows({"###", "#..", "###"}));
  EXPECT_EQ(notch.holes, 0);
  const PixelTopology two = pixel_topology(from_rows({"##..##", "##..##"}));
  EXPECT_EQ(two.components, 2);
  EXPECT_EQ(two.holes, 0);
  EXPECT_FALSE(pixel_topology({}).simply_connected());
}

// Chains: a path is; a thick corner, a branch, a loop and two pieces are not.
TEST(PixelTopology, Chains) {
  EXPECT_TRUE(is_simple_chain8({{5, 5}}));
  EXPECT_TRUE(is_simple_chain8(from_rows({"..##", "##.."})));
  EXPECT_FALSE(is_simple_chain8(from_rows({".##", "##."})));  // (1,0),(1,1) and neighbours: thick
  EXPECT_FALSE(is_simple_chain8(from_rows({"#..", "##."})));  // three mutually adjacent
  EXPECT_FALSE(is_simple_chain8(from_rows({"..#", "###", "..#"})));  // branch
  EXPECT_FALSE(is_simple_chain8(from_rows({"###", "#.#", "###"})));  // loop
  EXPECT_FALSE(is_simple_chain8(from_rows({"##.##"})));              // two pieces
  EXPECT_FALSE(is_simple_chain8({}));
}

// Cross-check against breadth-first flood fills on a dense grid, for random sets, and for random
// sets of at most one run per row (a convex polygon's rasterization; the fast path without holes).
TEST(PixelTopology, MatchesFloodFill) {
  std::mt19937_64 rng(2);
  const int w = 14, h = 12;
  for (int t = 0; t < 600; ++t) {
    const double density = 0.2 + 0.6 * (t % 7) / 6.0;
    std::vector<int> grid((w + 2) * (h + 2), 0);  // one background pixel of frame
    PixelSet s;
    for (int y = 0; y < h; ++y) {
      if (t < 300) {
        for (int x = 0; x < w; ++x)
          if (std::uniform_real_distribution<double>(0, 1)(rng) < density) {
            grid[(y + 1) * (w + 2) + x + 1] = 1;
            s.insert({x, y});
          }
        continue;
      }
      if (std::uniform_real_distribution<double>(0, 1)(rng) > density) continue;  // an empty row
      int a = int(rng() % w), b = int(rng() % w);
      if (a > b) std::swap(a, b);
      for (int x = a; x <= b; ++x) grid[(y + 1) * (w + 2) + x + 1] = 1, s.insert({x, y});
    }
    auto fill = [&](int value, bool eight) {
      std::vector<int> seen(grid.size(), 0);
      int comps = 0;
      for (size_t i = 0; i < grid.size(); ++i) {
        if (grid[i] != value || seen[i]) continue;
        ++comps;
        std::queue<size_t> q;
        q.push(i);
        seen[i] = 1;
        while (!q.empty()) {
          const int c = int(q.front());
          q.pop();
          const int cx = c % (w + 2), cy = c / (w + 2);
          for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
              if ((dx == 0 && dy == 0) || (!eight && dx != 0 && dy != 0)) continue;
              const int nx = cx + dx, ny = cy + dy;
              if (nx < 0 || ny < 0 || nx >= w + 2 || ny >= h + 2) continue;
              const size_t n = size_t(ny * (w + 2) + nx);
              if (grid[n] == value && !seen[n]) seen[n] = 1, q.push(n);
            }
        }
      }
      return comps;
    };
    const PixelTopology topo = pixel_topology(s);
    EXPECT_EQ(topo.components, fill(1, true));
    if (!s.empty()) {
      EXPECT_EQ(topo.holes, fill(0, false) - 1);  // minus the outside
    }
  }
}

}  // namespace
}  // namespace ra::geometry
