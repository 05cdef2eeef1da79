// Triangle rendering error TEs / TEu (NIST paper, section 3.6, eqs. 8-12). See
// triangle_metrics.h.
#include "runner/triangle_metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "runner/pixel_topology.h"

namespace ra {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace

double visible_edge_length(const ClippedPolygon& proj) {
  if (proj.status != ClipStatus::kVisible && proj.status != ClipStatus::kDegenerate) return 0;
  const size_t n = proj.vertices.size();
  if (n < 2) return 0;
  double len = 0;
  for (size_t i = 0; i < n; ++i) {
    if (i < proj.on_window_border.size() && proj.on_window_border[i]) continue;
    len += length(proj.vertices[(i + 1) % n] - proj.vertices[i]);
  }
  return len;
}

TriangleMetrics measure_triangle(const ClippedPolygon& proj, const PixelSet& lit, int width,
                                 int height) {
  thread_local PolygonCoverage coverage;  // reused: no allocation per triangle
  coverage.rows.clear();
  coverage.partial.clear();
  if (proj.status == ClipStatus::kVisible && !compute_coverage(proj.vertices, &coverage)) {
    // Cannot happen for clip_triangle's output (a finite convex hull inside the window); if it
    // does, say so rather than measure against an empty polygon.
    ClippedPolygon invalid;
    invalid.status = ClipStatus::kInvalid;
    return measure_triangle(invalid, coverage, lit, width, height);
  }
  return measure_triangle(proj, coverage, lit, width, height);
}

TriangleMetrics measure_triangle(const View& view, const Primitive& prim, const PixelSet& lit) {
  return measure_triangle(clip_triangle(view, prim.v[0], prim.v[1], prim.v[2]), lit, view.width,
                          view.height);
}

TriangleMetrics measure_triangle(const ClippedPolygon& proj, const PolygonCoverage& cov,
                                 const PixelSet& lit, int width, int height) {
  TriangleMetrics m;
  m.rendered = lit.size();
  if (proj.status == ClipStatus::kInvalid) {
    m.projected_area = m.rendered_outside = m.unrendered_inside = kNaN;
    m.te_signed = m.te_unsigned = m.te_signed_norm = m.te_unsigned_norm = kNaN;
    m.visible_edge_length = m.te_signed_edge_norm = m.te_unsigned_edge_norm = kNaN;
    return m;
  }
  m.valid = true;
  m.projected_area = proj.status == ClipStatus::kVisible ? proj.area : 0.0;

  // Walk the coverage rows and the lit runs together. Lit pixels in no coverage row, or in a row
  // but neither in its run nor among its partial pixels, are wholly outside (outside = 1).
  const std::vector<PixelRun>& runs = lit.runs();
  int64_t lit_covered = 0;  // lit pixels with positive area inside proj(T)
  double lit_partly_outside = 0, unlit_inside = 0;
  size_t j = 0;
  for (const CoverageRow& row : cov.rows) {
    while (j < runs.size() && runs[j].y < row.y) ++j;
    size_t row_end = j;
    while (row_end < runs.size() && runs[row_end].y == row.y) ++row_end;
    // The run: lit run pixels lose (1 - run_area) each, unlit ones miss run_area each.
    int64_t run_lit = 0;
    for (size_t r = j; r < row_end; ++r)
      run_lit += std::max<int64_t>(0, int64_t(std::min(runs[r].x_end, row.run_end)) -
                                          std::max(runs[r].x_begin, row.run_begin));
    const int64_t run_len = std::max(0, row.run_end - row.run_begin);
    lit_partly_outside += double(run_lit) * (1.0 - row.run_area);
    unlit_inside += double(run_len - run_lit) * row.run_area;
    // The partial pixels (increasing x) against the row's lit runs.
    int64_t partial_lit = 0;
    size_t q = j;
    for (uint32_t i = row.partial_begin; i < row.partial_end; ++i) {
      const PixelArea& pa = cov.partial[i];
      while (q < row_end && runs[q].x_end <= pa.x) ++q;
      if (q < row_end && runs[q].x_begin <= pa.x) {
        lit_partly_outside += 1.0 - pa.area;
        ++partial_lit;
      } else {
        unlit_inside += pa.area;
      }
    }
    lit_covered += run_lit + partial_lit;
    j = row_end;
  }
  const int64_t lit_wholly_outside = m.rendered - lit_covered;

  m.rendered_outside = double(lit_wholly_outside) + lit_partly_outside;
  m.unrendered_inside = unlit_inside;
  m.te_signed = m.rendered_outside - m.unrendered_inside;    // eq. 9
  m.te_unsigned = m.rendered_outside + m.unrendered_inside;  // eq. 10
  const double window_area = double(width) * double(height);
  m.te_signed_norm = m.te_signed / window_area;      // eq. 12
  m.te_unsigned_norm = m.te_unsigned / window_area;  // eq. 11
  m.visible_edge_length = visible_edge_length(proj);
  m.te_signed_edge_norm = m.visible_edge_length > 0 ? m.te_signed / m.visible_edge_length : kNaN;
  m.te_unsigned_edge_norm =
      m.visible_edge_length > 0 ? m.te_unsigned / m.visible_edge_length : kNaN;

  // Full window: as many in-window lit pixels as window pixels (the set has no duplicates).
  const int64_t window_pixels = int64_t(width) * int64_t(height);
  if (m.rendered >= window_pixels && window_pixels > 0) {
    PixelSet inside = lit;
    inside.clip_to({0, 0, width, height});
    m.full_window = inside.size() == window_pixels;
  }
  const PixelTopology topo = pixel_topology(lit);
  m.components = topo.components;
  m.holes = topo.holes;
  m.simply_connected = topo.simply_connected();
  return m;
}

}  // namespace ra
