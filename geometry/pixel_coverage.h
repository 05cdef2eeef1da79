// Exact area of each unit pixel square inside a convex polygon: inside(S, p) of the NIST paper,
// section 3.6 (outside(S, p) = 1 - inside(S, p), eq. 8). Coordinates: GL window coordinates in
// pixels, pixel (i, j) covering [i, i+1) x [j, j+1); areas in px^2.
//
// Method (row by row, O(rows + perimeter), not O(area)): in the strip [j, j+1] the polygon lies
// between its left chain and its right chain. The area of a pixel is the integral over the strip
// of the signed horizontal overlap of [i, i+1] with the region right of each chain piece (winding
// +1 right of the left chain, -1 right of the right chain). Each chain piece is split at integer x;
// a sub-piece inside column c adds dy * (c + 1 - mean x) to column c and "carries" dy to every
// column right of it, so only columns that a chain passes through are visited one by one. Columns
// between the chains form a run of identical pixels, each covered by the polygon's height in the
// strip (1, except in a row holding a horizontal top or bottom edge).
// Accuracy: each pixel's area is a sum of O(1) terms bounded by 1, computed relative to integer
// pixel boundaries; the error comes from rounding the edge crossings to doubles, about
// 2e-16 * |coordinate| px^2: ~1e-14 px^2 in a 128-pixel window, < 1e-11 px^2 at 16384 px (the
// tests check 1e-12 and 1e-10 against exact rational arithmetic).
#pragma once

#include <cstdint>
#include <vector>

#include "geometry/pixel_set.h"
#include "geometry/vector_math.h"

namespace ra::geometry {

struct PixelArea {
  int32_t x = 0;    // pixel column
  double area = 0;  // px^2 of the pixel inside the polygon, in (0, 1]
};

// One pixel row of a polygon's coverage: left partial pixels, then a run of pixels that all have
// the same area, then right partial pixels (the run may be empty).
struct CoverageRow {
  int32_t y = 0;                                // pixel row
  uint32_t partial_begin = 0, partial_end = 0;  // its pixels in PolygonCoverage::partial, by x
  int32_t run_begin = 0, run_end = 0;           // columns [run_begin, run_end), none partial
  double run_area = 0;                          // px^2 of each run pixel, in (0, 1]
};

// The pixels a polygon covers with positive area; pixels not listed have area 0.
struct PolygonCoverage {
  std::vector<CoverageRow> rows;   // increasing y; only rows with covered pixels
  std::vector<PixelArea> partial;  // grouped by row, increasing x within a row

  // Area of pixel (x, y) inside the polygon, px^2; O(log rows + log row partials).
  double area(int32_t x, int32_t y) const;
  // Sum of all pixel areas, px^2 (equals the polygon area up to rounding).
  // Used by tests as an independent check of the coverage against the polygon area.
  double total_area() const;
  // Number of pixels with positive area.
  // Used by tests as a check of which pixels the coverage holds.
  int64_t pixel_count() const;
};

// Fills `out` (reusing its storage) with the coverage of `polygon`: GL window coordinates (px),
// convex and counter-clockwise (y up), as ClippedPolygon::vertices; collinear or repeated vertices
// are allowed. Returns false, leaving `out` empty, when the polygon is not usable: a non-finite
// coordinate, |coordinate| > 2^30 px, or not convex counter-clockwise (exact test). Fewer than 3
// vertices or zero area: returns true with an empty coverage.
bool compute_coverage(const std::vector<Vec2>& polygon, PolygonCoverage* out);

// Area of one pixel inside a convex polygon (window coordinates), px^2, by clipping the polygon to
// the pixel square: O(vertices) per pixel. For spot checks; compute_coverage is the fast path.
// Used by tests as an independent check of compute_coverage (one pixel clipped on its own).
double pixel_area_in_convex_polygon(const std::vector<Vec2>& polygon, Pixel p);

}  // namespace ra::geometry
