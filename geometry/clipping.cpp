// Homogeneous clipping of segments and triangles and the map to window coordinates (NIST paper,
// sections 3.5-3.6: proj(.) is the projection clipped to the viewing area). See clipping.h.
#include "geometry/clipping.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "geometry/exact_predicates.h"

namespace ra::geometry {
namespace {

bool is_finite(Vec4 c) {
  return std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z) && std::isfinite(c.w);
}
bool is_finite(Vec2 p) { return std::isfinite(p.x) && std::isfinite(p.y); }

// Puts a point computed on `plane` exactly on it (x = -w on the left plane, ...), so that later
// window coordinates of clipped ends are exactly 0, W, 0 or H.
void snap_to_plane(Vec4& c, int plane) {
  switch (plane) {
    case kPlaneLeft:
      c.x = -c.w;
      break;
    case kPlaneRight:
      c.x = c.w;
      break;
    case kPlaneBottom:
      c.y = -c.w;
      break;
    case kPlaneTop:
      c.y = c.w;
      break;
    case kPlaneNear:
      c.z = -c.w;
      break;
    case kPlaneFar:
      c.z = c.w;
      break;
    default:
      break;
  }
}

// c_in + t (c_out - c_in) with t = d_in / (d_in - d_out), d_in > 0 > d_out: from the inside end.
// The point is put exactly on `plane`, and on every earlier plane that holds both ends (an edge
// along the right border cut by the top plane gives the window corner exactly).
Vec4 intersect_from_inside(Vec4 c_in, double d_in, Vec4 c_out, double d_out, int plane) {
  const double t = d_in / (d_in - d_out);
  Vec4 p = c_in + t * (c_out - c_in);
  for (int k = 0; k < plane; ++k)
    if (plane_distance(c_in, k) == 0 && plane_distance(c_out, k) == 0) snap_to_plane(p, k);
  snap_to_plane(p, plane);
  return p;
}

// Window coordinates of a point of the closed clip volume (w > 0); the normalised device
// coordinates are clamped to [-1, 1], which only removes rounding (see clipping.h).
Vec2 to_window(Vec4 c, int width, int height) {
  const double nx = std::clamp(c.x / c.w, -1.0, 1.0);
  const double ny = std::clamp(c.y / c.w, -1.0, 1.0);
  return {(nx + 1.0) * 0.5 * width, (ny + 1.0) * 0.5 * height};
}

}  // namespace

const char* clip_status_name(ClipStatus s) {
  switch (s) {
    case ClipStatus::kVisible:
      return "visible";
    case ClipStatus::kDegenerate:
      return "degenerate";
    case ClipStatus::kInvisible:
      return "invisible";
    case ClipStatus::kInvalid:
      return "invalid";
  }
  return "?";
}

double plane_distance(Vec4 c, int plane) {
  switch (plane) {
    case kPlaneLeft:
      return c.w + c.x;
    case kPlaneRight:
      return c.w - c.x;
    case kPlaneBottom:
      return c.w + c.y;
    case kPlaneTop:
      return c.w - c.y;
    case kPlaneNear:
      return c.w + c.z;
    case kPlaneFar:
      return c.w - c.z;
    default:
      return 0;
  }
}

