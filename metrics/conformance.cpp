#include "metrics/conformance.h"

#include <algorithm>
#include <cstdint>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

namespace ra::metrics {

namespace {

ConformanceVerdict verdict(Conformance c) { return {c, 0, ""}; }

// Collects the rules broken and the pixels that break them.
struct Violations {
  int64_t pixels = 0;
  std::string rules;
  std::vector<geometry::Pixel> where;  // the pixels that break a rule, where a rule names them
  void add(const char* rule, int64_t n) {
    if (n <= 0) return;
    pixels += n;
    if (!rules.empty()) rules += '+';
    rules += rule;
  }
  ConformanceVerdict result() const {
    if (pixels == 0) return verdict(Conformance::kWithinSpec);
    return {Conformance::kViolation, pixels, rules};
  }
};

// The pixels within one unit in x and in y of a pixel of `s` (its 3 x 3 dilation).
geometry::PixelSet dilate_by_one(const geometry::PixelSet& s) {
  std::vector<geometry::PixelRun> runs;
  runs.reserve(s.runs().size() * 3);
  for (const geometry::PixelRun& r : s.runs())
    for (int32_t dy = -1; dy <= 1; ++dy) runs.push_back({r.y + dy, r.x_begin - 1, r.x_end + 1});
  std::sort(runs.begin(), runs.end(), [](const geometry::PixelRun& a, const geometry::PixelRun& b) {
    return a.y != b.y ? a.y < b.y : a.x_begin < b.x_begin;
  });
  geometry::PixelSet out;
  for (size_t i = 0; i < runs.size();) {  // merge the overlapping runs of each row
    geometry::PixelRun m = runs[i++];
    while (i < runs.size() && runs[i].y == m.y && runs[i].x_begin <= m.x_end)
      m.x_end = std::max(m.x_end, runs[i++].x_end);
    out.append_run(m.y, m.x_begin, m.x_end);
  }
  return out;
}

// Fragments beyond the first in each column (x-major) or row (y-major) of `lit`, and which.
int64_t extra_per_line(const geometry::PixelSet& lit, bool by_column,
                       std::vector<geometry::Pixel>* where) {
  if (lit.empty()) return 0;
  int64_t extra = 0;
  if (!by_column) {  // runs come row by row: count each row's pixels in one pass
    const std::vector<geometry::PixelRun>& runs = lit.runs();
    for (size_t i = 0; i < runs.size();) {
      size_t j = i;
      int64_t n = 0;
      for (; j < runs.size() && runs[j].y == runs[i].y; ++j) n += runs[j].length();
      if (n > 1) {
        extra += n - 1;
        if (where)
          for (size_t k = i; k < j; ++k)
            for (int32_t x = runs[k].x_begin; x < runs[k].x_end; ++x) where->push_back({x, runs[k].y});
      }
      i = j;
    }
    return extra;
  }
  int32_t x0 = INT32_MAX, x1 = INT32_MIN;
  for (const geometry::PixelRun& r : lit.runs())
    x0 = std::min(x0, r.x_begin), x1 = std::max(x1, r.x_end);
  std::vector<int32_t> count(size_t(int64_t(x1) - x0), 0);  // a segment's columns: O(length)
  for (const geometry::PixelRun& r : lit.runs())
    for (int32_t x = r.x_begin; x < r.x_end; ++x) ++count[size_t(x - x0)];
  for (int32_t n : count) extra += n > 1 ? n - 1 : 0;
  if (where && extra > 0)
    for (const geometry::Pixel& p : lit)
      if (count[size_t(p.x - x0)] > 1) where->push_back(p);
  return extra;
}

// 14.5.1's rules 1-3 for `lit` against the diamond-exit pixels `diamond`. The count rule applies
// only when `count_applies` (see judge_segment); rule 3 is taken under each allowed major axis,
// and the one with fewer extra fragments counts.
Violations line_rules(const geometry::PixelSet& lit, const geometry::PixelSet& diamond,
                      bool count_applies, bool x_major_allowed, bool y_major_allowed) {
  Violations v;
  const geometry::PixelSet deviating = geometry::set_difference(lit, dilate_by_one(diamond));
  v.add("line-deviation", deviating.size());
  for (const geometry::Pixel& p : deviating) v.where.push_back(p);
  if (count_applies) v.add("line-count", std::abs(lit.size() - diamond.size()) - 1);
  const int64_t by_x = x_major_allowed ? extra_per_line(lit, true, nullptr) : INT64_MAX;
  const int64_t by_y = y_major_allowed ? extra_per_line(lit, false, nullptr) : INT64_MAX;
  const bool x = by_x <= by_y;
  v.add("line-column", x ? by_x : by_y);
  if ((x ? by_x : by_y) > 0) extra_per_line(lit, x, &v.where);
  return v;
}

ConformanceVerdict finish(const Violations& v, geometry::PixelSet* violating) {
  if (violating) *violating = geometry::PixelSet::from_pixels(v.where);
  return v.result();
}

}  // namespace

namespace {

// Whether window point q lies within the tapered capsule of the edge a -> b: the union of the
// discs of radius (1 - s) ra + s rb about a + s (b - a), s in [0, 1] (every point of the edge moves
// by at most its ends' moves interpolated). The distance to the edge minus the radius is convex in
// s; its minimum is at an end or where its derivative vanishes.
bool in_tapered_capsule(geometry::Vec2 q, geometry::Vec2 a, double ra, geometry::Vec2 b,
                        double rb) {
  if (!std::isfinite(ra) || !std::isfinite(rb)) return true;
  auto excess = [&](double s) {
    const geometry::Vec2 p{a.x + s * (b.x - a.x), a.y + s * (b.y - a.y)};
    return geometry::length(q - p) - ((1 - s) * ra + s * rb);
  };
  if (excess(0) <= 0 || excess(1) <= 0) return true;
  const geometry::Vec2 ab = b - a;
  const double len = geometry::length(ab);
  if (!(len > 0)) return false;
  const double g = (rb - ra) / len;  // radius gained per unit of length
  if (std::fabs(g) >= 1) return false;  // one end disc holds the other: the ends decide
  const geometry::Vec2 u{ab.x / len, ab.y / len};
  const geometry::Vec2 aq = q - a;
  const double along = geometry::dot(aq, u), perp = std::fabs(geometry::cross(u, aq));
  const double tau = -g * perp / std::sqrt(1 - g * g);  // along - s len at the minimum
  const double s = std::clamp((along - tau) / len, 0.0, 1.0);
  return excess(s) <= 0;
}

// Columns (by_column) or rows of the window that hold a fragment of the segment a -> b for every
// placement of its ends within their allowances: crossed with half a pixel to spare beyond each
// end, with the line at least three pixels inside the window across (conformance.h, rule 2 in the
// window). `cells`, when given, receives those columns or rows.
int64_t certain_window_lines(AllowedVertex a, AllowedVertex b, int width, int height,
                             bool by_column, std::vector<int32_t>* cells) {
  if (!std::isfinite(a.allowance) || !std::isfinite(b.allowance)) return 0;
  if (!by_column) {  // rows of a y-major segment: the same with x and y exchanged
    std::swap(a.p.x, a.p.y);
    std::swap(b.p.x, b.p.y);
    std::swap(width, height);
  }
  if (a.p.x > b.p.x) std::swap(a, b);
  const double dx = b.p.x - a.p.x;
  if (!(dx > 0)) return 0;
  const double first = std::max(0.0, std::ceil(a.p.x + a.allowance));  // column's left edge
  const double last = std::min(double(width), std::floor(b.p.x - b.allowance));  // right edge
  int64_t n = 0;
  for (double left = first; left + 1 <= last; ++left) {
    const double xc = left + 0.5;
    const double s = (xc - a.p.x) / dx;
    const double y = a.p.y + s * (b.p.y - a.p.y);
    const double shift = 2 * ((1 - s) * a.allowance + s * b.allowance);  // y and slope x x
    if (y - shift >= 3 && y + shift <= height - 3) {
      ++n;
      if (cells) cells->push_back(int32_t(left));
    }
  }
  return n;
}

// The float part of the allowance (px) at point p of the segment a -> b: the ends' float
// allowances interpolated by p's place along it.
double float_allowance_at(const AllowedVertex& a, const AllowedVertex& b, geometry::Vec2 p) {
  const double fa = a.allowance - kSnapAllowancePx, fb = b.allowance - kSnapAllowancePx;
  if (!std::isfinite(fa) || !std::isfinite(fb)) return INFINITY;
  const geometry::Vec2 ab = b.p - a.p;
  const double len2 = geometry::dot(ab, ab);
  const double s = len2 > 0 ? std::clamp(geometry::dot(p - a.p, ab) / len2, 0.0, 1.0) : 0.0;
  return (1 - s) * fa + s * fb;
}

// Pixels of `lit` inside the window.
int64_t inside_window(const geometry::PixelSet& lit, int width, int height) {
  int64_t n = 0;
  for (const geometry::PixelRun& r : lit.runs())
    if (r.y >= 0 && r.y < height)
      n += std::max(0, std::min(r.x_end, int32_t(width)) - std::max(r.x_begin, int32_t(0)));
  return n;
}

// Rule 2 inside the window for a segment a window side cut: at least certain - 3 fragments.
void judge_window_count(const AllowedVertex& a, const AllowedVertex& b, int width, int height,
                        bool x_major, bool y_major, const geometry::PixelSet& lit,
                        const geometry::PixelSet& exact, Violations& v) {
  std::vector<int32_t> columns, rows;
  const int64_t by_x = x_major ? certain_window_lines(a, b, width, height, true, &columns)
                               : INT64_MAX;
  const int64_t by_y = y_major ? certain_window_lines(a, b, width, height, false, &rows)
                               : INT64_MAX;
  const bool x = by_x <= by_y;
  const int64_t shortfall = (x ? by_x : by_y) - 3 - inside_window(lit, width, height);
  if (shortfall <= 0) return;
  v.add(lit.empty() ? "line-missing" : "line-window-count", shortfall);
  const std::vector<int32_t>& cells = x ? columns : rows;
  for (const geometry::Pixel& p : geometry::set_difference(exact, lit))
    if (std::binary_search(cells.begin(), cells.end(), x ? p.x : p.y)) v.where.push_back(p);
}

}  // namespace

ConformanceVerdict judge_point(const ClipWithError& clip, int width, int height,
                               const geometry::PixelSet& lit, const geometry::PixelSet& exact,
                               geometry::SubpixelGrid effective, geometry::PixelSet* violating) {
  if (violating) violating->clear();
  if (lit == exact) return verdict(Conformance::kExact);
  const geometry::Vec4 c = clip.c;
  if (!effective.exact() && lit == geometry::rasterize_point(c, width, height, effective))
    return verdict(Conformance::kSnapped);
  Violations v;
  if (!(c.w > 0) || !std::isfinite(c.w)) {  // behind the camera: nothing may be lit
    v.add("point-pixel", lit.size());
    for (const geometry::Pixel& p : lit) v.where.push_back(p);
    return finish(v, violating);
  }
  const AllowedVertex at = window_vertex(clip, width, height);
  const double x = at.p.x, y = at.p.y, tol = at.allowance;
  // Normalized device depth, -1 (near) to 1 (far), and its float error (window_error.h).
  const double z = c.z / c.w;
  const double ztol = clip.err.w < c.w ? (clip.err.z + std::fabs(z) * clip.err.w) / c.w +
                                             kFloatRelativeError * std::fabs(z)
                                       : INFINITY;
  const bool may_be_lit =
      x > -tol && x < width + tol && y > -tol && y < height + tol && std::fabs(z) < 1 + ztol;
  const bool may_be_empty = !(x > tol && x < width - tol && y > tol && y < height - tol &&
                              std::fabs(z) < 1 - ztol);
  int64_t allowed_lit = 0;
  if (may_be_lit && std::isfinite(tol)) {
    const geometry::PixelRect allowed{int32_t(std::floor(x - tol)), int32_t(std::floor(y - tol)),
                                      int32_t(std::floor(x + tol)) + 1,
                                      int32_t(std::floor(y + tol)) + 1};
    for (const geometry::Pixel& p : lit)
      if (p.x >= allowed.x0 && p.x < allowed.x1 && p.y >= allowed.y0 && p.y < allowed.y1)
        ++allowed_lit;
      else
        v.where.push_back(p);
  } else if (may_be_lit) {
    allowed_lit = lit.size();
  } else {
    for (const geometry::Pixel& p : lit) v.where.push_back(p);
  }
  v.add("point-pixel", lit.size() - allowed_lit);
  v.add("point-count", allowed_lit - 1);
  if (lit.empty() && !may_be_empty) {
    v.add("point-missing", 1);
    for (const geometry::Pixel& p : exact) v.where.push_back(p);
  }
  return finish(v, violating);
}

ConformanceVerdict judge_point(geometry::Vec4 clip, int width, int height,
                               const geometry::PixelSet& lit, const geometry::PixelSet& exact,
                               geometry::SubpixelGrid effective, geometry::PixelSet* violating) {
  return judge_point(ClipWithError{clip, geometry::Vec4{0, 0, 0, 0}}, width, height, lit, exact,
                     effective, violating);
}

ConformanceVerdict judge_segment(const geometry::ClippedSegment& segment,
                                 const std::vector<AllowedVertex>& near_clipped, int width,
                                 int height, const geometry::PixelSet& lit,
                                 const geometry::PixelSet& exact, geometry::SubpixelGrid effective,
                                 geometry::PixelSet* violating) {
  if (violating) violating->clear();
  if (lit == exact) return verdict(Conformance::kExact);
  std::optional<geometry::PixelSet> snapped;
  if (!effective.exact()) {
    snapped = geometry::rasterize_segment(segment, width, height, effective);
    if (lit == *snapped) return verdict(Conformance::kSnapped);
  }
  // The segment as GL may place it: its ends before any window side cut them.
  const std::vector<AllowedVertex> ends =
      near_clipped.size() == 2 ? near_clipped : uniform_allowance({segment.p0, segment.p1}, width,
                                                                  height);
  auto side = [](int plane) {
    return plane >= geometry::kPlaneLeft && plane <= geometry::kPlaneTop;
  };
  const bool count_applies = !side(segment.plane0) && !side(segment.plane1);
  // The major axis as the implementation may have placed the ends: |dx| and |dy| each move by up
  // to the two allowances. Either ends: those before the window cut them (a guard band), or the
  // cut ones, snapped after the cut, with the float allowance of their place on the segment.
  auto allowed_axes = [](geometry::Vec2 a, geometry::Vec2 b, double tol, bool& x, bool& y) {
    const double dx = std::fabs(b.x - a.x), dy = std::fabs(b.y - a.y);
    x = x || !(dx + tol < dy - tol);
    y = y || !(dy + tol < dx - tol);
  };
  bool x_major = false, y_major = false;
  allowed_axes(ends[0].p, ends[1].p, ends[0].allowance + ends[1].allowance, x_major, y_major);
  const double cut_tol = 2 * kSnapAllowancePx + float_allowance_at(ends[0], ends[1], segment.p0) +
                         float_allowance_at(ends[0], ends[1], segment.p1);
  allowed_axes(segment.p0, segment.p1, cut_tol, x_major, y_major);
  Violations best = line_rules(lit, exact, count_applies, x_major, y_major);
  auto consider = [&](const geometry::PixelSet& diamond) {
    Violations s = line_rules(lit, diamond, count_applies, x_major, y_major);
    if (s.pixels < best.pixels) best = std::move(s);
  };
  if (snapped && best.pixels > 0) consider(*snapped);
  // The coarsest snaps GL allows, either rounding: an implementation with 4 subpixel bits runs
  // diamond-exit on those ends (a segment shorter than a pixel can gain or lose its fragment).
  for (geometry::SnapRounding r :
       {geometry::SnapRounding::kNearest, geometry::SnapRounding::kTruncate})
    if (best.pixels > 0)
      consider(geometry::rasterize_segment(segment, width, height,
                                           geometry::SubpixelGrid(kLeastSubpixelBits, r)));
  if (!count_applies)
    judge_window_count(ends[0], ends[1], width, height, x_major, y_major, lit, exact, best);
  return finish(best, violating);
}

ConformanceVerdict judge_segment(const geometry::ClippedSegment& segment, double magnitude,
                                 int width, int height, const geometry::PixelSet& lit,
                                 const geometry::PixelSet& exact, geometry::SubpixelGrid effective,
                                 geometry::PixelSet* violating) {
  const double a = conformance_allowance(magnitude, width, height);
  return judge_segment(segment, {{segment.p0, a}, {segment.p1, a}}, width, height, lit, exact,
                       effective, violating);
}

std::pair<geometry::Vec2, geometry::Vec2> rectangle_ends(
    const geometry::ClippedSegment& segment, const std::vector<AllowedVertex>& near_clipped) {
  auto side = [](int plane) {
    return plane >= geometry::kPlaneLeft && plane <= geometry::kPlaneTop;
  };
  const bool guard = near_clipped.size() == 2;
  return {guard && side(segment.plane0) ? near_clipped[0].p : segment.p0,
          guard && side(segment.plane1) ? near_clipped[1].p : segment.p1};
}

ConformanceVerdict judge_rectangle_segment(const geometry::ClippedSegment& segment,
                                           const std::vector<AllowedVertex>& near_clipped,
                                           int width, int height, const geometry::PixelSet& lit,
                                           const geometry::PixelSet& exact,
                                           geometry::SubpixelGrid effective,
                                           geometry::PixelSet* violating) {
  if (violating) violating->clear();
  if (lit == exact) return verdict(Conformance::kExact);
  const auto [a, b] = rectangle_ends(segment, near_clipped);
  if (!effective.exact() &&
      lit == geometry::rasterize_rectangle_segment(a, b, width, height, effective))
    return verdict(Conformance::kSnapped);
  const double ra = near_clipped.size() == 2 ? near_clipped[0].allowance
                                             : conformance_allowance(0, width, height);
  const double rb = near_clipped.size() == 2 ? near_clipped[1].allowance : ra;
  // Moving the ends turns the segment: the half-width normal swings by up to (ra + rb) / length.
  const double len = geometry::length(b - a);
  const double turn = len > 0 ? 0.5 * (ra + rb) / len : std::numeric_limits<double>::infinity();
  const std::vector<geometry::Vec2> corners = geometry::segment_rectangle(a, b);
  // The rectangle of the window-cut ends, allowed where a side cut an end (a clipping rasterizer).
  geometry::PixelSet cut_rectangle;
  const auto moved = [](geometry::Vec2 p, geometry::Vec2 q) { return p.x != q.x || p.y != q.y; };
  if (moved(a, segment.p0) || moved(b, segment.p1))
    cut_rectangle = geometry::rasterize_rectangle_segment(segment.p0, segment.p1, width, height);
  auto allowed = [&](geometry::Pixel px, bool lit_here) {
    if (!cut_rectangle.empty() && cut_rectangle.contains(px) == lit_here) return true;
    if (corners.empty()) return false;
    const geometry::Vec2 c{px.x + 0.5, px.y + 0.5};
    const double r[4] = {std::sqrt(2.0) * ra + turn, std::sqrt(2.0) * rb + turn,
                         std::sqrt(2.0) * rb + turn, std::sqrt(2.0) * ra + turn};
    for (int i = 0; i < 4; ++i)
      if (in_tapered_capsule(c, corners[i], r[i], corners[(i + 1) % 4], r[(i + 1) % 4]))
        return true;
    return false;
  };
  Violations v;
  for (const geometry::Pixel& px : geometry::set_difference(lit, exact))
    if (!allowed(px, true)) v.where.push_back(px);
  for (const geometry::Pixel& px : geometry::set_difference(exact, lit))
    if (!allowed(px, false)) v.where.push_back(px);
  v.add(lit.empty() ? "line-missing" : "line-rectangle", int64_t(v.where.size()));
  return finish(v, violating);
}

ConformanceVerdict judge_polygon(const geometry::ClippedPolygon& polygon,
                                 const std::vector<AllowedVertex>& near_clipped, int width,
                                 int height, const geometry::PixelSet& lit,
                                 const geometry::PixelSet& exact, geometry::SubpixelGrid effective,
                                 geometry::PixelSet* violating) {
  if (violating) violating->clear();
  if (lit == exact) return verdict(Conformance::kExact);
  if (!effective.exact() && lit == geometry::rasterize_polygon(polygon, width, height, effective))
    return verdict(Conformance::kSnapped);
  // The edges a snap or float error can move: those of the polygon clipped to the near plane,
  // each end with its own allowance (sqrt 2 of it: a move in x and in y).
  struct Edge {
    geometry::Vec2 a, b;
    double ra, rb;
  };
  std::vector<Edge> edges;
  const size_t n = near_clipped.size();
  for (size_t i = 0; i < n && n >= 2; ++i) {
    if (n == 2 && i == 1) break;  // a segment: one edge
    const AllowedVertex& a = near_clipped[i];
    const AllowedVertex& b = near_clipped[(i + 1) % n];
    edges.push_back({a.p, b.p, std::sqrt(2.0) * a.allowance, std::sqrt(2.0) * b.allowance});
  }
  // Edges of the visible polygon on none of those lines were cut by the far plane: the uniform
  // allowance. Edges on the window border never move a pixel inside the window.
  const double uniform = std::sqrt(2.0) * conformance_allowance(0, width, height);
  const std::vector<geometry::Vec2>& p = polygon.vertices;
  const size_t m = p.size();
  const size_t near_edges = edges.size();
  auto on_line = [](geometry::Vec2 q, const Edge& e) {
    const geometry::Vec2 ab = e.b - e.a;
    const double len = geometry::length(ab);
    const double scale = 1 + std::max({std::fabs(e.a.x), std::fabs(e.a.y), std::fabs(e.b.x),
                                       std::fabs(e.b.y)});
    return len > 0 && std::fabs(geometry::cross(ab, q - e.a)) / len <= 1e-9 * scale;
  };
  for (size_t i = 0; i < m; ++i) {
    if (m == 2 && i == 1) break;
    if (m > 2 && i < polygon.on_window_border.size() && polygon.on_window_border[i]) continue;
    const geometry::Vec2 a = p[i], b = p[(i + 1) % m];
    bool known = false;
    for (size_t k = 0; k < near_edges && !known; ++k)
      known = on_line(a, edges[k]) && on_line(b, edges[k]);
    if (!known) edges.push_back({a, b, uniform, uniform});
  }
  auto allowed = [&](geometry::Pixel px) {
    const geometry::Vec2 c{px.x + 0.5, px.y + 0.5};
    for (const Edge& e : edges)
      if (in_tapered_capsule(c, e.a, e.ra, e.b, e.rb)) return true;
    return false;
  };
  Violations v;
  for (const geometry::PixelSet& differing :
       {geometry::set_difference(lit, exact), geometry::set_difference(exact, lit)})
    for (const geometry::Pixel& px : differing)
      if (!allowed(px)) v.where.push_back(px);
  v.add(lit.empty() ? "polygon-missing" : "polygon-edge", int64_t(v.where.size()));
  return finish(v, violating);
}

ConformanceVerdict judge_polygon(const geometry::ClippedPolygon& polygon, double magnitude,
                                 int width, int height, const geometry::PixelSet& lit,
                                 const geometry::PixelSet& exact, geometry::SubpixelGrid effective,
                                 geometry::PixelSet* violating) {
  std::vector<AllowedVertex> vertices;
  for (const geometry::Vec2& q : polygon.vertices)
    vertices.push_back({q, conformance_allowance(magnitude, width, height)});
  return judge_polygon(polygon, vertices, width, height, lit, exact, effective, violating);
}

ConformanceVerdict judge_primitive(const geometry::View& view, const geometry::Primitive& prim,
                                   const geometry::PixelSet& lit, geometry::SubpixelGrid effective,
                                   geometry::PixelSet* violating, bool rectangle_lines) {
  const int w = view.width, h = view.height;
  if (rectangle_lines && prim.kind == geometry::Kind::kLine) {
    const geometry::ClippedSegment segment = geometry::clip_segment(view, prim.v[0], prim.v[1]);
    const std::vector<AllowedVertex> ends = near_clipped_vertices(view, prim);
    geometry::PixelSet exact;
    if (segment.status == geometry::ClipStatus::kVisible) {
      const auto [a, b] = rectangle_ends(segment, ends);
      exact = geometry::rasterize_rectangle_segment(a, b, w, h);
    }
    return judge_rectangle_segment(segment, ends, w, h, lit, exact, effective, violating);
  }
  const geometry::PixelSet exact = geometry::rasterize_reference(view, prim);
  switch (prim.kind) {
    case geometry::Kind::kPoint:
      return judge_point(clip_with_error(view, prim.v[0]), w, h, lit, exact, effective, violating);
    case geometry::Kind::kLine:
      return judge_segment(geometry::clip_segment(view, prim.v[0], prim.v[1]),
                           near_clipped_vertices(view, prim), w, h, lit, exact, effective,
                           violating);
    case geometry::Kind::kTriangle:
      return judge_polygon(geometry::clip_triangle(view, prim.v[0], prim.v[1], prim.v[2]),
                           near_clipped_vertices(view, prim), w, h, lit, exact, effective,
                           violating);
  }
  return {};
}

}  // namespace ra::metrics
