// Triangle rendering error TEs / TEu (NIST paper, section 3.6, eqs. 8-12). See
// triangle_metrics.h.
#include "metrics/triangle_metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "geometry/pixel_topology.h"

namespace ra::metrics {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The fields that follow from rendered_outside and unrendered_inside, and the connectivity of lit.
void finish_metrics(TriangleMetrics& m, const geometry::ClippedPolygon& proj,
                    const geometry::PixelSet& lit, int width, int height) {
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
    geometry::PixelSet inside = lit;
    inside.clip_to({0, 0, width, height});
    m.full_window = inside.size() == window_pixels;
  }
  const geometry::PixelTopology topo = geometry::pixel_topology(lit);
  m.components = topo.components;
  m.holes = topo.holes;
  m.simply_connected = topo.simply_connected();
}

// Metrics of an invalid proj(T): NaN.
TriangleMetrics invalid_metrics(int64_t rendered) {
  TriangleMetrics m;
  m.rendered = rendered;
  m.projected_area = m.rendered_outside = m.unrendered_inside = kNaN;
  m.te_signed = m.te_unsigned = m.te_signed_norm = m.te_unsigned_norm = kNaN;
  m.visible_edge_length = m.te_signed_edge_norm = m.te_unsigned_edge_norm = kNaN;
  return m;
}

// What both measures know before their walk: invalid metrics for an invalid projection, else the
// pixels lit and the projected area (0 when the triangle is clipped away).
TriangleMetrics started_metrics(const geometry::ClippedPolygon& proj,
                                const geometry::PixelSet& lit) {
  if (proj.status == geometry::ClipStatus::kInvalid) return invalid_metrics(lit.size());
  TriangleMetrics m;
  m.rendered = lit.size();
  m.valid = true;
  m.projected_area = proj.status == geometry::ClipStatus::kVisible ? proj.area : 0.0;
  return m;
}

}  // namespace

double visible_edge_length(const geometry::ClippedPolygon& proj) {
  if (proj.status != geometry::ClipStatus::kVisible &&
      proj.status != geometry::ClipStatus::kDegenerate)
    return 0;
  const size_t n = proj.vertices.size();
  if (n < 2) return 0;
  double len = 0;
  for (size_t i = 0; i < n; ++i) {
    if (i < proj.on_window_border.size() && proj.on_window_border[i]) continue;
    len += geometry::length(proj.vertices[(i + 1) % n] - proj.vertices[i]);
  }
  return len;
}

TriangleMetrics measure_triangle(const geometry::ClippedPolygon& proj,
                                 const geometry::PixelSet& lit, int width, int height) {
  thread_local geometry::PolygonCoverage coverage;  // reused: no allocation per triangle
  coverage.rows.clear();
  coverage.partial.clear();
  if (proj.status == geometry::ClipStatus::kVisible &&
      !geometry::compute_coverage(proj.vertices, &coverage)) {
    // Cannot happen for clip_triangle's output (a finite convex hull inside the window); if it
    // does, say so rather than measure against an empty polygon.
    geometry::ClippedPolygon invalid;
    invalid.status = geometry::ClipStatus::kInvalid;
    return measure_triangle(invalid, coverage, lit, width, height);
  }
  return measure_triangle(proj, coverage, lit, width, height);
}

TriangleMetrics measure_triangle(const geometry::View& view, const geometry::Primitive& prim,
                                 const geometry::PixelSet& lit) {
  return measure_triangle(geometry::clip_triangle(view, prim.v[0], prim.v[1], prim.v[2]), lit,
                          view.width, view.height);
}