ClippedSegment clip_segment(Vec4 c0, Vec4 c1, int width, int height) {
  ClippedSegment s;
  if (!is_finite(c0) || !is_finite(c1)) {
    s.status = ClipStatus::kInvalid;
    return s;
  }
  // Liang-Barsky: each plane bounds t from below (entering) or above (leaving).
  double t0 = 0, t1 = 1;
  int plane0 = -1, plane1 = -1;
  for (int k = 0; k < 6; ++k) {
    const double d0 = plane_distance(c0, k), d1 = plane_distance(c1, k);
    if (d0 < 0 && d1 < 0) return s;  // wholly outside this plane
    if (d0 < 0) {
      const double t = d0 / (d0 - d1);
      if (t > t0) t0 = t, plane0 = k;
    } else if (d1 < 0) {
      const double t = d0 / (d0 - d1);
      if (t < t1) t1 = t, plane1 = k;
    }
  }
  if (t0 > t1) return s;
  s.t0 = t0;
  s.t1 = t1;
  s.plane0 = plane0;
  s.plane1 = plane1;
  s.clip0 = c0;
  s.clip1 = c1;
  if (plane0 >= 0) {
    s.clip0 = c0 + t0 * (c1 - c0);
    snap_to_plane(s.clip0, plane0);
  }
  if (plane1 >= 0) {
    s.clip1 = c0 + t1 * (c1 - c0);
    snap_to_plane(s.clip1, plane1);
  }
  // Inside the closed volume w >= |x|, so w <= 0 only at the homogeneous origin (a degenerate
  // matrix): no window position exists.
  if (!(s.clip0.w > 0) || !(s.clip1.w > 0)) {
    s.status = ClipStatus::kInvalid;
    return s;
  }
  s.p0 = to_window(s.clip0, width, height);
  s.p1 = to_window(s.clip1, width, height);
  if (!is_finite(s.p0) || !is_finite(s.p1)) {  // overflow of huge (but finite) input
    s.status = ClipStatus::kInvalid;
    return s;
  }
  s.status =
      (s.p0.x == s.p1.x && s.p0.y == s.p1.y) ? ClipStatus::kDegenerate : ClipStatus::kVisible;
  return s;
}

ClippedSegment clip_segment(const View& view, Vec3 e1, Vec3 e2) {
  return clip_segment(view.to_clip(e1), view.to_clip(e2), view.width, view.height);
}

ClippedPolygon clip_triangle(Vec4 a, Vec4 b, Vec4 c, int width, int height) {
  ClippedPolygon out;
  if (!is_finite(a) || !is_finite(b) || !is_finite(c)) {
    out.status = ClipStatus::kInvalid;
    return out;
  }
  // Sutherland-Hodgman; each plane adds at most one vertex, so 3 + 6 = 9 suffice.
  std::array<Vec4, 12> buf_a, buf_b;
  Vec4* poly = buf_a.data();
  Vec4* next = buf_b.data();
  int n = 3;
  poly[0] = a, poly[1] = b, poly[2] = c;
  for (int k = 0; k < 6 && n > 0; ++k) {
    double d[12];
    bool all_inside = true;
    for (int i = 0; i < n; ++i) {
      d[i] = plane_distance(poly[i], k);
      all_inside = all_inside && d[i] >= 0;
    }
    if (all_inside) continue;
    int m = 0;
    for (int i = 0; i < n; ++i) {
      const int j = (i + 1) % n;
      if (d[i] >= 0) next[m++] = poly[i];
      // A vertex exactly on the plane is kept as is; no intersection is made next to it.
      if (d[i] > 0 && d[j] < 0) {
        next[m++] = intersect_from_inside(poly[i], d[i], poly[j], d[j], k);
      } else if (d[i] < 0 && d[j] > 0) {
        next[m++] = intersect_from_inside(poly[j], d[j], poly[i], d[i], k);
      }
    }
    std::swap(poly, next);
    n = m;
  }
  if (n == 0) return out;  // invisible
  std::vector<Vec2> win(n);
  for (int i = 0; i < n; ++i) {
    if (!(poly[i].w > 0)) {  // the homogeneous origin: see clip_segment
      out.status = ClipStatus::kInvalid;
      return out;
    }
    win[i] = to_window(poly[i], width, height);
    if (!is_finite(win[i])) {  // overflow of huge (but finite) input
      out.status = ClipStatus::kInvalid;
      return out;
    }
  }
  // Facing from the clipped polygon in its original vertex order (clipping keeps the order).
  const double facing_area = polygon_signed_area(win);
  out.vertices = convex_hull(std::move(win));
  const size_t nv = out.vertices.size();
  out.area = nv >= 3 ? polygon_signed_area(out.vertices) : 0.0;
  if (out.area > 0) {
    out.status = ClipStatus::kVisible;
    out.orientation = facing_area > 0 ? 1 : facing_area < 0 ? -1 : 0;
  } else {
    out.status = ClipStatus::kDegenerate;
    out.area = 0;
  }
  const double W = width, H = height;
  out.on_window_border.resize(nv > 1 ? nv : 0);
  for (size_t i = 0; i < out.on_window_border.size(); ++i) {
    const Vec2 u = out.vertices[i], v = out.vertices[(i + 1) % nv];
    out.on_window_border[i] = (u.x == 0 && v.x == 0) || (u.x == W && v.x == W) ||
                              (u.y == 0 && v.y == 0) || (u.y == H && v.y == H);
  }
  return out;
}

