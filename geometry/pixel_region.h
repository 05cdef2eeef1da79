// Where a primitive may have lit pixels: a union of disjoint rectangles of window pixels (GL window
// coordinates, pixel (x, y) covers [x, x+1) x [y, y+1)). A point uses one rectangle, its bounding
// box; a line a strip of rectangles along its major axis, so that a long diagonal line reads back
// about length x 40 pixels instead of its length squared; a triangle horizontal bands that follow
// its sides, so that a large one reads back little more than its area, not its bounding box
// (at least twice its area).
#pragma once

#include <cstdint>
#include <vector>

#include "geometry/clipping.h"
#include "geometry/pixel_set.h"

namespace ra::geometry {

struct PixelRegion {
  std::vector<PixelRect> rects;  // pairwise disjoint, none empty

  PixelRegion() = default;
  PixelRegion(const PixelRect& r) {  // implicit: a rectangle is a region
    if (!r.empty()) rects.push_back(r);
  }
  bool empty() const { return rects.empty(); }
  int64_t area() const;     // pixels
  PixelRect bounds() const; // the smallest rectangle holding every rect; empty when empty()
  bool overlaps(const PixelRegion& other) const;
  bool contains(Pixel p) const;
};

// Rectangles along the major axis of a clipped segment's window projection, each `chunk` pixels long
// or shorter, each covering the segment's minor-axis range over its columns (rows) plus `margin`
// pixels on every side, clamped to the window. Their union holds every pixel within `margin`
// pixels (in rows and in columns) of a pixel the segment passes through, as the bounding box with
// the same margin does; empty when the segment is not ideally visible.
// `chunk` 0 chooses a length from the slope so that each rectangle stays about 32 pixels tall
// (wide), balancing the fixed cost of one readback against the pixels it reads.
PixelRegion strip_region(const ClippedSegment& s, int width, int height, int margin, int chunk = 0);

// Horizontal bands of `band_rows` rows (the last one shorter) over a clipped polygon's window
// projection: band rows [y0, y1) span the columns of the polygon's x-range over y in
// [y0 - margin, y1 + margin], plus `margin` columns on each side, clamped to the window, as
// bounding_rect does for the whole polygon. Their union holds every pixel within `margin` rows and
// columns of the polygon, and is the bounding rectangle when one band covers it; a band is one
// readback, so rows of a band share one call. Empty when the polygon is neither visible nor
// degenerate. band_rows >= 1.
PixelRegion band_region(const ClippedPolygon& p, int width, int height, int margin, int band_rows);

}  // namespace ra::geometry
