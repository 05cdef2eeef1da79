// Test helper (tests only): exact rational-arithmetic versions of the geometry, written without
// the project's code paths, so the tests compare two independent computations. Every double is a
// rational number, and cpp_rational converts it exactly; clipping by axis-parallel lines and the
// shoelace formula stay in the rationals, so the results below are exact.
#pragma once

// Boost's cpp_int trips GCC 12's -Wmaybe-uninitialized inside its own headers (a false positive).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <boost/multiprecision/cpp_int.hpp>
#pragma GCC diagnostic pop

#include <algorithm>
#include <vector>

#include "geometry/pixel_set.h"
#include "geometry/vector_math.h"

namespace ra::geometry {
namespace oracle {

using Q = boost::multiprecision::cpp_rational;

struct QVec2 {
  Q x, y;
};

inline std::vector<QVec2> to_q(const std::vector<Vec2>& poly) {
  std::vector<QVec2> out;
  for (const Vec2& v : poly) out.push_back({Q(v.x), Q(v.y)});
  return out;
}

// Twice the signed area (shoelace), exact.
inline Q twice_area(const std::vector<QVec2>& p) {
  Q s = 0;
  for (size_t i = 0; i < p.size(); ++i) {
    const QVec2& a = p[i];
    const QVec2& b = p[(i + 1) % p.size()];
    s += a.x * b.y - a.y * b.x;
  }
  return s;
}

// Keeps the part of polygon p with coord(v) >= bound (keep_above) or <= bound, coord = x or y.
inline std::vector<QVec2> clip_axis(const std::vector<QVec2>& p, bool use_x, const Q& bound,
                                    bool keep_above) {
  std::vector<QVec2> out;
  auto val = [&](const QVec2& v) {
    const Q d = (use_x ? v.x : v.y) - bound;
    return keep_above ? d : Q(-d);
  };
  for (size_t i = 0; i < p.size(); ++i) {
    const QVec2& a = p[i];
    const QVec2& b = p[(i + 1) % p.size()];
    const Q da = val(a), db = val(b);
    if (da >= 0) out.push_back(a);
    if ((da > 0 && db < 0) || (da < 0 && db > 0)) {
      const Q t = da / (da - db);
      out.push_back({a.x + t * (b.x - a.x), a.y + t * (b.y - a.y)});
    }
  }
  return out;
}

// Exact area of pixel px inside the convex polygon (any orientation).
inline Q pixel_area(const std::vector<QVec2>& poly, Pixel px) {
  std::vector<QVec2> p = clip_axis(poly, true, Q(px.x), true);
  p = clip_axis(p, true, Q(px.x + 1), false);
  p = clip_axis(p, false, Q(px.y), true);
  p = clip_axis(p, false, Q(px.y + 1), false);
  const Q a = twice_area(p) / 2;
  return a < 0 ? Q(-a) : a;
}

// Exact pixel-centre test with the top-left rule (y up, polygon made counter-clockwise here):
// inside when strictly left of every edge, or on an edge that goes down or is horizontal going
// left (and strictly left of the others).
inline bool covers_centre(std::vector<QVec2> poly, const QVec2& q) {
  if (twice_area(poly) < 0) std::reverse(poly.begin(), poly.end());
  if (twice_area(poly) == 0) return false;
  for (size_t i = 0; i < poly.size(); ++i) {
    const QVec2& a = poly[i];
    const QVec2& b = poly[(i + 1) % poly.size()];
    if (a.x == b.x && a.y == b.y) continue;
    const Q e = (b.x - a.x) * (q.y - a.y) - (b.y - a.y) * (q.x - a.x);
    if (e > 0) continue;
    if (e < 0) return false;
    const bool owns = b.y < a.y || (b.y == a.y && b.x < a.x);
    if (!owns) return false;
  }
  return true;
}

// The diamond-exit rule evaluated literally with a concrete perturbation eps (valid when eps is
// far below the coordinates' grid, e.g. 2^-30 for coordinates on a 1/8 grid): the closed segment
// a' b' (a' = a - (eps, eps^2)) meets the open diamond of f iff some t in [0, 1] satisfies the
// four strict side inequalities; then the fragment is produced unless b' is in the diamond.
inline bool diamond_fragment(const Vec2& a_in, const Vec2& b_in, Pixel f, const Q& eps) {
  const QVec2 a{Q(a_in.x) - eps, Q(a_in.y) - eps * eps};
  const QVec2 b{Q(b_in.x) - eps, Q(b_in.y) - eps * eps};
  const QVec2 c{Q(f.x) + Q(1) / 2, Q(f.y) + Q(1) / 2};
  const QVec2 d{b.x - a.x, b.y - a.y};
  const Q half = Q(1) / 2;
  // t in [lo, hi] with strictness flags.
  Q lo = 0, hi = 1;
  bool lo_strict = false, hi_strict = false;
  const int sides[4][2] = {{1, 1}, {1, -1}, {-1, 1}, {-1, -1}};
  for (const auto& s : sides) {
    // s.(a + t d - c) < 1/2  <=>  alpha + beta t < 1/2
    const Q alpha = s[0] * (a.x - c.x) + s[1] * (a.y - c.y);
    const Q beta = s[0] * d.x + s[1] * d.y;
    if (beta == 0) {
      if (!(alpha < half)) return false;
    } else {
      const Q t = (half - alpha) / beta;
      if (beta > 0) {  // t' < t
        if (t < hi || (t == hi && !hi_strict)) hi = t, hi_strict = true;
      } else {  // t' > t
        if (t > lo || (t == lo && !lo_strict)) lo = t, lo_strict = true;
      }
    }
  }
  const bool meets = lo < hi || (lo == hi && !lo_strict && !hi_strict);
  if (!meets) return false;
  Q db = 0;
  db += (b.x > c.x ? Q(b.x - c.x) : Q(c.x - b.x));
  db += (b.y > c.y ? Q(b.y - c.y) : Q(c.y - b.y));
  return !(db < half);
}

}  // namespace oracle
}  // namespace ra::geometry
