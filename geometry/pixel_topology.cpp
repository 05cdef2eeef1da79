// Connectivity of lit pixel sets by union-find over horizontal runs. See pixel_topology.h.
#include "geometry/pixel_topology.h"

#include <algorithm>
#include <numeric>

namespace ra::geometry {
namespace {

class UnionFind {
 public:
  explicit UnionFind(size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0); }
  size_t find(size_t a) {
    while (parent_[a] != a) a = parent_[a] = parent_[parent_[a]];  // path halving
    return a;
  }
  // Returns true when a and b were in different sets.
  bool unite(size_t a, size_t b) {
    a = find(a), b = find(b);
    if (a == b) return false;
    parent_[std::max(a, b)] = std::min(a, b);
    return true;
  }

 private:
  std::vector<size_t> parent_;
};

// Joins the runs of two consecutive rows, indices [a0, a1) and [b0, b1) of `runs` (each row sorted
// and disjoint); `touch(a, b)` says whether two runs are adjacent. Returns the number of merges.
template <class Touch>
int64_t join_rows(const std::vector<PixelRun>& runs, size_t a0, size_t a1, size_t b0, size_t b1,
                  UnionFind& uf, Touch touch) {
  int64_t merges = 0;
  size_t i = a0, j = b0;
  while (i < a1 && j < b1) {
    if (touch(runs[i], runs[j]) && uf.unite(i, j)) ++merges;
    // Advance the run that ends first: it cannot touch anything further right.
    if (runs[i].x_end < runs[j].x_end)
      ++i;
    else
      ++j;
  }
  return merges;
}

}  // namespace

namespace {

// Index ranges [row_begin[r], row_begin[r + 1]) of the runs of each distinct row.
std::vector<size_t> row_starts(const std::vector<PixelRun>& runs) {
  std::vector<size_t> starts;
  for (size_t i = 0; i < runs.size(); ++i)
    if (i == 0 || runs[i].y != runs[i - 1].y) starts.push_back(i);
  starts.push_back(runs.size());
  return starts;
}

int64_t components_of_runs(const std::vector<PixelRun>& runs) {
  if (runs.empty()) return 0;
  const std::vector<size_t> rs = row_starts(runs);
  UnionFind uf(runs.size());
  int64_t count = int64_t(runs.size());
  auto touch8 = [](const PixelRun& a, const PixelRun& b) {
    return a.x_begin <= b.x_end && b.x_begin <= a.x_end;  // some |dx| <= 1
  };
  for (size_t r = 0; r + 2 < rs.size(); ++r) {
    if (runs[rs[r + 1]].y != runs[rs[r]].y + 1) continue;  // rows not adjacent
    count -= join_rows(runs, rs[r], rs[r + 1], rs[r + 1], rs[r + 2], uf, touch8);
  }
  return count;
}

}  // namespace

int64_t count_components8(const PixelSet& s) { return components_of_runs(s.runs()); }

PixelTopology pixel_topology(const PixelSet& s) {
  PixelTopology t;
  const std::vector<PixelRun>& runs = s.runs();
  t.components = components_of_runs(runs);
  if (runs.empty()) return t;
  // At most one run per row (any convex polygon's pixels): no holes, since every unlit pixel of a
  // row reaches the frame along its row, left or right of the run. Saves the background pass.
  bool one_run_per_row = true;
  for (size_t i = 1; i < runs.size() && one_run_per_row; ++i)
    one_run_per_row = runs[i].y != runs[i - 1].y;
  if (one_run_per_row) return t;
  // Background runs inside the bounding box grown by one pixel on every side: the grown frame is
  // background and connects everything outside, so holes = background components - 1.
  int32_t xmin = runs[0].x_begin, xmax = runs[0].x_end;  // [xmin, xmax)
  for (const PixelRun& r : runs) xmin = std::min(xmin, r.x_begin), xmax = std::max(xmax, r.x_end);
  const int32_t x0 = xmin - 1, x1 = xmax + 1;
  const int32_t y0 = runs.front().y - 1, y1 = runs.back().y + 1;
  std::vector<PixelRun> bg;
  std::vector<size_t> bg_rows;  // start of each row's background runs, one entry per row y0..y1
  size_t k = 0;
  for (int32_t y = y0; y <= y1; ++y) {
    bg_rows.push_back(bg.size());
    int32_t x = x0;
    for (; k < runs.size() && runs[k].y == y; ++k) {
      if (runs[k].x_begin > x) bg.push_back({y, x, runs[k].x_begin});
      x = runs[k].x_end;
    }
    if (x < x1) bg.push_back({y, x, x1});
  }
  bg_rows.push_back(bg.size());
  UnionFind uf(bg.size());
  int64_t count = int64_t(bg.size());
  auto touch4 = [](const PixelRun& a, const PixelRun& b) {
    return a.x_begin < b.x_end && b.x_begin < a.x_end;  // share a column
  };
  for (size_t r = 0; r + 2 < bg_rows.size(); ++r)
    count -= join_rows(bg, bg_rows[r], bg_rows[r + 1], bg_rows[r + 1], bg_rows[r + 2], uf, touch4);
  t.holes = count - 1;
  return t;
}

bool is_simple_chain8(const PixelSet& s) {
  if (s.empty()) return false;
  if (s.size() == 1) return true;
  if (count_components8(s) != 1) return false;
  const std::vector<Pixel> px = s.pixels();  // a chain is thin: O(length)
  // Rows of the set: [start[r], start[r + 1]) holds row ys[r].
  std::vector<size_t> start;
  std::vector<int32_t> ys;
  for (size_t i = 0; i < px.size(); ++i)
    if (i == 0 || px[i].y != px[i - 1].y) start.push_back(i), ys.push_back(px[i].y);
  start.push_back(px.size());
  // Lit pixels among x-1..x+1 of row r (r may be out of range).
  auto lit_around = [&](size_t r, int32_t x) {
    auto b = px.begin() + start[r], e = px.begin() + start[r + 1];
    auto it = std::lower_bound(b, e, Pixel{x - 1, ys[r]});
    int n = 0;
    for (; it != e && it->x <= x + 1; ++it) ++n;
    return n;
  };
  int64_t ends = 0;
  for (size_t r = 0; r < ys.size(); ++r) {
    const bool below = r > 0 && ys[r - 1] == ys[r] - 1;
    const bool above = r + 1 < ys.size() && ys[r + 1] == ys[r] + 1;
    for (size_t i = start[r]; i < start[r + 1]; ++i) {
      const int32_t x = px[i].x;
      int degree = 0;
      degree += i > start[r] && px[i - 1].x == x - 1;
      degree += i + 1 < start[r + 1] && px[i + 1].x == x + 1;
      if (below) degree += lit_around(r - 1, x);
      if (above) degree += lit_around(r + 1, x);
      if (degree == 1) {
        ++ends;
      } else if (degree != 2) {
        return false;
      }
    }
  }
  return ends == 2;
}

}  // namespace ra::geometry