ClippedPolygon clip_triangle(const View& view, Vec3 a, Vec3 b, Vec3 c) {
  return clip_triangle(view.to_clip(a), view.to_clip(b), view.to_clip(c), view.width, view.height);
}

namespace {

PixelRect rect_of_points(const Vec2* pts, size_t n, int width, int height, int margin) {
  if (n == 0) return {};
  double x0 = pts[0].x, x1 = pts[0].x, y0 = pts[0].y, y1 = pts[0].y;
  for (size_t i = 1; i < n; ++i) {
    x0 = std::min(x0, pts[i].x), x1 = std::max(x1, pts[i].x);
    y0 = std::min(y0, pts[i].y), y1 = std::max(y1, pts[i].y);
  }
  // The points are inside [0, W] x [0, H], so the int conversions cannot overflow.
  PixelRect r;
  r.x0 = std::max(0, int32_t(std::floor(x0)) - margin);
  r.y0 = std::max(0, int32_t(std::floor(y0)) - margin);
  r.x1 = std::min(width, int32_t(std::floor(x1)) + 1 + margin);
  r.y1 = std::min(height, int32_t(std::floor(y1)) + 1 + margin);
  return r;
}

}  // namespace

PixelRect bounding_rect(const ClippedSegment& s, int width, int height, int margin) {
  if (!ideally_visible(s)) return {};
  const Vec2 pts[2] = {s.p0, s.p1};
  return rect_of_points(pts, 2, width, height, margin);
}

PixelRect bounding_rect(const ClippedPolygon& p, int width, int height, int margin) {
  if (p.status != ClipStatus::kVisible && p.status != ClipStatus::kDegenerate) return {};
  return rect_of_points(p.vertices.data(), p.vertices.size(), width, height, margin);
}

double polygon_signed_area(const std::vector<Vec2>& poly) {
  const size_t n = poly.size();
  if (n < 3) return 0;
  const Vec2 o = poly[0];
  double twice = 0;
  for (size_t i = 1; i + 1 < n; ++i) twice += cross(poly[i] - o, poly[i + 1] - o);
  return 0.5 * twice;
}

std::vector<Vec2> convex_hull(std::vector<Vec2> pts) {
  // Andrew's monotone chain with exact orientation; collinear points are dropped (<= 0).
  std::sort(pts.begin(), pts.end(),
            [](Vec2 p, Vec2 q) { return p.x != q.x ? p.x < q.x : p.y < q.y; });
  pts.erase(
      std::unique(pts.begin(), pts.end(), [](Vec2 p, Vec2 q) { return p.x == q.x && p.y == q.y; }),
      pts.end());
  const size_t n = pts.size();
  if (n < 3) return pts;
  std::vector<Vec2> hull(2 * n);
  size_t k = 0;
  for (size_t i = 0; i < n; ++i) {  // lower chain
    while (k >= 2 && orient2d(hull[k - 2], hull[k - 1], pts[i]) <= 0) --k;
    hull[k++] = pts[i];
  }
  for (size_t i = n - 1, lower = k + 1; i-- > 0;) {  // upper chain
    while (k >= lower && orient2d(hull[k - 2], hull[k - 1], pts[i]) <= 0) --k;
    hull[k++] = pts[i];
  }
  hull.resize(k - 1);  // the last point repeats the first
  if (hull.size() == 2 && hull[0].x == hull[1].x && hull[0].y == hull[1].y) hull.resize(1);
  return hull;
}

}  // namespace ra::geometry
