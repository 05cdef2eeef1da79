// The line segment audit of the NIST paper, section 3.5: offset errors of the rendered pixels from
// the projected line and extent errors at its ends. Coordinates: GL window coordinates in pixels,
// a rendered pixel standing for its centre (i + 0.5, j + 0.5); lengths in px.
//
// Definitions (eqs. 3-7), with e1, e2 the ends of the VISIBLE part of the segment (clipped to the
// clip volume: ClippedSegment::p0 = ptProj(e1), p1 = ptProj(e2)) and lnProj the infinite line
// through them:
//   ds(p)       signed perpendicular distance from the centre of p to lnProj, > 0 on the left of
//               the direction e1 -> e2 (counter-clockwise side, y up)
//   LSEs        = | sum_p ds(p) / N |                                                   (eq. 3)
//   s(p)        = position of the projection of p on lnProj, measured from ptProj(e1) towards
//               ptProj(e2); the rendered pixels are ordered by s (ties by (y, x)); first, last
//   extentError = |s(first) - 0| + |s(last) - L|, L = |ptProj(e2) - ptProj(e1)|          (eq. 4)
//   LSEu        = (sum_p |ds(p)| + extentError) / (N + 2)                                (eq. 5)
//   norm        = value / sqrt(W H)                                                    (eqs. 6-7)
// Short projections (L < 1 px) need nothing special: the line through e1, e2 is well defined.
// Decision for L == 0 (a segment seen exactly end-on, or touching the clip volume at one point):
// there is no line, so the segment is treated as the point ptProj(e1): each offset is the
// distance |c(p) - ptProj(e1)|, LSEs is the length of the mean offset vector (the bias), the
// extent error is 0 (a point has no extent; its offsets already measure how far the pixels
// reach) and LSEu = sum |offset| / (N + 2). `degenerate` is set.
// With no rendered pixel (N = 0) the metrics are undefined: NaN (the paper computes them only for
// true-visible cases).
#pragma once

#include <cstdint>
#include <vector>

#include "geometry/clipping.h"
#include "geometry/pixel_set.h"

namespace ra::metrics {

struct LineMetrics {
  bool valid = false;           // false for an invalid (NaN/inf) or invisible segment
  bool degenerate = false;      // projected visible length is 0: point distances (see above)
  double projected_length = 0;  // L, px
  int64_t count = 0;            // N, rendered pixels
  double mean_signed_offset =
      0;                      // sum ds / N, px (> 0: biased left of e1 -> e2); NaN if degenerate
  double lse_signed = 0;      // LSEs, eq. 3, px
  double sum_abs_offset = 0;  // sum |ds|, px
  // Signed extent errors, px: > 0 overshoot (pixels reach beyond the end), < 0 undershoot.
  double start_extent = 0;       // -s(first)
  double end_extent = 0;         // s(last) - L
  double extent_error = 0;       // eq. 4: |start_extent| + |end_extent|, px
  double lse_unsigned = 0;       // LSEu, eq. 5, px
  double lse_signed_norm = 0;    // eq. 7, normalised window units
  double lse_unsigned_norm = 0;  // eq. 6
  geometry::Pixel first, last;   // the ends of the ordering along the line
  // Shape of the lit set (pixel_topology.h): components are 8-connected; gaps = components - 1
  // (the number of breaks in the drawn line, whatever their direction); chain: the set is one
  // simple 8-connected path.
  int64_t components = 0;
  int64_t gaps = 0;
  bool chain = false;
};

// Signed distance from point q to the infinite line through a and b (window coordinates), px:
// > 0 when q is left of a -> b. Precondition: a != b (returns NaN otherwise).
// Used by tests as an independent check of the line metrics (distances from first principles).
double signed_distance_to_line(geometry::Vec2 q, geometry::Vec2 a, geometry::Vec2 b);

// The rendered pixels ordered along the line from e1 to e2 (by the projection of their centres;
// ties by (y, x)); for e1 == e2, by distance from e1.
// Used by tests as an independent check of the line metrics (the order they walk a line in).
std::vector<geometry::Pixel> order_along_line(const geometry::PixelSet& lit, geometry::Vec2 e1,
                                              geometry::Vec2 e2);

// The line metrics of `lit` (pixels rendered for the segment, sorted, GL window coordinates)
// against the visible segment `seg` in a width x height window. Requires ideally_visible(seg);
// otherwise valid = false and the metrics are NaN.
LineMetrics measure_line(const geometry::ClippedSegment& seg, const geometry::PixelSet& lit,
                         int width, int height);
// The same for segment `prim` (Kind::kLine, e1 = v[0], e2 = v[1]) under `view`.
LineMetrics measure_line(const geometry::View& view, const geometry::Primitive& prim,
                         const geometry::PixelSet& lit);

}  // namespace ra::metrics