TriangleMetrics measure_triangle(const geometry::ClippedPolygon& proj,
                                 const geometry::PolygonCoverage& cov,
                                 const geometry::PixelSet& lit, int width, int height) {
  TriangleMetrics m = started_metrics(proj, lit);
  if (!m.valid) return m;

  // Walk the coverage rows and the lit runs together. Lit pixels in no coverage row, or in a row
  // but neither in its run nor among its partial pixels, are wholly outside (outside = 1).
  const std::vector<geometry::PixelRun>& runs = lit.runs();
  int64_t lit_covered = 0;  // lit pixels with positive area inside proj(T)
  double lit_partly_outside = 0, unlit_inside = 0;
  size_t j = 0;
  for (const geometry::CoverageRow& row : cov.rows) {
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
      const geometry::PixelArea& pa = cov.partial[i];
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
  finish_metrics(m, proj, lit, width, height);
  return m;
}

TriangleMetrics measure_triangle_coverage(const geometry::ClippedPolygon& proj,
                                          const geometry::PixelSet& lit,
                                          const std::vector<uint8_t>& samples_lit, int samples,
                                          int width, int height) {
  thread_local geometry::PolygonCoverage coverage;
  coverage.rows.clear();
  coverage.partial.clear();
  if (proj.status == geometry::ClipStatus::kVisible &&
      !geometry::compute_coverage(proj.vertices, &coverage))
    return invalid_metrics(lit.size());  // as measure_triangle: cannot happen for clip_triangle's
  return measure_triangle_coverage(proj, coverage, lit, samples_lit, samples, width, height);
}

TriangleMetrics measure_triangle_coverage(const geometry::ClippedPolygon& proj,
                                          const geometry::PolygonCoverage& cov,
                                          const geometry::PixelSet& lit,
                                          const std::vector<uint8_t>& samples_lit, int samples,
                                          int width, int height) {
  if (samples < 1 || samples_lit.size() != size_t(lit.size()))
    throw std::invalid_argument("measure_triangle_coverage: " + std::to_string(samples_lit.size()) +
                                " coverage values for " + std::to_string(lit.size()) +
                                " pixels, " + std::to_string(samples) + " samples per pixel");
  TriangleMetrics m = started_metrics(proj, lit);
  if (!m.valid) return m;

  // Where each lit run's coverage values start in samples_lit.
  const std::vector<geometry::PixelRun>& runs = lit.runs();
  thread_local std::vector<size_t> first;
  first.resize(runs.size());
  size_t offset = 0;
  for (size_t r = 0; r < runs.size(); ++r) first[r] = offset, offset += size_t(runs[r].length());
  int64_t samples_total = 0;
  for (uint8_t k : samples_lit) samples_total += k;

  // Walk the coverage rows and the lit runs together, as measure_triangle does, with c(p) in
  // place of 1 for a lit pixel. Covered pixels in no row, or in a row but neither in its run nor
  // among its partial pixels, have a = 0: they add their coverage, summed at the end.
  const double per_sample = 1.0 / samples;  // exact for a power of two
  int64_t samples_visited = 0;
  double excess = 0, missing = 0;  // sums of max(c - a, 0) and max(a - c, 0)
  auto add = [&](uint8_t k, double area) {
    samples_visited += k;
    const double d = k * per_sample - area;
    if (d > 0) excess += d; else missing -= d;
  };
  size_t j = 0;
  for (const geometry::CoverageRow& row : cov.rows) {
    while (j < runs.size() && runs[j].y < row.y) ++j;
    size_t row_end = j;
    while (row_end < runs.size() && runs[row_end].y == row.y) ++row_end;
    int64_t run_lit = 0;
    for (size_t r = j; r < row_end; ++r) {
      const int32_t xb = std::max(runs[r].x_begin, row.run_begin);
      const int32_t xe = std::min(runs[r].x_end, row.run_end);
      for (int32_t x = xb; x < xe; ++x) add(samples_lit[first[r] + size_t(x - runs[r].x_begin)], row.run_area);
      run_lit += std::max(0, xe - xb);
    }
    missing += double(std::max(0, row.run_end - row.run_begin) - run_lit) * row.run_area;
    size_t q = j;
    for (uint32_t i = row.partial_begin; i < row.partial_end; ++i) {
      const geometry::PixelArea& pa = cov.partial[i];
      while (q < row_end && runs[q].x_end <= pa.x) ++q;
      if (q < row_end && runs[q].x_begin <= pa.x)
        add(samples_lit[first[q] + size_t(pa.x - runs[q].x_begin)], pa.area);
      else
        missing += pa.area;
    }
    j = row_end;
  }
  excess += double(samples_total - samples_visited) * per_sample;

  m.rendered_outside = excess;
  m.unrendered_inside = missing;
  finish_metrics(m, proj, lit, width, height);
  return m;
}

}  // namespace ra::metrics
