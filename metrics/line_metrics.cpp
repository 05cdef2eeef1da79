// Line segment rendering errors LSEs / LSEu with extent errors (NIST paper, section 3.5,
// eqs. 3-7). See line_metrics.h.
#include "metrics/line_metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/pixel_topology.h"

namespace ra::metrics {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

inline geometry::Vec2 centre(geometry::Pixel p) { return {p.x + 0.5, p.y + 0.5}; }

void set_undefined(LineMetrics& m) {
  m.mean_signed_offset = m.lse_signed = m.sum_abs_offset = kNaN;
  m.start_extent = m.end_extent = m.extent_error = kNaN;
  m.lse_unsigned = m.lse_signed_norm = m.lse_unsigned_norm = kNaN;
}

}  // namespace

double signed_distance_to_line(geometry::Vec2 q, geometry::Vec2 a, geometry::Vec2 b) {
  const geometry::Vec2 d = b - a;
  const double len = geometry::length(d);
  if (!(len > 0)) return kNaN;
  return geometry::cross(d, q - a) / len;
}

std::vector<geometry::Pixel> order_along_line(const geometry::PixelSet& lit, geometry::Vec2 e1,
                                              geometry::Vec2 e2) {
  const geometry::Vec2 d = e2 - e1;
  const bool point = d.x == 0 && d.y == 0;
  // Key: projection on the line (a positive multiple of it), or squared distance for a point.
  auto key = [&](geometry::Pixel p) {
    const geometry::Vec2 r = centre(p) - e1;
    return point ? geometry::dot(r, r) : geometry::dot(d, r);
  };
  std::vector<geometry::Pixel> out(lit.begin(), lit.end());
  std::stable_sort(out.begin(), out.end(), [&](geometry::Pixel a, geometry::Pixel b) {
    return key(a) < key(b);
  });  // ties keep (y, x)
  return out;
}

LineMetrics measure_line(const geometry::ClippedSegment& seg, const geometry::PixelSet& lit,
                         int width, int height) {
  LineMetrics m;
  m.count = int64_t(lit.size());
  if (!geometry::ideally_visible(seg)) {
    m.projected_length = kNaN;
    set_undefined(m);
    return m;
  }
  m.valid = true;
  m.components = geometry::count_components8(lit);
  m.gaps = std::max<int64_t>(0, m.components - 1);
  m.chain = geometry::is_simple_chain8(lit);
  const geometry::Vec2 e1 = seg.p0, e2 = seg.p1, d = e2 - e1;
  const double len = geometry::length(d);
  m.projected_length = len;
  m.degenerate = !(len > 0);
  if (lit.empty()) {
    set_undefined(m);
    return m;
  }
  const double n = double(lit.size());
  const double norm = std::sqrt(double(width) * double(height));  // one normalised unit, px

  if (m.degenerate) {
    // The point ptProj(e1): offsets are distances to it; the bias is the mean offset vector.
    geometry::Vec2 sum{0, 0};
    double sum_abs = 0, dmin = INFINITY, dmax = -INFINITY;
    for (const geometry::Pixel& p : lit) {
      const geometry::Vec2 r = centre(p) - e1;
      const double dist = geometry::length(r);
      sum = sum + r;
      sum_abs += dist;
      if (dist < dmin) dmin = dist, m.first = p;
      if (dist >= dmax) dmax = dist, m.last = p;
    }
    m.mean_signed_offset = kNaN;  // no side without a line
    m.lse_signed = geometry::length((1.0 / n) * sum);
    m.sum_abs_offset = sum_abs;
    m.start_extent = m.end_extent = m.extent_error = 0;
  } else {
    const geometry::Vec2 u = (1.0 / len) * d;  // unit direction e1 -> e2
    double sum = 0, sum_abs = 0, smin = INFINITY, smax = -INFINITY;
    for (const geometry::Pixel& p :
         lit) {  // (y, x) order: ties go to the first for min, last for max
      const geometry::Vec2 r = centre(p) - e1;
      const double ds = geometry::cross(u, r);  // > 0 left of e1 -> e2
      const double s = geometry::dot(u, r);     // position along the line from ptProj(e1)
      sum += ds;
      sum_abs += std::fabs(ds);
      if (s < smin) smin = s, m.first = p;
      if (s >= smax) smax = s, m.last = p;
    }
    m.mean_signed_offset = sum / n;
    m.lse_signed = std::fabs(sum / n);  // eq. 3
    m.sum_abs_offset = sum_abs;
    m.start_extent = -smin;                                    // > 0: beyond ptProj(e1)
    m.end_extent = smax - len;                                 // > 0: beyond ptProj(e2)
    m.extent_error = std::fabs(smin) + std::fabs(smax - len);  // eq. 4
  }
  m.lse_unsigned = (m.sum_abs_offset + m.extent_error) / (n + 2);  // eq. 5
  m.lse_signed_norm = m.lse_signed / norm;                         // eq. 7
  m.lse_unsigned_norm = m.lse_unsigned / norm;                     // eq. 6
  return m;
}

LineMetrics measure_line(const geometry::View& view, const geometry::Primitive& prim,
                         const geometry::PixelSet& lit) {
  return measure_line(geometry::clip_segment(view, prim.v[0], prim.v[1]), lit, view.width,
                      view.height);
}

}  // namespace ra::metrics
