#include "metrics/conformance.h"

#include <algorithm>
#include <cstdint>
#include <cmath>
#include <optional>
#include <vector>

namespace ra {

namespace {

ConformanceVerdict verdict(Conformance c) { return {c, 0, ""}; }

// Collects the rules broken and the pixels that break them.
struct Violations {
  int64_t pixels = 0;
  std::string rules;
  std::vector<Pixel> where;  // the pixels that break a rule, where a rule names them
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
PixelSet dilate_by_one(const PixelSet& s) {
  std::vector<PixelRun> runs;
  runs.reserve(s.runs().size() * 3);
  for (const PixelRun& r : s.runs())
    for (int32_t dy = -1; dy <= 1; ++dy) runs.push_back({r.y + dy, r.x_begin - 1, r.x_end + 1});
  std::sort(runs.begin(), runs.end(), [](const PixelRun& a, const PixelRun& b) {
    return a.y != b.y ? a.y < b.y : a.x_begin < b.x_begin;
  });
  PixelSet out;
  for (size_t i = 0; i < runs.size();) {  // merge the overlapping runs of each row
    PixelRun m = runs[i++];
    while (i < runs.size() && runs[i].y == m.y && runs[i].x_begin <= m.x_end)
      m.x_end = std::max(m.x_end, runs[i++].x_end);
    out.append_run(m.y, m.x_begin, m.x_end);
  }
  return out;
}

// Fragments beyond the first in each column (x-major) or row (y-major) of `lit`, and which.
int64_t extra_per_line(const PixelSet& lit, bool by_column, std::vector<Pixel>* where) {
  if (lit.empty()) return 0;
  int64_t extra = 0;
  if (!by_column) {  // runs come row by row: count each row's pixels in one pass
    const std::vector<PixelRun>& runs = lit.runs();
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
  for (const PixelRun& r : lit.runs()) x0 = std::min(x0, r.x_begin), x1 = std::max(x1, r.x_end);
  std::vector<int32_t> count(size_t(int64_t(x1) - x0), 0);  // a segment's columns: O(length)
  for (const PixelRun& r : lit.runs())
    for (int32_t x = r.x_begin; x < r.x_end; ++x) ++count[size_t(x - x0)];
  for (int32_t n : count) extra += n > 1 ? n - 1 : 0;
  if (where && extra > 0)
    for (const Pixel& p : lit)
      if (count[size_t(p.x - x0)] > 1) where->push_back(p);
  return extra;
}

// 14.5.1's rules 1-3 for `lit` against the diamond-exit pixels `diamond`. The count rule applies
// only when `count_applies` (see judge_segment); rule 3 is taken under each allowed major axis,
// and the one with fewer extra fragments counts.
Violations line_rules(const PixelSet& lit, const PixelSet& diamond, bool count_applies,
                      bool x_major_allowed, bool y_major_allowed) {
  Violations v;
  const PixelSet deviating = set_difference(lit, dilate_by_one(diamond));
  v.add("line-deviation", deviating.size());
  for (const Pixel& p : deviating) v.where.push_back(p);
  if (count_applies) v.add("line-count", std::abs(lit.size() - diamond.size()) - 1);
  const int64_t by_x = x_major_allowed ? extra_per_line(lit, true, nullptr) : INT64_MAX;
  const int64_t by_y = y_major_allowed ? extra_per_line(lit, false, nullptr) : INT64_MAX;
  const bool x = by_x <= by_y;
  v.add("line-column", x ? by_x : by_y);
  if ((x ? by_x : by_y) > 0) extra_per_line(lit, x, &v.where);
  return v;
}

ConformanceVerdict finish(const Violations& v, PixelSet* violating) {
  if (violating) *violating = PixelSet::from_pixels(v.where);
  return v.result();
}

}  // namespace

double near_clipped_window_magnitude(const View& view, const Primitive& prim) {
  const int n = vertex_count(prim.kind);
  Vec4 c[3];
  for (int i = 0; i < n; ++i) c[i] = view.to_clip(prim.v[i]);
  double m = 0;
  auto include = [&](Vec4 q) {  // q in front of the near plane (w > 0)
    const Vec2 p = view.clip_to_window(q);
    m = std::max({m, std::fabs(p.x), std::fabs(p.y)});
  };
  for (int i = 0; i < n; ++i) {
    const double di = c[i].z + c[i].w;  // >= 0 on the near plane's visible side
    if (di > 0 && c[i].w > 0) include(c[i]);
    if (n == 1) break;
    const int j = (i + 1) % n;
    if (n == 2 && i == 1) break;
    const double dj = c[j].z + c[j].w;
    if ((di > 0) != (dj > 0)) {  // the edge crosses the near plane: where
      const double t = di / (di - dj);
      const Vec4 q{c[i].x + t * (c[j].x - c[i].x), c[i].y + t * (c[j].y - c[i].y),
                   c[i].z + t * (c[j].z - c[i].z), c[i].w + t * (c[j].w - c[i].w)};
      if (q.w > 0) include(q);
    }
  }
  return std::isfinite(m) ? m : 0.0;
}

double conformance_allowance(double magnitude, int width, int height) {
  return kSnapAllowancePx +
         kFloatRelativeError * std::max({magnitude, double(width), double(height)});
}

ConformanceVerdict judge_point(Vec4 clip, int width, int height, const PixelSet& lit,
                               const PixelSet& exact, SubpixelGrid effective,
                               PixelSet* violating) {
  if (violating) violating->clear();
  if (lit == exact) return verdict(Conformance::kExact);
  if (!effective.exact() && lit == rasterize_point(clip, width, height, effective))
    return verdict(Conformance::kSnapped);
  Violations v;
  if (!(clip.w > 0) || !std::isfinite(clip.w)) {  // behind the camera: nothing may be lit
    v.add("point-pixel", lit.size());
    for (const Pixel& p : lit) v.where.push_back(p);
    return finish(v, violating);
  }
  const double x = (clip.x / clip.w + 1.0) * 0.5 * width;  // as View::clip_to_window
  const double y = (clip.y / clip.w + 1.0) * 0.5 * height;
  const double z = clip.z / clip.w;  // normalized device depth, -1 (near) to 1 (far)
  const double tol = conformance_allowance(std::max(std::fabs(x), std::fabs(y)), width, height);
  const double ztol = 2 * kFloatRelativeError;
  const bool may_be_lit =
      x > -tol && x < width + tol && y > -tol && y < height + tol && std::fabs(z) < 1 + ztol;
  const bool may_be_empty = !(x > tol && x < width - tol && y > tol && y < height - tol &&
                              std::fabs(z) < 1 - ztol);
  int64_t allowed_lit = 0;
  if (may_be_lit) {
    const PixelRect allowed{int32_t(std::floor(x - tol)), int32_t(std::floor(y - tol)),
                            int32_t(std::floor(x + tol)) + 1, int32_t(std::floor(y + tol)) + 1};
    for (const Pixel& p : lit)
      if (p.x >= allowed.x0 && p.x < allowed.x1 && p.y >= allowed.y0 && p.y < allowed.y1)
        ++allowed_lit;
      else
        v.where.push_back(p);
  } else {
    for (const Pixel& p : lit) v.where.push_back(p);
  }
  v.add("point-pixel", lit.size() - allowed_lit);
  v.add("point-count", allowed_lit - 1);
  if (lit.empty() && !may_be_empty) {
    v.add("point-missing", 1);
    for (const Pixel& p : exact) v.where.push_back(p);
  }
  return finish(v, violating);
}

ConformanceVerdict judge_segment(const ClippedSegment& segment, double magnitude, int width,
                                 int height, const PixelSet& lit, const PixelSet& exact,
                                 SubpixelGrid effective, PixelSet* violating) {
  if (violating) violating->clear();
  if (lit == exact) return verdict(Conformance::kExact);
  std::optional<PixelSet> snapped;
  if (!effective.exact()) {
    snapped = rasterize_segment(segment, width, height, effective);
    if (lit == *snapped) return verdict(Conformance::kSnapped);
  }
  // Rule 2 counts every fragment of the segment, also those the window then discards: where a
  // window side cut an end, the visible count says nothing (a one-pixel shift that rule 1 allows
  // moves where a nearly parallel segment leaves the window by many pixels).
  auto side = [](int plane) { return plane >= kPlaneLeft && plane <= kPlaneTop; };
  const bool count_applies = !side(segment.plane0) && !side(segment.plane1);
  // The major axis of the segment as the implementation may have snapped it: each end may move
  // by the allowance in x and y, so |dx| and |dy| by twice that.
  const double tol = conformance_allowance(magnitude, width, height);
  const double dx = std::fabs(segment.p1.x - segment.p0.x), dy = std::fabs(segment.p1.y - segment.p0.y);
  const bool x_major = dx + 2 * tol >= dy - 2 * tol, y_major = dy + 2 * tol >= dx - 2 * tol;
  Violations best = line_rules(lit, exact, count_applies, x_major, y_major);
  auto consider = [&](const PixelSet& diamond) {
    Violations s = line_rules(lit, diamond, count_applies, x_major, y_major);
    if (s.pixels < best.pixels) best = std::move(s);
  };
  if (snapped && best.pixels > 0) consider(*snapped);
  // The coarsest snaps GL allows, either rounding: an implementation with 4 subpixel bits runs
  // diamond-exit on those ends (a segment shorter than a pixel can gain or lose its fragment).
  for (SnapRounding r : {SnapRounding::kNearest, SnapRounding::kTruncate})
    if (best.pixels > 0)
      consider(rasterize_segment(segment, width, height, SubpixelGrid(kLeastSubpixelBits, r)));
  return finish(best, violating);
}

ConformanceVerdict judge_polygon(const ClippedPolygon& polygon, double magnitude, int width,
                                 int height, const PixelSet& lit, const PixelSet& exact,
                                 SubpixelGrid effective, PixelSet* violating) {
  if (violating) violating->clear();
  if (lit == exact) return verdict(Conformance::kExact);
  if (!effective.exact() && lit == rasterize_polygon(polygon, width, height, effective))
    return verdict(Conformance::kSnapped);
  // The edges a snap or rounding can move, each with its allowance (a vertex moves by up to the
  // allowance in x and in y: sqrt(2) times that in distance). Edges on the window border are cut
  // by the window itself and never move. Distances are compared squared (no sqrt per pixel).
  struct Edge {
    Vec2 a, ab;
    double len2, allowance2;
  };
  std::vector<Edge> edges;
  const std::vector<Vec2>& p = polygon.vertices;
  const size_t n = p.size();
  const double allowance = std::sqrt(2.0) * conformance_allowance(magnitude, width, height);
  for (size_t i = 0; i < n; ++i) {
    const size_t j = (i + 1) % n;
    if (n > 2 && i < polygon.on_window_border.size() && polygon.on_window_border[i]) continue;
    if (n == 2 && i == 1) break;  // a degenerate polygon: one segment
    const Vec2 ab = p[j] - p[i];
    edges.push_back({p[i], ab, dot(ab, ab), allowance * allowance});
  }
  auto allowed = [&](Pixel px) {
    const Vec2 c{px.x + 0.5, px.y + 0.5};
    for (const Edge& e : edges) {
      const Vec2 ac = c - e.a;
      const double t = e.len2 > 0 ? std::clamp(dot(ac, e.ab) / e.len2, 0.0, 1.0) : 0.0;
      const Vec2 d = ac - t * e.ab;
      if (dot(d, d) <= e.allowance2) return true;
    }
    return false;
  };
  Violations v;
  for (const PixelSet& differing : {set_difference(lit, exact), set_difference(exact, lit)})
    for (const Pixel& px : differing)
      if (!allowed(px)) v.where.push_back(px);
  v.add("polygon-edge", int64_t(v.where.size()));
  return finish(v, violating);
}

ConformanceVerdict judge_primitive(const View& view, const Primitive& prim, const PixelSet& lit,
                                   SubpixelGrid effective, PixelSet* violating) {
  const int w = view.width, h = view.height;
  const PixelSet exact = rasterize_reference(view, prim);
  switch (prim.kind) {
    case Kind::kPoint:
      return judge_point(view.to_clip(prim.v[0]), w, h, lit, exact, effective, violating);
    case Kind::kLine:
      return judge_segment(clip_segment(view, prim.v[0], prim.v[1]),
                           near_clipped_window_magnitude(view, prim), w, h, lit, exact, effective,
                           violating);
    case Kind::kTriangle:
      return judge_polygon(clip_triangle(view, prim.v[0], prim.v[1], prim.v[2]),
                           near_clipped_window_magnitude(view, prim), w, h, lit, exact, effective,
                           violating);
  }
  return {};
}

}  // namespace ra
