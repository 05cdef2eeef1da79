// Conformance verdicts: whether one primitive's lit pixels are what the OpenGL spec allows an
// implementation to produce, not only whether they equal the exact reference rasterizer's.
// Coordinates: GL window coordinates in pixels (pixel (i, j) covers [i, i+1) x [j, j+1), centre
// (i + 0.5, j + 0.5), y up), as in geometry/reference_rasterizer.h.
//
// What GL leaves to the implementation (OpenGL 4.6 core; the same text is in 2.1):
// - Subpixel precision: window coordinates may be snapped to a grid of GL_SUBPIXEL_BITS bits, and
//   the least value an implementation may report is 4 (chapter 23, implementation-dependent
//   values). A vertex may therefore move by up to 2^-4 px in x and in y: kSnapAllowancePx.
// - Floating point: results are accurate to "about 1 part in 10^5" (section 2.3.4.1). How far
//   that moves a vertex's window position is derived stage by stage in metrics/window_error.h:
//   each vertex of the primitive clipped to the near plane has its own allowance (snap plus
//   float error), and a point of an edge may move by the allowances of its two ends interpolated
//   along it (a vertex the near clip put far outside the window moves the far end of its edges,
//   not the end inside the window).
// Per kind, what may differ from the exact reference (the "allowance" below is the sum of both):
// - Polygons (14.6.1): a pixel whose centre lies within the allowance of an edge: of the polygon
//   clipped to the near plane (its vertices with their allowances, x sqrt 2 for a move in x and
//   y), or of an edge the far plane cut (the uniform allowance). The window's sides never remove
//   a pixel inside the window. Broken: "polygon-edge"; a polygon drawn as nothing with a pixel
//   no edge can remove: "polygon-missing".
// - Lines (14.5.1), other algorithms than diamond-exit are allowed when (1) every fragment lies
//   within one unit in x and in y of a diamond-exit fragment ("line-deviation"), (2) the fragment
//   count differs from diamond-exit's by at most one ("line-count"), (3) an x-major segment has no
//   two fragments in one column, a y-major one none in one row ("line-column"). Rule 4 (shared
//   ends of connected segments) does not apply to a lone segment. Diamond-exit is taken on the
//   exact ends, on the ends snapped to the platform's effective grid and on the ends snapped to
//   GL's coarsest grid (4 bits, either rounding); the best one counts.
//   Rule 2 counts every fragment, also those the window discards: where a window side cut an end
//   it is judged on the fragments inside the window instead ("line-window-count"; "line-missing"
//   when nothing is drawn). Diamond-exit lights one fragment per column of an x-major segment;
//   a column is certain to hold a fragment inside the window when, for every placement of the
//   ends within their allowances, the segment crosses it by more than half a pixel beyond each end
//   and its line lies at least three rows inside the window (rule 1 lets a fragment lie one unit
//   from the diamond-exit fragment of a neighbouring column, whose row may differ by one more,
//   and a tie may put a fragment one row lower). An implementation may drop one
//   fragment (rule 2) and shift its fragments by one column (rule 1), so at least certain - 3
//   fragments must lie inside the window (likewise rows for a y-major segment; where the
//   allowance could swap the axes, the smaller count). Rule 3 takes either axis as the major one
//   where the allowance could swap them: for the ends before the window cut them, or for the cut
//   ends snapped after the cut.
// - Points (14.4), size 1: exactly one fragment, the pixel containing the (snapped) position: any
//   pixel within the allowance of the position, in x and in y ("point-pixel", more than one:
//   "point-count"); none at all only when the position lies within the allowance of a window side
//   or its depth within its float error of the near or far plane ("point-missing").
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "geometry/clipping.h"
#include "geometry/pixel_set.h"
#include "geometry/reference_rasterizer.h"
#include "geometry/view.h"
#include "metrics/records.h"
#include "metrics/window_error.h"

