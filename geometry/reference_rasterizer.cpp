// The exact reference rasterizer (OpenGL 2.1 spec 3.4-3.6 / 4.6 spec 14.4-14.6; lecture 002 for
// pixel-centre sampling and the top-left rule). See reference_rasterizer.h for the rules.
#include "geometry/reference_rasterizer.h"

#include <algorithm>
#include <cmath>

#include "geometry/exact_predicates.h"

namespace ra::geometry {
namespace {

inline int sign_of_difference(double b, double a) { return (b > a) - (b < a); }
inline bool same_point(Vec2 a, Vec2 b) { return a.x == b.x && a.y == b.y; }
inline bool finite(Vec2 p) { return std::isfinite(p.x) && std::isfinite(p.y); }

// --- Diamond-exit rule -------------------------------------------------------------------------
// The open diamond R_c = {q : |q.x - c.x| + |q.y - c.y| < 1/2} is the intersection of the four
// open half-planes s . (q - c) < 1/2, s in {(+-1, +-1)}. A closed segment meets an open convex
// polygon iff no separating axis exists among the polygon's side normals and the segment's normal.
// Ends are perturbed to p - (e, e^2); each test is a polynomial in e whose sign, for e -> 0+, is
// the sign of its first non-zero coefficient.

// s . (p' - c) < 1/2 for p' = p - (e, e^2): constant term s.(p - c) - 1/2, then -sx e.
bool below_diamond_side(double sx, double sy, Vec2 p, Vec2 c) {
  const double t[5] = {sx * p.x, -sx * c.x, sy * p.y, -sy * c.y, -0.5};
  const int s = exact_sign_of_sum(t, 5);
  if (s != 0) return s < 0;
  return sx > 0;
}

constexpr double kSides[4][2] = {{1, 1}, {1, -1}, {-1, 1}, {-1, -1}};

bool perturbed_end_in_diamond(Vec2 p, Vec2 c) {
  for (const auto& s : kSides)
    if (!below_diamond_side(s[0], s[1], p, c)) return false;
  return true;
}

// Along the segment normal n = (-Dy, Dx), D = b - a: the segment projects to the single value
// k = cross(D, a' - c) = k0 + Dy e - Dx e^2, the diamond to the open interval of half-width
// max(|Dx|, |Dy|) / 2. Tests sigma * k < |D_q| / 2 for the axis q (x when use_x).
bool normal_below(double sigma, bool use_x, Vec2 a, Vec2 b, Vec2 c) {
  const double aq = use_x ? a.x : a.y, bq = use_x ? b.x : b.y;
  const int sq = sign_of_difference(bq, aq);
  if (sq == 0) return false;  // |D_q| = 0: nothing is below 0 in absolute value
  // k0 = (bx-ax)(ay-cy) - (by-ay)(ax-cx) = bx ay - bx cy + ax cy - by ax + by cx - ay cx.
  const double pa[6] = {sigma * b.x,  -sigma * b.x, sigma * a.x,
                        -sigma * b.y, sigma * b.y,  -sigma * a.y};
  const double pb[6] = {a.y, c.y, c.y, a.x, c.x, c.x};
  const double half_dq[2] = {-sq * bq * 0.5, sq * aq * 0.5};  // -|D_q| / 2, exactly
  const int s = exact_sign_of_dot_plus(pa, pb, 6, half_dq, 2);
  if (s != 0) return s < 0;
  const int dy = sign_of_difference(b.y, a.y), dx = sign_of_difference(b.x, a.x);
  const int lead = dy != 0 ? int(sigma) * dy : -int(sigma) * dx;  // e, then e^2 coefficient
  return lead < 0;
}

bool segment_meets_diamond(Vec2 a, Vec2 b, Vec2 c) {
  for (const auto& s : kSides)
    if (!below_diamond_side(s[0], s[1], a, c) && !below_diamond_side(s[0], s[1], b, c))
      return false;
  if (same_point(a, b)) return true;
  const bool within_x = normal_below(+1, true, a, b, c) && normal_below(-1, true, a, b, c);
  return within_x || (normal_below(+1, false, a, b, c) && normal_below(-1, false, a, b, c));
}

// --- Polygon sampling --------------------------------------------------------------------------

// Top-left rule for a counter-clockwise polygon in y-up window coordinates: a centre exactly on
// edge a -> b is inside when the edge goes down (a left edge) or is horizontal going left (top).
inline bool edge_owns_boundary(Vec2 a, Vec2 b) { return b.y < a.y || (b.y == a.y && b.x < a.x); }

bool covers(const std::vector<Vec2>& poly, Vec2 q) {
  const size_t n = poly.size();
  if (n < 3) return false;
  for (size_t k = 0; k < n; ++k) {
    const Vec2 a = poly[k], b = poly[(k + 1) % n];
    if (same_point(a, b)) continue;
    const int o = orient2d(a, b, q);
    if (o < 0 || (o == 0 && !edge_owns_boundary(a, b))) return false;
  }
  return true;
}

// Bound on the error of a crossing x = a.x + t, t = (yc - a.y) ((b.x - a.x) / (b.y - a.y)),
// relative to |a.x| + |t|: six roundings of at most 2^-53 each (the bound's own included), doubled.
constexpr double kCrossingRelativeError = 16 * 0x1p-53;
// A clipped triangle has at most 3 + 6 vertices (one per clip plane crossed); more: exact path.
constexpr size_t kMaxHullVertices = 16;

Vec2 snap(Vec2 p, SubpixelGrid g) { return {snap_to_subpixel(p.x, g), snap_to_subpixel(p.y, g)}; }

}  // namespace

const char* snap_rounding_name(SnapRounding r) {
  return r == SnapRounding::kNearest ? "nearest" : "truncation";
}

std::string subpixel_grid_text(SubpixelGrid grid) {
  if (grid.exact()) return "exact";
  return std::to_string(grid.bits) + " bits, " + snap_rounding_name(grid.rounding);
}

double snap_to_subpixel(double v, SubpixelGrid grid) {
  if (grid.exact()) return v;
  const double scale = std::ldexp(1.0, grid.bits);  // exact: a power of two
  if (grid.rounding == SnapRounding::kTruncate) return std::floor(v * scale) / scale;
  return std::nearbyint(v * scale) / scale;  // default rounding mode: nearest, ties to even
}

PixelSet rasterize_point(Vec4 c, int width, int height, SubpixelGrid grid) {
  if (!View::inside_clip_volume(c)) return {};
  // The same expression as View::clip_to_window.
  const double x = snap_to_subpixel((c.x / c.w + 1.0) * 0.5 * width, grid);
  const double y = snap_to_subpixel((c.y / c.w + 1.0) * 0.5 * height, grid);
  // Strictly inside the volume means x < W; only rounding can reach W (or -0 below 0).
  const int32_t px = std::clamp(int32_t(std::floor(x)), 0, width - 1);
  const int32_t py = std::clamp(int32_t(std::floor(y)), 0, height - 1);
  return {Pixel{px, py}};
}

bool diamond_exit_fragment(Vec2 a, Vec2 b, Pixel f) {
  const Vec2 c{f.x + 0.5, f.y + 0.5};
  return segment_meets_diamond(a, b, c) && !perturbed_end_in_diamond(b, c);
}

PixelSet rasterize_segment(Vec2 a, Vec2 b, int width, int height, SubpixelGrid grid) {
  if (!finite(a) || !finite(b)) return {};
  a = snap(a, grid);
  b = snap(b, grid);
  if (same_point(a, b)) return {};  // it exits no diamond
  // Enumerate along the major axis u (v the minor one): with |dv/du| <= 1 the L1 distance from a
  // centre to the segment is |cu - uq| + |cv - vq|, (uq, vq) the segment point nearest in u, so
  // only rows floor(vq) - 1 .. floor(vq) + 1 can be lit in a column. Clear cases are decided in
  // double with a wide margin; anything within the margin goes to the exact predicate.
  constexpr double kMargin = 1e-7;
  const bool x_major = std::fabs(b.x - a.x) >= std::fabs(b.y - a.y);
  const double ua = x_major ? a.x : a.y, ub = x_major ? b.x : b.y;
  const double va = x_major ? a.y : a.x, vb = x_major ? b.y : b.x;
  const int32_t nu = x_major ? width : height, nv = x_major ? height : width;
  const double umin = std::min(ua, ub), umax = std::max(ua, ub);
  const double slope = (vb - va) / (ub - ua);
  // The window bounds also keep the int conversions in range.
  const int32_t i0 = int32_t(std::max(std::floor(umin) - 1, 0.0));
  const int32_t i1 = int32_t(std::min(std::floor(umax) + 1, double(nu - 1)));
  std::vector<Pixel> out;  // a segment lights O(length) pixels: collect, then sort into runs
  for (int32_t i = i0; i <= i1; ++i) {
    const double cu = i + 0.5;
    const double uq = std::clamp(cu, umin, umax);
    const double vq = va + (uq - ua) * slope;
    const double jf = std::floor(vq);
    for (double jd = jf - 1; jd <= jf + 1; jd += 1) {
      if (jd < 0 || jd >= nv) continue;
      const int32_t j = int32_t(jd);
      const double dist = std::fabs(cu - uq) + std::fabs(j + 0.5 - vq);
      if (dist > 0.5 + kMargin) continue;
      const Pixel f = x_major ? Pixel{i, j} : Pixel{j, i};
      const Vec2 c{f.x + 0.5, f.y + 0.5};
      const double end_dist = std::fabs(b.x - c.x) + std::fabs(b.y - c.y);
      bool lit;
      if (dist < 0.5 - kMargin && end_dist > 0.5 + kMargin) {
        lit = true;
      } else if (end_dist < 0.5 - kMargin) {
        lit = false;  // the segment ends inside this diamond
      } else {
        lit = diamond_exit_fragment(a, b, f);
      }
      if (lit) out.push_back(f);
    }
  }
  return PixelSet::from_pixels(std::move(out));
}

PixelSet rasterize_segment(const ClippedSegment& s, int width, int height, SubpixelGrid grid) {
  if (s.status != ClipStatus::kVisible) return {};
  return rasterize_segment(s.p0, s.p1, width, height, grid);
}

std::vector<Vec2> segment_rectangle(Vec2 a, Vec2 b) {
  const Vec2 d = b - a;
  const double len = length(d);
  if (!(len > 0) || !std::isfinite(len)) return {};
  const Vec2 n{-0.5 * d.y / len, 0.5 * d.x / len};  // half the unit normal, to the left of a -> b
  return {a - n, b - n, b + n, a + n};
}

PixelSet rasterize_rectangle_segment(Vec2 a, Vec2 b, int width, int height, SubpixelGrid grid) {
  a = {snap_to_subpixel(a.x, grid), snap_to_subpixel(a.y, grid)};
  b = {snap_to_subpixel(b.x, grid), snap_to_subpixel(b.y, grid)};
  const std::vector<Vec2> rectangle = segment_rectangle(a, b);
  if (rectangle.empty()) return {};
  return rasterize_convex_polygon(rectangle, width, height);
}

bool polygon_covers_sample(const std::vector<Vec2>& ccw_polygon, Vec2 q) {
  return covers(ccw_polygon, q);
}

PixelSet rasterize_convex_polygon(const std::vector<Vec2>& polygon, int width, int height,
                                  SubpixelGrid grid) {
  PixelSet out;
  for (const Vec2& v : polygon)
    if (!finite(v)) return out;
  // The hull (exact) makes any input convex counter-clockwise without repeats; after a snap it
  // also removes the rare reflex vertex that rounding to the grid can create.
  std::vector<Vec2> pts = polygon;
  for (Vec2& v : pts) v = snap(v, grid);
  const std::vector<Vec2> poly = convex_hull(std::move(pts));
  const size_t n = poly.size();
  if (n < 3) return out;
  double ymin = poly[0].y, ymax = poly[0].y;
  for (const Vec2& v : poly) ymin = std::min(ymin, v.y), ymax = std::max(ymax, v.y);
  // Rows whose centre height lies in [ymin, ymax] (exact comparisons below).
  const int32_t j0 = int32_t(std::clamp(std::floor(ymin - 0.5), 0.0, double(height)));
  const int32_t j1 = int32_t(std::clamp(std::ceil(ymax - 0.5), -1.0, double(height - 1)));
  // Each non-horizontal edge line bounds a row's x from below (edge going down, a left edge) or
  // from above (going up): x = a.x + (yc - a.y) * slope at the row's centre height yc.
  struct EdgeLine {
    double ax, ay, slope;  // slope = (b.x - a.x) / (b.y - a.y)
    bool left;
  };
  EdgeLine edges[kMaxHullVertices];
  size_t edge_count = 0;
  if (n <= kMaxHullVertices) {
    for (size_t k = 0; k < n; ++k) {
      const Vec2 a = poly[k], b = poly[k + 1 == n ? 0 : k + 1];
      if (a.y != b.y) edges[edge_count++] = {a.x, a.y, (b.x - a.x) / (b.y - a.y), b.y < a.y};
    }
  }
  for (int32_t j = j0; j <= j1; ++j) {
    const double yc = j + 0.5;
    if (yc < ymin || yc > ymax) continue;
    // The polygon's x interval at yc. Each crossing is computed in double within
    // kCrossingRelativeError (|a.x| + |t|) of the exact one; with the bounds kept both ways, a
    // centre farther than that from the crossings is decided without the exact test.
    double xl = -INFINITY, xr = INFINITY;            // the crossings as computed
    double xl_up = -INFINITY, xl_down = -INFINITY;  // max over left edges of x + err, x - err
    double xr_up = INFINITY, xr_down = INFINITY;    // min over right edges of x + err, x - err
    bool finite_crossings = edge_count > 0;  // an overflowing slope (dy ~ 1e-320) is not certified
    for (size_t k = 0; k < edge_count; ++k) {
      const EdgeLine& e = edges[k];
      const double t = (yc - e.ay) * e.slope;
      const double x = e.ax + t;
      const double err = kCrossingRelativeError * (std::fabs(e.ax) + std::fabs(t));
      finite_crossings &= std::isfinite(x + err);
      if (e.left) {
        xl = std::max(xl, x);
        xl_up = std::max(xl_up, x + err), xl_down = std::max(xl_down, x - err);
      } else {
        xr = std::min(xr, x);
        xr_up = std::min(xr_up, x + err), xr_down = std::min(xr_down, x - err);
      }
    }
    const double i0 = std::ceil(xl - 0.5), i1 = std::floor(xr - 0.5);  // centres inside
    int32_t lo = int32_t(std::clamp(i0, 0.0, double(width)));
    int32_t hi = int32_t(std::clamp(i1, -1.0, double(width - 1)));
    // Certified: lo's centre right of every left crossing and lo - 1's left of the largest (or
    // outside the window); the same for hi on the right. Strictly inside the row range, no
    // horizontal edge is met, so the top-left rule matters only at an exact tie, never certified.
    const bool certified =
        finite_crossings && yc > ymin && yc < ymax && std::isfinite(xl) && std::isfinite(xr) &&
        lo + 0.5 > xl_up && (lo == 0 || lo - 0.5 < xl_down) && hi + 0.5 < xr_down &&
        (hi == width - 1 || hi + 1.5 > xr_up);
    if (!certified) {  // settle both ends with the exact test, from one pixel outside each
      lo = int32_t(std::clamp(i0 - 1, 0.0, double(width)));
      hi = int32_t(std::clamp(i1 + 1, -1.0, double(width - 1)));
      while (lo <= hi && !covers(poly, {lo + 0.5, yc})) ++lo;
      while (hi >= lo && !covers(poly, {hi + 0.5, yc})) --hi;
    }
    if (lo <= hi) out.append_run(j, lo, hi + 1);  // rows ascend: a convex row is one interval
  }
  return out;
}

PixelSet rasterize_polygon(const ClippedPolygon& p, int width, int height, SubpixelGrid grid) {
  if (p.status != ClipStatus::kVisible) return {};
  return rasterize_convex_polygon(p.vertices, width, height, grid);
}

PixelSet rasterize_reference(const View& view, const Primitive& prim, SubpixelGrid grid) {
  switch (prim.kind) {
    case Kind::kPoint: {
      // Depth judged in eye space (View::point_inside), right for every near / far ratio; then
      // only x, y and w are left for the clip-space test.
      if (!view.point_inside(prim.v[0])) return {};
      Vec4 c = view.to_clip(prim.v[0]);
      c.z = 0;
      return rasterize_point(c, view.width, view.height, grid);
    }
    case Kind::kLine:
      return rasterize_segment(clip_segment(view, prim.v[0], prim.v[1]), view.width, view.height,
                               grid);
    case Kind::kTriangle:
      return rasterize_polygon(clip_triangle(view, prim.v[0], prim.v[1], prim.v[2]), view.width,
                               view.height, grid);
  }
  return {};
}

}  // namespace ra::geometry
