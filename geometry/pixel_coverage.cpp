// Exact pixel areas of a convex polygon (NIST paper, section 3.6, inside(S, p)). See
// pixel_coverage.h for the method.
#include "geometry/pixel_coverage.h"

#include <algorithm>
#include <cmath>

#include "geometry/exact_predicates.h"

namespace ra::geometry {
namespace {

// Part of one chain edge inside a pixel strip: from (x0, y0) to (x1, y1), y0 < y1, with the
// edge's slope dy/dx (unused when x0 == x1).
struct Piece {
  double x0, y0, x1, y1, dydx;
};

// x of the edge a -> b (a.y < b.y, slope dx/dy) at height y in [a.y, b.y]; exact at the ends,
// clamped between the ends' x so that rounding never moves it outside the edge.
double x_at(Vec2 a, Vec2 b, double dxdy, double y) {
  if (y <= a.y) return a.x;
  if (y >= b.y) return b.x;
  const double x = a.x + (y - a.y) * dxdy;
  return std::clamp(x, std::min(a.x, b.x), std::max(a.x, b.x));
}

// One y-monotone chain of the polygon, bottom to top, walked strip by strip.
class Chain {
 public:
  void reset() {
    pts_.clear();
    dxdy_.clear();
    dydx_.clear();
    k_ = 0;
  }
  void add(Vec2 p) {
    if (!pts_.empty()) {  // slopes once per edge, not per strip
      const Vec2 a = pts_.back();
      dxdy_.push_back(a.y < p.y ? (p.x - a.x) / (p.y - a.y) : 0.0);
      dydx_.push_back(a.x != p.x ? (p.y - a.y) / (p.x - a.x) : 0.0);
    }
    pts_.push_back(p);
  }

  // The chain's pieces inside [ylo, yhi] (horizontal edges give none) and their x range.
  // Strips must come in increasing order.
  void pieces(double ylo, double yhi, std::vector<Piece>& out, double& xmin, double& xmax) {
    out.clear();
    while (k_ + 1 < pts_.size() && pts_[k_ + 1].y <= ylo) ++k_;  // edges wholly below
    for (size_t k = k_; k + 1 < pts_.size() && pts_[k].y < yhi; ++k) {
      const Vec2 a = pts_[k], b = pts_[k + 1];
      if (!(a.y < b.y)) continue;  // horizontal
      const double y0 = std::max(a.y, ylo), y1 = std::min(b.y, yhi);
      if (!(y0 < y1)) continue;
      out.push_back({x_at(a, b, dxdy_[k], y0), y0, x_at(a, b, dxdy_[k], y1), y1, dydx_[k]});
    }
    xmin = INFINITY, xmax = -INFINITY;
    for (const Piece& p : out) {
      xmin = std::min({xmin, p.x0, p.x1});
      xmax = std::max({xmax, p.x0, p.x1});
    }
  }

 private:
  std::vector<Vec2> pts_;
  std::vector<double> dxdy_, dydx_;  // per edge
  size_t k_ = 0;
};

// Per-column accumulators over the columns [start, start + len): area[c] is what the pieces inside
// column c add to it; carry[c] is what pieces left of column c (or on its left boundary) add to
// every column from c on.
class Accumulator {
 public:
  void reset(int32_t start, int32_t len) {
    start_ = start;
    area_.assign(size_t(len), 0.0);
    carry_.assign(size_t(len) + 1, 0.0);
  }

  // Adds a piece with winding sign s (+1 left chain, -1 right chain).
  void add(const Piece& p, double s) {
    if (p.x0 == p.x1) {  // vertical
      const double c = std::floor(p.x0);
      if (c == p.x0) {
        carry_[index(c)] += s * (p.y1 - p.y0);  // on a column boundary: all of column c onwards
      } else {
        cell(p.x0, p.y0, p.x1, p.y1, s);
      }
      return;
    }
    // Split at the integer x values strictly between the ends.
    double xa = p.x0, ya = p.y0;
    if (p.x0 < p.x1) {
      for (double k = std::floor(p.x0) + 1; k < p.x1; k += 1) {
        const double yb = std::clamp(p.y0 + (k - p.x0) * p.dydx, ya, p.y1);
        cell(xa, ya, k, yb, s);
        xa = k, ya = yb;
      }
    } else {
      for (double k = std::ceil(p.x0) - 1; k > p.x1; k -= 1) {
        const double yb = std::clamp(p.y0 + (k - p.x0) * p.dydx, ya, p.y1);
        cell(xa, ya, k, yb, s);
        xa = k, ya = yb;
      }
    }
    cell(xa, ya, p.x1, p.y1, s);
  }

