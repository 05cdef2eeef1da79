// The point audit of the NIST paper (section 3.4): ideal projection, visibility and the point
// rendering error PE. Coordinates: GL window coordinates in pixels (pixel centres at +0.5).
#pragma once

#include "geometry/pixel_set.h"
#include "metrics/records.h"
#include "geometry/view.h"

namespace ra::metrics {

struct IdealPoint {
  bool visible = false;  // strictly inside the clip volume (GL discards points outside it)
  geometry::Vec2 window;  // projected position, pixels (meaningful when visible)
};

IdealPoint project_point(const geometry::View& view, geometry::Vec3 p);

// Where a rendered point may be: the pixel containing the ideal position plus `margin` pixels on
// each side; empty when the point is not visible.
geometry::PixelRect point_region(const geometry::View& view, const IdealPoint& ideal,
                                 int margin = 2);

// The paper's apparent convention for "lies in the field of view" (its Table 2): the point is in
// front of the camera between the near and far planes and its projection lies in the window grown
// by `margin_px` pixels on each side, (-m, W + m) x (-m, H + m) in GL window coordinates. With
// margin 0 this is project_point's `visible`. The paper's false-invisible counts (72, 154, 11, 29
// per view group, about 1/W of its visible points, none false-visible) fit a margin of half a pixel
// on each side (docs/method.md, "Where we differ from the paper"); GL itself never draws such a point.
bool inside_window_margin(const geometry::View& view, geometry::Vec3 p, double margin_px);

// Visibility class of a point (true-visible needs exactly one lit pixel).
Visibility classify_point(bool ideal_visible, size_t lit_pixels);

// PE (eq. 1): distance from the projected point to the centre of the rendered pixel, pixels.
double point_error(geometry::Vec2 projected, geometry::Pixel rendered);

// Fills visibility, pixels, pe and pe_norm (eq. 2: PE / sqrt(W*H)) of `rec`.
void measure_point(const geometry::View& view, const IdealPoint& ideal,
                   const geometry::PixelSet& lit, Record& rec);

}  // namespace ra::metrics
