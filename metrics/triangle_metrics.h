// The triangle audit of the NIST paper, section 3.6: the area of rendered pixels outside the
// projected triangle and of unrendered pixels inside it. Coordinates: GL window coordinates in
// pixels (pixel (i, j) covers [i, i+1) x [j, j+1)); areas in px^2; proj(T) is the triangle
// projected and clipped to the window (ClippedPolygon).
//
// Reading of eqs. 9-10 (the extracted text is scrambled, the definitions around it are not):
//   TEs = sum_{p in P(T)} outside(proj T, p) - sum_{p not in P(T)} inside(proj T, p)   (eq. 9)
//   TEu = sum_{p in P(T)} outside(proj T, p) + sum_{p not in P(T)} inside(proj T, p)   (eq. 10)
// over all pixels, with inside + outside = 1 (eq. 8). A rendered pixel wholly inside proj(T) and
// an unrendered pixel wholly outside contribute 0, so only the polygon's boundary pixels are
// visited one by one; its interior runs are counted against the lit runs of P(T) (pixel_set.h):
// O(rows + boundary pixels + lit runs), never O(W * H) or O(|P|). The connectivity fields cost
// O(runs) (pixel_topology.h). Note TEs = |P(T)| - area(proj T).
//
// Edge normalisation (the paper's alternative, "divide by the combined length of the visible
// edges"). Decision: the visible edges are the boundary of proj(T) that lies inside the window:
// the parts of the triangle's edges inside the clip volume plus the edges created by the near and
// far planes (pixels are sampled, and can be wrong, along those too), but not the edges created
// by (or lying on) the window sides x = 0, x = W, y = 0, y = H: pixels end exactly there, so no
// rasterization error is possible along them.
//
// Antialiased renderings (multisample platforms, see platforms/readback_measurement.cpp): a pixel p is partly lit,
// with coverage c(p) = samples lit / samples in [0, 1], and the same sums become
//   TEs_cov = sum_p (c(p) - a(p)) = total coverage - area(proj T)
//   TEu_cov = sum_p |c(p) - a(p)|
// over all pixels, a(p) = inside(proj T, p) the exact area; with c in {0, 1} they are eqs. 9-10.
// rendered_outside becomes the coverage in excess of the area (sum of max(c - a, 0)) and
// unrendered_inside the area in excess of the coverage (sum of max(a - c, 0)). Normalisations,
// edge length and connectivity (of the pixels with any coverage) are as above.
#pragma once

#include <cstdint>
#include <vector>

#include "geometry/clipping.h"
#include "geometry/pixel_coverage.h"
#include "geometry/pixel_set.h"

namespace ra::metrics {

struct TriangleMetrics {
  bool valid = false;                // false when the clipped triangle is invalid (NaN/inf input)
  double projected_area = 0;         // area of proj(T), px^2
  int64_t rendered = 0;              // |P(T)|, lit pixels
  double rendered_outside = 0;       // sum over lit pixels of outside(proj T, p), px^2, >= 0
  double unrendered_inside = 0;      // sum over unlit pixels of inside(proj T, p), px^2, >= 0
  double te_signed = 0;              // TEs, eq. 9, px^2: > 0 biased to lit pixels outside
  double te_unsigned = 0;            // TEu, eq. 10, px^2
  double te_signed_norm = 0;         // TEs / (W H), eq. 12, normalised window area units
  double te_unsigned_norm = 0;       // TEu / (W H), eq. 11
  double visible_edge_length = 0;    // px, see the decision above
  double te_signed_edge_norm = 0;    // TEs / visible_edge_length, px; NaN when the length is 0
  double te_unsigned_edge_norm = 0;  // TEu / visible_edge_length, px; NaN when the length is 0
  bool full_window = false;          // every pixel of the window is lit
  int64_t components = 0;            // 8-connected components of the lit pixels (pixel_topology.h)
  int64_t holes = 0;                 // enclosed 4-connected unlit components
  bool simply_connected = false;     // components == 1 && holes == 0
};

// Length of the visible edges of a clipped triangle, px: the polygon's perimeter without the
// edges on the window border (ClippedPolygon::on_window_border). A zero-area polygon (a segment)
// counts both of its sides; invisible or invalid: 0.
double visible_edge_length(const geometry::ClippedPolygon& proj);

// The triangle metrics of `lit` (the pixels rendered for the triangle, sorted, GL window
// coordinates; pixels outside the window count as wholly outside proj(T)) against `proj`, in a
// width x height window (W * H up to 2^62). An invisible or zero-area proj(T) has inside = 0
// everywhere, so every lit pixel is error. Status kInvalid: valid = false, metrics NaN.
TriangleMetrics measure_triangle(const geometry::ClippedPolygon& proj,
                                 const geometry::PixelSet& lit, int width, int height);
// The same for triangle `prim` (Kind::kTriangle) under `view`: clip_triangle, then the above.
TriangleMetrics measure_triangle(const geometry::View& view, const geometry::Primitive& prim,
                                 const geometry::PixelSet& lit);
// The same with the coverage of proj.vertices already computed (compute_coverage), e.g. once per
// triangle when several renderers are compared.
TriangleMetrics measure_triangle(const geometry::ClippedPolygon& proj,
                                 const geometry::PolygonCoverage& coverage,
                                 const geometry::PixelSet& lit, int width, int height);

// The coverage form of the metrics (TEs_cov, TEu_cov, see the top of this file) for an antialiased
// rendering: `lit` the pixels with any coverage (sorted, GL window coordinates), `samples_lit[i]`
// the samples lit of the i-th pixel of `lit` in its (y, x) order, 1..samples, `samples` (>= 1) the
// samples per pixel. Cost: O(rows + boundary pixels + lit runs + |lit|), the last a pass over the
// bytes of samples_lit (the readback of those pixels already cost as much). `rendered` = |lit|.
TriangleMetrics measure_triangle_coverage(const geometry::ClippedPolygon& proj,
                                          const geometry::PixelSet& lit,
                                          const std::vector<uint8_t>& samples_lit, int samples,
                                          int width, int height);
TriangleMetrics measure_triangle_coverage(const geometry::ClippedPolygon& proj,
                                          const geometry::PolygonCoverage& coverage,
                                          const geometry::PixelSet& lit,
                                          const std::vector<uint8_t>& samples_lit, int samples,
                                          int width, int height);

}  // namespace ra::metrics