  // Emits the columns with positive area, starting with carry `carry_in`; returns the carry out.
  double emit(double carry_in, std::vector<PixelArea>& out) const {
    double run = carry_in;
    for (size_t i = 0; i < area_.size(); ++i) {
      run += carry_[i];
      const double a = std::min(run + area_[i], 1.0);
      if (a > 0) out.push_back({start_ + int32_t(i), a});
    }
    return run + carry_.back();
  }

 private:
  size_t index(double column) const { return size_t(int64_t(column) - start_); }

  // A sub-piece inside one column: both x in [c, c+1] for c = floor(min x).
  void cell(double xa, double ya, double xb, double yb, double s) {
    const double c = std::floor(std::min(xa, xb));
    const double dy = s * (yb - ya);
    area_[index(c)] += dy * (((c + 1) - xa) + ((c + 1) - xb)) * 0.5;
    carry_[index(c) + 1] += dy;
  }

  int32_t start_ = 0;
  std::vector<double> area_, carry_;
};

bool usable_polygon(const std::vector<Vec2>& poly) {
  constexpr double kMax = 1073741824.0;  // 2^30: keeps pixel indices in int32
  for (const Vec2& v : poly)
    if (!(std::fabs(v.x) <= kMax && std::fabs(v.y) <= kMax)) return false;  // also NaN
  // Convex counter-clockwise: no right turn (collinear allowed), and y goes up once and down once
  // around the boundary (an all-left-turn star winds twice and changes direction 4 times).
  const size_t n = poly.size();
  int y_changes = 0, last_dir = 0;
  for (size_t i = 0; i < n; ++i) {
    if (orient2d(poly[i], poly[(i + 1) % n], poly[(i + 2) % n]) < 0) return false;
    const double dy = poly[(i + 1) % n].y - poly[i].y;
    const int dir = (dy > 0) - (dy < 0);
    if (dir != 0) {
      if (last_dir != 0 && dir != last_dir) ++y_changes;
      last_dir = dir;
    }
  }
  // Close the cycle: compare the last direction with the first non-zero one.
  for (size_t i = 0; i < n; ++i) {
    const double dy = poly[(i + 1) % n].y - poly[i].y;
    const int dir = (dy > 0) - (dy < 0);
    if (dir != 0) {
      if (dir != last_dir) ++y_changes;
      break;
    }
  }
  return y_changes == 0 || y_changes == 2;
}

}  // namespace

bool compute_coverage(const std::vector<Vec2>& poly, PolygonCoverage* out) {
  out->rows.clear();
  out->partial.clear();
  const size_t n = poly.size();
  if (n < 3) return true;
  if (!usable_polygon(poly)) return false;
  size_t ib = 0, it = 0;
  for (size_t i = 1; i < n; ++i) {
    if (poly[i].y < poly[ib].y) ib = i;
    if (poly[i].y > poly[it].y) it = i;
  }
  const double ymin = poly[ib].y, ymax = poly[it].y;
  if (!(ymin < ymax)) return true;  // zero area

  // Chains bottom to top: counter-clockwise from the bottom vertex is the right side.
  thread_local Chain left, right;
  thread_local std::vector<Piece> lp, rp;
  thread_local Accumulator acc;
  left.reset();
  right.reset();
  for (size_t i = ib;; i = (i + 1) % n) {
    right.add(poly[i]);
    if (i == it) break;
  }
  for (size_t i = ib;; i = (i + n - 1) % n) {
    left.add(poly[i]);
    if (i == it) break;
  }

  const int32_t j0 = int32_t(std::floor(ymin)), j1 = int32_t(std::ceil(ymax));
  for (int32_t j = j0; j < j1; ++j) {
    const double ylo = std::max(double(j), ymin), yhi = std::min(double(j + 1), ymax);
    if (!(ylo < yhi)) continue;
    const double h = yhi - ylo;  // the polygon's height in this strip
    double lmin, lmax, rmin, rmax;
    left.pieces(ylo, yhi, lp, lmin, lmax);
    right.pieces(ylo, yhi, rp, rmin, rmax);
    if (lp.empty() || rp.empty()) continue;  // cannot happen for h > 0; kept for safety

    CoverageRow row;
    row.y = j;
    row.partial_begin = uint32_t(out->partial.size());
    row.run_area = h;
    const int32_t ls = int32_t(std::floor(lmin)), le = int32_t(std::ceil(lmax));
    const int32_t rs = int32_t(std::floor(rmin)), re = int32_t(std::ceil(rmax));
    if (le > rs) {  // the chains share columns: one span, no run
      const int32_t start = std::min(ls, rs), end = std::max(le, re);
      acc.reset(start, end - start);
      for (const Piece& p : lp) acc.add(p, +1.0);
      for (const Piece& p : rp) acc.add(p, -1.0);
      acc.emit(0.0, out->partial);
      row.run_begin = row.run_end = end;
    } else {
      acc.reset(ls, le - ls);
      for (const Piece& p : lp) acc.add(p, +1.0);
      acc.emit(0.0, out->partial);
      row.run_begin = le;
      row.run_end = rs;
      acc.reset(rs, re - rs);
      for (const Piece& p : rp) acc.add(p, -1.0);
      acc.emit(h, out->partial);  // right of the left chain everything starts covered by h
    }
    row.partial_end = uint32_t(out->partial.size());
    if (row.run_begin < row.run_end || row.partial_begin < row.partial_end)
      out->rows.push_back(row);
  }
  return true;
}

double PolygonCoverage::area(int32_t x, int32_t y) const {
  auto r = std::lower_bound(rows.begin(), rows.end(), y,
                            [](const CoverageRow& row, int32_t v) { return row.y < v; });
  if (r == rows.end() || r->y != y) return 0;
  if (x >= r->run_begin && x < r->run_end) return r->run_area;
  auto b = partial.begin() + r->partial_begin, e = partial.begin() + r->partial_end;
  auto p = std::lower_bound(b, e, x, [](const PixelArea& a, int32_t v) { return a.x < v; });
  return (p != e && p->x == x) ? p->area : 0.0;
}

double PolygonCoverage::total_area() const {
  double sum = 0;
  for (const PixelArea& p : partial) sum += p.area;
  for (const CoverageRow& r : rows) sum += double(r.run_end - r.run_begin) * r.run_area;
  return sum;
}

int64_t PolygonCoverage::pixel_count() const {
  int64_t n = int64_t(partial.size());
  for (const CoverageRow& r : rows) n += r.run_end - r.run_begin;
  return n;
}

double pixel_area_in_convex_polygon(const std::vector<Vec2>& polygon, Pixel px) {
  // Sutherland-Hodgman against the four sides of the pixel, in coordinates local to the pixel.
  std::vector<Vec2> poly, next;
  poly.reserve(polygon.size() + 4);
  for (const Vec2& v : polygon) poly.push_back({v.x - px.x, v.y - px.y});
  for (int side = 0; side < 4 && !poly.empty(); ++side) {
    // Inside value: x >= 0, x <= 1, y >= 0, y <= 1.
    auto inside = [side](Vec2 v) {
      switch (side) {
        case 0:
          return v.x;
        case 1:
          return 1.0 - v.x;
        case 2:
          return v.y;
        default:
          return 1.0 - v.y;
      }
    };
    next.clear();
    for (size_t i = 0; i < poly.size(); ++i) {
      const Vec2 a = poly[i], b = poly[(i + 1) % poly.size()];
      const double da = inside(a), db = inside(b);
      if (da >= 0) next.push_back(a);
      if ((da > 0 && db < 0) || (da < 0 && db > 0)) {
        const Vec2 from = da > 0 ? a : b, to = da > 0 ? b : a;
        const double df = da > 0 ? da : db, dt = da > 0 ? db : da;
        Vec2 p = from + (df / (df - dt)) * (to - from);
        if (side == 0) p.x = 0;
        if (side == 1) p.x = 1;
        if (side == 2) p.y = 0;
        if (side == 3) p.y = 1;
        next.push_back(p);
      }
    }
    poly.swap(next);
  }
  double twice = 0;
  for (size_t i = 0; i < poly.size(); ++i) twice += cross(poly[i], poly[(i + 1) % poly.size()]);
  return std::fabs(0.5 * twice);
}

}  // namespace ra::geometry
