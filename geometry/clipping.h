// The visible part of a line segment or triangle: clipping against the six planes of the clip
// volume -w <= x, y, z <= w in homogeneous clip coordinates, before the perspective divide, then
// the map to GL window coordinates (pixels; pixel (i, j) covers [i, i+1) x [j, j+1); y up).
// This is proj(.) of the NIST paper (sections 3.5 and 3.6: "the projection ... clipped to the
// viewing area"); the clip volume is closed here (a primitive touching a plane is visible).
//
// Why homogeneous: clip coordinates are a linear function of the world point (w = 1), so the
// world segment maps to the straight clip-space segment between its endpoints' clip coordinates,
// including vertices behind the camera (w < 0), where a divide first would wrap through infinity.
// The parameter t of a clipped endpoint is therefore also its parameter on the world segment.
//
// Robustness: an intersection is always computed from the inside vertex towards the outside one
// (so an edge shared by two primitives gives bit-identical points), the coordinate of the cutting
// plane is set exactly (x = w on the right plane, so x_window == W exactly; likewise for earlier
// planes holding both ends of the cut edge, so window corners are exact), and window coordinates
// are clamped to the window rectangle: every clipped point is mathematically inside the closed clip
// volume, so the clamp only removes rounding. Non-finite input gives status kInvalid.
#pragma once

#include <vector>

#include "geometry/pixel_set.h"
#include "geometry/primitive.h"
#include "geometry/vector_math.h"
#include "geometry/view.h"

namespace ra::geometry {

enum class ClipStatus {
  kVisible,     // meets the clip volume with a positive window length (segment) or area (polygon)
  kDegenerate,  // meets the clip volume, but its visible part has zero window length or area
  kInvisible,   // does not meet the closed clip volume
  kInvalid,     // a coordinate is NaN or infinite (or the projection is undefined): no geometry
};
// Used by tests to name a status in their messages.
const char* clip_status_name(ClipStatus s);  // "visible", "degenerate", "invisible", "invalid"

// The six clip planes, in the order used for plane indices below.
enum ClipPlane { kPlaneLeft, kPlaneRight, kPlaneBottom, kPlaneTop, kPlaneNear, kPlaneFar };

// Signed distance-like value of clip-space point c to plane `plane` (clip units): w + x for left,
// w - x for right, w + y, w - y, w + z (near), w - z (far). >= 0 is inside.
double plane_distance(Vec4 c, int plane);

struct ClippedSegment {
  ClipStatus status = ClipStatus::kInvisible;
  // Parameters of the visible part on the input segment c0 + t (c1 - c0), 0 <= t0 <= t1 <= 1
  // (equally on the world segment e1 + t (e2 - e1)). Meaningful when visible or degenerate.
  double t0 = 0, t1 = 0;
  Vec4 clip0, clip1;  // clip coordinates of the visible part's ends
  Vec2 p0, p1;        // GL window coordinates (pixels) of those ends: ptProj(e1), ptProj(e2)
  int plane0 = -1, plane1 = -1;  // ClipPlane that cut each end; -1 when it is the input vertex

  // Used by tests as an independent check of the clipped length.
  double window_length() const { return length(p1 - p0); }  // pixels
};

// Clips the segment c0 -> c1 (clip coordinates) to the closed clip volume (parametric,
// Liang-Barsky in homogeneous form) and maps the visible part to a width x height window.
// Degenerate: the visible part projects to one window point (touches the volume at one point, or
// lies along a line of sight). The direction c0 -> c1 is kept (p0 comes from the c0 side).
ClippedSegment clip_segment(Vec4 c0, Vec4 c1, int width, int height);
// Same for the world segment e1 -> e2 under `view`.
ClippedSegment clip_segment(const View& view, Vec3 e1, Vec3 e2);

struct ClippedPolygon {
  ClipStatus status = ClipStatus::kInvisible;
  // The visible part in GL window coordinates (pixels): the convex hull of the clipped vertices,
  // counter-clockwise (y up), with no repeated or collinear vertices. Visible: >= 3 vertices.
  // Degenerate: 1 or 2 vertices (a point or a segment: zero area). Otherwise empty.
  std::vector<Vec2> vertices;
  double area = 0;  // of the polygon, px^2 (> 0 exactly when visible)
  // Facing of the projected triangle: +1 counter-clockwise in window coordinates (front face under
  // GL's default glFrontFace(GL_CCW)), -1 clockwise, 0 when the visible part has zero area.
  int orientation = 0;
  // For each polygon edge i (vertices[i] -> vertices[i+1 mod n]): true when it lies on the window
  // border (x == 0, x == W, y == 0 or y == H along its whole length). Such edges are created by
  // clipping to the side planes (or lie there by chance) and cannot be drawn wrongly.
  std::vector<bool> on_window_border;
};

// Clips the triangle a, b, c (clip coordinates) to the closed clip volume (Sutherland-Hodgman in
// homogeneous coordinates) and maps it to a width x height window.
//
// Decision: a triangle whose visible part has zero window area (edge-on to the eye, collinear or
// repeated vertices, or touching the volume only along a face, an edge or a point) is kDegenerate
// and is *not* ideally visible: it has no interior, GL rasterizes no fragment for a zero-area
// polygon, and its TE metrics would only count rendered pixels as error.
ClippedPolygon clip_triangle(Vec4 a, Vec4 b, Vec4 c, int width, int height);
ClippedPolygon clip_triangle(const View& view, Vec3 a, Vec3 b, Vec3 c);

// "Ideally visible" (the paper's "lies in the field of view"): a segment meets the closed clip
// volume (visible or degenerate, so a segment seen end-on still counts); a triangle's visible part
// has positive window area (visible only).
inline bool ideally_visible(const ClippedSegment& s) {
  return s.status == ClipStatus::kVisible || s.status == ClipStatus::kDegenerate;
}
inline bool ideally_visible(const ClippedPolygon& p) { return p.status == ClipStatus::kVisible; }

// Window pixels that the clipped primitive touches (its window bounding box, closed, so an end
// exactly on x = k includes pixel column k), grown by `margin` pixels on each side and clamped to
// the width x height window. Empty for invisible or invalid primitives. A rasterizer following the
// GL rules lights pixels only inside the margin-0 rectangle; a margin covers renderer error.
PixelRect bounding_rect(const ClippedSegment& s, int width, int height, int margin = 0);
PixelRect bounding_rect(const ClippedPolygon& p, int width, int height, int margin = 0);

// Signed area of a simple polygon by the shoelace formula, px^2 (or the square of its units):
// positive when counter-clockwise (y up). Computed relative to the first vertex so that large
// window coordinates do not cost precision.
double polygon_signed_area(const std::vector<Vec2>& poly);

// Convex hull of points (any order, duplicates allowed), counter-clockwise (y up), without
// repeated or collinear vertices, starting from the point with the smallest x (then y); exact
// orientation tests. 0, 1 or 2 points when the input is empty, one point, or collinear.
std::vector<Vec2> convex_hull(std::vector<Vec2> points);

}  // namespace ra::geometry
