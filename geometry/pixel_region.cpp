#include "geometry/pixel_region.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace ra::geometry {

int64_t PixelRegion::area() const {
  int64_t a = 0;
  for (const PixelRect& r : rects) a += r.area();
  return a;
}

PixelRect PixelRegion::bounds() const {
  if (rects.empty()) return {};
  PixelRect b = rects.front();
  for (const PixelRect& r : rects) {
    b.x0 = std::min(b.x0, r.x0), b.y0 = std::min(b.y0, r.y0);
    b.x1 = std::max(b.x1, r.x1), b.y1 = std::max(b.y1, r.y1);
  }
  return b;
}

namespace {
bool rects_overlap(const PixelRect& a, const PixelRect& b) {
  return a.x0 < b.x1 && b.x0 < a.x1 && a.y0 < b.y1 && b.y0 < a.y1;
}
}  // namespace

bool PixelRegion::overlaps(const PixelRegion& other) const {
  if (empty() || other.empty() || !rects_overlap(bounds(), other.bounds())) return false;
  for (const PixelRect& a : rects)
    for (const PixelRect& b : other.rects)
      if (rects_overlap(a, b)) return true;
  return false;
}

bool PixelRegion::contains(Pixel p) const {
  for (const PixelRect& r : rects)
    if (r.x0 <= p.x && p.x < r.x1 && r.y0 <= p.y && p.y < r.y1) return true;
  return false;
}

PixelRegion strip_region(const ClippedSegment& s, int width, int height, int margin, int chunk) {
  PixelRegion region;
  if (!ideally_visible(s)) return region;
  // Work in (major, minor) coordinates: u along the axis with the larger extent.
  const bool x_major = std::abs(s.p1.x - s.p0.x) >= std::abs(s.p1.y - s.p0.y);
  Vec2 a = x_major ? s.p0 : Vec2{s.p0.y, s.p0.x};
  Vec2 b = x_major ? s.p1 : Vec2{s.p1.y, s.p1.x};
  if (a.x > b.x) std::swap(a, b);
  const int major_size = x_major ? width : height, minor_size = x_major ? height : width;
  const double slope = b.x > a.x ? (b.y - a.y) / (b.x - a.x) : 0.0;  // |slope| <= 1
  if (chunk <= 0) {
    constexpr double kMinorSpan = 32.0;  // pixels of minor extent per rectangle, about
    chunk = std::abs(slope) * 4096 <= kMinorSpan ? 4096 : int(kMinorSpan / std::abs(slope));
    chunk = std::max(chunk, 16);
  }
  // The segment's minor coordinate at major coordinate u, held constant beyond its ends.
  auto minor_at = [&](double u) {
    const double t = std::clamp(u, a.x, b.x);
    return a.y + slope * (t - a.x);
  };
  const int u_begin = std::max(0, int(std::floor(a.x)) - margin);
  const int u_end = std::min(major_size, int(std::floor(b.x)) + 1 + margin);
  for (int u0 = u_begin; u0 < u_end; u0 += chunk) {
    const int u1 = std::min(u_end, u0 + chunk);
    // Columns u0 .. u1-1 cover major coordinates [u0, u1]; widened by the margin, so that the
    // diagonal neighbours of the pixels touched in the next chunk are inside too. The line is
    // monotone in between.
    const double m0 = minor_at(u0 - margin), m1 = minor_at(u1 + margin);
    const int v0 = std::max(0, int(std::floor(std::min(m0, m1))) - margin);
    const int v1 = std::min(minor_size, int(std::floor(std::max(m0, m1))) + 1 + margin);
    if (v1 <= v0) continue;
    region.rects.push_back(x_major ? PixelRect{u0, v0, u1, v1} : PixelRect{v0, u0, v1, u1});
  }
  return region;
}

PixelRegion band_region(const ClippedPolygon& p, int width, int height, int margin, int band_rows) {
  PixelRegion region;
  if (p.status != ClipStatus::kVisible && p.status != ClipStatus::kDegenerate) return region;
  const PixelRect box = bounding_rect(p, width, height, margin);
  if (box.empty()) return region;
  const std::vector<Vec2>& v = p.vertices;
  const size_t n = v.size();
  // The polygon's x-range over the slab lo <= y <= hi: its edges clipped to the slab (a convex
  // polygon's extreme x over a slab lies on an edge), vertices included. {+inf, -inf} when none.
  auto x_range = [&](double lo, double hi) {
    double x_min = std::numeric_limits<double>::infinity(), x_max = -x_min;
    auto take = [&](double x) { x_min = std::min(x_min, x), x_max = std::max(x_max, x); };
    for (size_t i = 0; i < n; ++i) {
      Vec2 a = v[i], b = v[(i + 1) % n];
      if (a.y > b.y) std::swap(a, b);
      if (b.y < lo || a.y > hi) continue;
      auto x_at = [&](double y) {  // on the edge; a horizontal edge lies inside the slab whole
        return b.y > a.y ? a.x + (b.x - a.x) * ((y - a.y) / (b.y - a.y)) : a.x;
      };
      take(a.y >= lo ? a.x : x_at(lo));
      take(b.y <= hi ? b.x : x_at(hi));
      if (b.y == a.y) take(b.x);
    }
    return std::pair{x_min, x_max};
  };
  for (int y0 = box.y0; y0 < box.y1; y0 += band_rows) {
    const int y1 = std::min(box.y1, y0 + band_rows);
    const auto [x_min, x_max] = x_range(double(y0 - margin), double(y1 + margin));
    if (!(x_min <= x_max)) continue;  // the polygon does not reach this band
    PixelRect r{std::max(box.x0, int32_t(std::floor(x_min)) - margin), y0,
                std::min(box.x1, int32_t(std::floor(x_max)) + 1 + margin), y1};
    if (!r.empty()) region.rects.push_back(r);
  }
  return region;
}

}  // namespace ra::geometry
