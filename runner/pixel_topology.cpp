// Connectivity of lit pixel sets by union-find over horizontal runs. See pixel_topology.h.
#include "runner/pixel_topology.h"

#include <algorithm>
#include <limits>
#include <numeric>

namespace ra {
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

size_t lower_bound_from(const PixelSet& s, size_t from, Pixel key, size_t guess) {
  const size_t n = s.size();
  size_t lo = from;  // every index below lo holds a pixel < key
  const size_t g = from + guess;
  if (guess > 0 && g < n) {
    if (s[g] < key) {
      lo = g + 1;
    } else {  // the answer is in [lo, g]: double steps back from g
      size_t upper = g, step = 1;
      while (upper > lo) {
        const size_t p = upper - std::min(step, upper - lo);
        if (s[p] < key) {
          lo = p + 1;
          break;
        }
        upper = p;
        step *= 2;
      }
      return size_t(std::lower_bound(s.begin() + lo, s.begin() + upper, key) - s.begin());
    }
  }
  size_t probe = lo, step = 1;  // double steps forward from lo
  while (probe < n && s[probe] < key) {
    lo = probe + 1;
    probe += step;
    step *= 2;
  }
  const size_t hi = std::min(probe, n);
  return size_t(std::lower_bound(s.begin() + lo, s.begin() + hi, key) - s.begin());
}

std::vector<PixelRun> pixel_runs(const PixelSet& s) {
  std::vector<PixelRun> runs;
  size_t k = 0, last_len = 0;
  while (k < s.size()) {
    const int32_t y = s[k].y;
    // Neighbouring rows of a filled shape have similar lengths: guess the previous one.
    const size_t end =
        lower_bound_from(s, k, Pixel{std::numeric_limits<int32_t>::min(), y + 1}, last_len);
    last_len = end - k;
    if (int64_t(s[end - 1].x) - s[k].x == int64_t(end - k) - 1) {  // consecutive: one run
      runs.push_back({y, s[k].x, s[end - 1].x + 1});
    } else {
      PixelRun r{y, s[k].x, s[k].x + 1};
      for (size_t i = k + 1; i < end; ++i) {
        if (s[i].x == r.x_end) {
          ++r.x_end;
        } else {
          runs.push_back(r);
          r = {y, s[i].x, s[i].x + 1};
        }
      }
      runs.push_back(r);
    }
    k = end;
  }
  return runs;
}

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

int64_t count_components8(const PixelSet& s) { return components_of_runs(pixel_runs(s)); }

PixelTopology pixel_topology(const PixelSet& s) {
  PixelTopology t;
  const std::vector<PixelRun> runs = pixel_runs(s);
  t.components = components_of_runs(runs);
  if (runs.empty()) return t;
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
  // Rows of the set: [start[r], start[r + 1]) holds row ys[r].
  std::vector<size_t> start;
  std::vector<int32_t> ys;
  for (size_t i = 0; i < s.size(); ++i)
    if (i == 0 || s[i].y != s[i - 1].y) start.push_back(i), ys.push_back(s[i].y);
  start.push_back(s.size());
  // Lit pixels among x-1..x+1 of row r (r may be out of range).
  auto lit_around = [&](size_t r, int32_t x) {
    auto b = s.begin() + start[r], e = s.begin() + start[r + 1];
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
      const int32_t x = s[i].x;
      int degree = 0;
      degree += i > start[r] && s[i - 1].x == x - 1;
      degree += i + 1 < start[r + 1] && s[i + 1].x == x + 1;
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

}  // namespace ra
