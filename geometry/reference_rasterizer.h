// The project's own exact rasterizer: what an implementation following the OpenGL rules, with
// exact arithmetic, lights for one primitive. Input: the same double-precision projection the
// metrics use (clipping.h). Output: GL window pixels (pixel (i, j) covers [i, i+1) x [j, j+1),
// centre (i + 0.5, j + 0.5), y up), sorted by (y, x), inside the width x height window.
//
// Rules (OpenGL 2.1 spec sections 3.4-3.6 = OpenGL 4.6 sections 14.4-14.6):
// - Points, size 1: a point strictly inside the clip volume lights the pixel containing its window
//   position, (floor(x), floor(y)). Outside the clip volume: nothing.
// - Lines, width 1, no antialiasing, the "diamond-exit" rule on the clipped segment pa -> pb: the
//   fragment with centre f is produced when the segment meets the open diamond
//   R_f = { |x - f.x| + |y - f.y| < 1/2 }, except when pb lies in R_f. Boundary cases are settled
//   exactly as the spec says: both ends are perturbed to p - (e, e^2) for an infinitesimal e > 0
//   (so a segment through a diamond corner or an end on a diamond side is decided consistently).
//   Consequences: a segment starting on a pixel centre lights that pixel, one ending on a centre
//   does not; a zero-length segment lights nothing; an x-major segment lights one pixel per column.
// - Polygons (both faces), no antialiasing: a pixel is lit when its centre is inside the clipped
//   polygon. A centre exactly on an edge is inside when the edge is a "left" or a "top" edge, in GL
//   window coordinates with y up and the polygon taken counter-clockwise (interior on the left of
//   each directed edge): left edge = going down (dy < 0); top edge = horizontal going left
//   (dy == 0, dx < 0). This is the lecture's top-left rule (stated by D3D for y down) with "top"
//   and "left" as seen in the GL window (y up). GL itself only requires that a centre on an edge
//   shared by two polygons is lit exactly once, which this rule guarantees; a driver using the
//   mirrored convention differs only on centres exactly on edges (measure zero for random
//   primitives). The convex polygon is rasterized directly (all its edges at once), so there are
//   no fan diagonals to double-light or drop.
//
// Arithmetic: every decision is an exact sign (exact_predicates.h) on the double window
// coordinates, so ties (centres on edges, segments through diamond corners) are real ties, never
// rounding noise. Subpixel precision: an exact `grid` (bits 0) uses the double coordinates as they
// are (the ideal of the paper: no precision is lost before sampling). A grid of b > 0 bits first
// snaps window coordinates to 2^-b px (to nearest, ties to even, or truncating), as hardware with
// GL_SUBPIXEL_BITS = b does, so the reference can match a real implementation's sampling.
// Note: snapping applies to the clipped vertices (for a polygon, the hull is retaken after the
// snap); hardware with guard bands snaps the unclipped vertices instead, which can differ by less
// than 2^-b px along edges cut by the window sides.
#pragma once

#include <string>
#include <vector>

#include "geometry/clipping.h"
#include "geometry/pixel_set.h"
#include "geometry/primitive.h"
#include "geometry/vector_math.h"
#include "geometry/view.h"

namespace ra::geometry {

// How window coordinates are snapped before sampling: to the grid of 2^-bits px (bits <= 0: not
// at all, the exact reference), rounding to the nearest grid point (ties to even) or truncating
// (down, as dropping the fraction bits of a two's-complement fixed-point number does).
enum class SnapRounding { kNearest, kTruncate };
struct SubpixelGrid {
  int bits = 0;
  SnapRounding rounding = SnapRounding::kNearest;
  SubpixelGrid(int b = 0, SnapRounding r = SnapRounding::kNearest) : bits(b), rounding(r) {}
  bool exact() const { return bits <= 0; }
  bool operator==(const SubpixelGrid& o) const {
    return exact() ? o.exact() : bits == o.bits && rounding == o.rounding;
  }
};
// "exact", "8 bits, nearest", "4 bits, truncation".
std::string subpixel_grid_text(SubpixelGrid grid);
const char* snap_rounding_name(SnapRounding r);  // "nearest", "truncation"

// Window coordinate (px) snapped to `grid`; unchanged for an exact grid.
double snap_to_subpixel(double v, SubpixelGrid grid);

// The pixel a point lights: empty unless c (clip coordinates) is strictly inside the clip volume.
PixelSet rasterize_point(Vec4 c, int width, int height, SubpixelGrid grid = {});

// The diamond-exit rule for one fragment: true when the segment a -> b (window coordinates, px)
// produces the fragment of pixel f. Exact, with the spec's perturbation.
bool diamond_exit_fragment(Vec2 a, Vec2 b, Pixel f);

// The pixels of the segment a -> b (window coordinates, px; normally ClippedSegment::p0 -> p1),
// by the diamond-exit rule; O(length). Non-finite ends: empty.
PixelSet rasterize_segment(Vec2 a, Vec2 b, int width, int height, SubpixelGrid grid = {});
// The clipped segment's pixels; empty unless it is visible.
PixelSet rasterize_segment(const ClippedSegment& s, int width, int height, SubpixelGrid grid = {});

// Vulkan's strict lines (Vulkan 1.3, "Basic Line Segment Rasterization", strictLines true): the
// segment a -> b (window coordinates, px; snapped to `grid` first) covers the rectangle of width 1
// centred on it, from a to b; a pixel is lit when its centre lies inside that rectangle, decided
// as for a polygon (rasterize_convex_polygon, its tie rule). Zero length: empty.
PixelSet rasterize_rectangle_segment(Vec2 a, Vec2 b, int width, int height,
                                     SubpixelGrid grid = {});
// The rectangle's corners, counter-clockwise (a - n, b - n, b + n, a + n with n half the unit
// normal); empty for a zero-length or non-finite segment.
std::vector<Vec2> segment_rectangle(Vec2 a, Vec2 b);

// Whether the sample point q (window coordinates) is covered by the convex counter-clockwise
// polygon under the top-left rule above. Exact.
// Used by tests as an independent check of the rasterizer, one sample at a time.
bool polygon_covers_sample(const std::vector<Vec2>& ccw_polygon, Vec2 q);

// The pixels whose centres the convex counter-clockwise polygon covers (window coordinates, px;
// normally ClippedPolygon::vertices); O(rows x vertices): a row's ends are decided in double with a
// certified error bound, by the exact test only near a tie. Zero area: empty.
PixelSet rasterize_convex_polygon(const std::vector<Vec2>& ccw_polygon, int width, int height,
                                  SubpixelGrid grid = {});
// The clipped triangle's pixels; empty unless it is visible.
PixelSet rasterize_polygon(const ClippedPolygon& p, int width, int height, SubpixelGrid grid = {});

// The pixels the reference lights for `prim` under `view` (clip, project, rasterize as above).
PixelSet rasterize_reference(const View& view, const Primitive& prim, SubpixelGrid grid = {});

}  // namespace ra::geometry