namespace ra::metrics {

// The version of the rules above, in the run manifest ("conformance_rules"; a manifest without it
// was judged by version 1): an audit compares two runs' classes only when both were judged by the
// same rules. Version 2 judges a window-cut segment's count inside the window, names missing
// primitives, and gives each vertex its own float allowance (window_error.h).
constexpr int kConformanceRulesVersion = 2;

struct ConformanceVerdict {
  Conformance conformance = Conformance::kNotCompared;
  int64_t violating_pixels = -1;  // 0 unless kViolation
  std::string violated_rules;     // '+'-joined rule names (above); empty unless kViolation
};

// The verdict for a rendered point, segment or triangle. `exact` is the exact reference's pixels
// (rasterize_* with an exact grid), `lit` the platform's; `effective` the grid the platform
// effectively snaps to (runner/effective_subpixel.h; exact when it does not snap);
// `near_clipped` near_clipped_vertices() of the primitive (the segment's two ends, the polygon's
// vertices). `violating`, when given, receives the pixels that break a rule (lit or left dark; a
// count rule names the reference's pixels it misses).
ConformanceVerdict judge_point(const ClipWithError& clip, int width, int height,
                               const geometry::PixelSet& lit, const geometry::PixelSet& exact,
                               geometry::SubpixelGrid effective,
                               geometry::PixelSet* violating = nullptr);
ConformanceVerdict judge_segment(const geometry::ClippedSegment& segment,
                                 const std::vector<AllowedVertex>& near_clipped, int width,
                                 int height, const geometry::PixelSet& lit,
                                 const geometry::PixelSet& exact, geometry::SubpixelGrid effective,
                                 geometry::PixelSet* violating = nullptr);
ConformanceVerdict judge_polygon(const geometry::ClippedPolygon& polygon,
                                 const std::vector<AllowedVertex>& near_clipped, int width,
                                 int height, const geometry::PixelSet& lit,
                                 const geometry::PixelSet& exact, geometry::SubpixelGrid effective,
                                 geometry::PixelSet* violating = nullptr);

// Vulkan's strict lines (the default line mode where the device reports strictLines; Vulkan 1.3,
// "Basic Line Segment Rasterization"): the segment covers a rectangle of width 1 from end to end,
// and a pixel is lit when its centre lies inside (geometry/reference_rasterizer.h
// rasterize_rectangle_segment). `exact` is that rectangle's pixels for the segment's ends as the
// near and far planes leave them (a window side does not cut the rectangle: its far end stays
// where the vertex is). As for polygons, a pixel may differ from `exact` when its centre lies
// within the allowance of a side of the rectangle, each corner taking the allowance of its end
// plus the turn the two ends' allowances can give the segment (half of their sum over its length);
// where a window side cut an end, the rectangle of the cut end is allowed too. Broken:
// "line-rectangle"; nothing drawn where a pixel had to be: "line-missing".
ConformanceVerdict judge_rectangle_segment(const geometry::ClippedSegment& segment,
                                           const std::vector<AllowedVertex>& near_clipped,
                                           int width, int height, const geometry::PixelSet& lit,
                                           const geometry::PixelSet& exact,
                                           geometry::SubpixelGrid effective,
                                           geometry::PixelSet* violating = nullptr);
// The ends judge_rectangle_segment draws the rectangle between: the segment's ends, but where a
// window side cut an end, the near-clipped vertex of that end (window coordinates, px).
std::pair<geometry::Vec2, geometry::Vec2> rectangle_ends(
    const geometry::ClippedSegment& segment, const std::vector<AllowedVertex>& near_clipped);

// Hand-made cases with no view: a point exactly at `clip` (no transform error), a segment or
// polygon whose clipped vertices all have the uniform allowance conformance_allowance(magnitude).
ConformanceVerdict judge_point(geometry::Vec4 clip, int width, int height,
                               const geometry::PixelSet& lit, const geometry::PixelSet& exact,
                               geometry::SubpixelGrid effective,
                               geometry::PixelSet* violating = nullptr);
ConformanceVerdict judge_segment(const geometry::ClippedSegment& segment, double magnitude,
                                 int width, int height, const geometry::PixelSet& lit,
                                 const geometry::PixelSet& exact, geometry::SubpixelGrid effective,
                                 geometry::PixelSet* violating = nullptr);
ConformanceVerdict judge_polygon(const geometry::ClippedPolygon& polygon, double magnitude,
                                 int width, int height, const geometry::PixelSet& lit,
                                 const geometry::PixelSet& exact, geometry::SubpixelGrid effective,
                                 geometry::PixelSet* violating = nullptr);

// The same for primitive `prim` under `view`, clipping it and rasterizing its exact reference here
// (for one primitive at a time, as `renderaudit show` needs; the runner reuses its own).
// `rectangle_lines`: segments by Vulkan's strict-line rule (judge_rectangle_segment).
ConformanceVerdict judge_primitive(const geometry::View& view, const geometry::Primitive& prim,
                                   const geometry::PixelSet& lit, geometry::SubpixelGrid effective,
                                   geometry::PixelSet* violating = nullptr,
                                   bool rectangle_lines = false);

}  // namespace ra::metrics
