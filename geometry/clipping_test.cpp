// Clipping to the clip volume and the map to window coordinates: hard cases with closed-form
// expectations.
#include "geometry/clipping.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace ra::geometry {
namespace {


// Window position of an eye-space point under make_view's projection, from the closed form of
// gluPerspective (independent of the matrix code): x_ndc = (f / aspect) x / -z.
Vec2 closed_form_window(const View& v, Vec3 p) {
  const double f = 1.0 / std::tan(v.fov_deg * M_PI / 360.0);
  const double aspect = double(v.width) / v.height;
  return {((f / aspect) * p.x / -p.z + 1) * 0.5 * v.width, (f * p.y / -p.z + 1) * 0.5 * v.height};
}

// Both ends inside: nothing is cut, the ends are the plain projections.
TEST(ClipSegment, InsideIsUnchanged) {
  const View v = make_view(30, 128, 128);
  const Vec3 e1{0.01, 0.02, -0.5}, e2{-0.03, 0.01, -0.9};
  const ClippedSegment s = clip_segment(v, e1, e2);
  ASSERT_EQ(s.status, ClipStatus::kVisible);
  EXPECT_EQ(s.t0, 0.0);
  EXPECT_EQ(s.t1, 1.0);
  EXPECT_EQ(s.plane0, -1);
  EXPECT_EQ(s.plane1, -1);
  const Vec2 w1 = closed_form_window(v, e1), w2 = closed_form_window(v, e2);
  EXPECT_NEAR(s.p0.x, w1.x, 1e-9);
  EXPECT_NEAR(s.p0.y, w1.y, 1e-9);
  EXPECT_NEAR(s.p1.x, w2.x, 1e-9);
  EXPECT_NEAR(s.p1.y, w2.y, 1e-9);
}

// One end behind the camera (w < 0): the visible part ends on the near plane at the world
// parameter where z = -near; dividing first would have wrapped the far end through infinity.
TEST(ClipSegment, CrossingTheNearPlane) {
  const View v = make_view(30, 128, 128);
  const Vec3 e1{0, 0, -0.5}, e2{0.001, 0, 0.5};
  const ClippedSegment s = clip_segment(v, e1, e2);
  ASSERT_EQ(s.status, ClipStatus::kVisible);
  const double t = (0.5 - v.near) / 1.0;  // z(t) = -0.5 + t = -near
  EXPECT_NEAR(s.t1, t, 1e-12);
  EXPECT_EQ(s.plane1, kPlaneNear);
  const Vec2 expect = closed_form_window(v, {0.001 * t, 0, -v.near});
  EXPECT_NEAR(s.p1.x, expect.x, 1e-9);
  EXPECT_NEAR(s.p1.y, expect.y, 1e-9);
}

// Behind the camera and far to the side: the visible part ends on the right side of the window
// (x == W exactly), not at the near plane, and never wraps to the left side.
TEST(ClipSegment, BehindCameraEndsOnTheSide) {
  const View v = make_view(30, 128, 128);
  const Vec3 e1{0.1, 0, -0.5}, e2{0.1, 0, 0.5};
  const ClippedSegment s = clip_segment(v, e1, e2);
  ASSERT_EQ(s.status, ClipStatus::kVisible);
  const double f = 1.0 / std::tan(15 * M_PI / 180);
  EXPECT_NEAR(s.t0, 0.0, 0.0);
  EXPECT_NEAR(s.t1, 0.5 - 0.1 * f, 1e-12);  // f x / -z = 1 with z = -0.5 + t
  EXPECT_EQ(s.plane1, kPlaneRight);
  EXPECT_EQ(s.p1.x, 128.0);  // exactly on the border
  EXPECT_NEAR(s.p1.y, 64.0, 1e-9);
}

// Both ends behind the camera: invisible, although dividing by w < 0 would put them on screen.
TEST(ClipSegment, BothBehindCameraIsInvisible) {
  const ClippedSegment s = clip_segment(Vec4{0, 0, 0.5, -1}, Vec4{0.1, 0.2, 0.5, -2}, 100, 100);
  EXPECT_EQ(s.status, ClipStatus::kInvisible);
  EXPECT_FALSE(ideally_visible(s));
  EXPECT_TRUE(bounding_rect(s, 100, 100, 3).empty());
}

// Both ends outside different planes, crossing the whole window: both ends land exactly on the
// left and right borders.
TEST(ClipSegment, BothOutsideCrossing) {
  const ClippedSegment s = clip_segment(Vec4{-3, 0.5, 0, 1}, Vec4{3, -0.5, 0, 1}, 200, 100);
  ASSERT_EQ(s.status, ClipStatus::kVisible);
  EXPECT_EQ(s.p0.x, 0.0);
  EXPECT_EQ(s.p1.x, 200.0);
  EXPECT_NEAR(s.p0.y, (0.5 / 3 + 1) * 50, 1e-12);
  EXPECT_NEAR(s.t0, 1.0 / 3, 1e-15);
  EXPECT_NEAR(s.t1, 2.0 / 3, 1e-15);
}

// Outside two different planes and missing the corner (x + y = 2.5 never meets the square).
TEST(ClipSegment, BothOutsideMissingTheCorner) {
  const ClippedSegment s = clip_segment(Vec4{0.5, 2, 0, 1}, Vec4{2, 0.5, 0, 1}, 100, 100);
  EXPECT_EQ(s.status, ClipStatus::kInvisible);
}

// Touching the volume at exactly one point (the corner x = y = w): degenerate but ideally visible
// (the intersection with the closed volume is not empty), window length 0.
TEST(ClipSegment, TouchingTheCorner) {
  const ClippedSegment s = clip_segment(Vec4{0, 2, 0, 1}, Vec4{2, 0, 0, 1}, 100, 100);
  EXPECT_EQ(s.status, ClipStatus::kDegenerate);
  EXPECT_TRUE(ideally_visible(s));
  EXPECT_EQ(s.p0.x, 100.0);
  EXPECT_EQ(s.p0.y, 100.0);
  EXPECT_EQ(s.window_length(), 0.0);
}

// Lying in the right plane x = w: visible (closed volume), on the border x = W.
TEST(ClipSegment, LyingOnAPlane) {
  const ClippedSegment s = clip_segment(Vec4{1, -0.5, 0, 1}, Vec4{1, 0.5, 0, 1}, 64, 64);
  ASSERT_EQ(s.status, ClipStatus::kVisible);
  EXPECT_EQ(s.p0.x, 64.0);
  EXPECT_EQ(s.p1.x, 64.0);
  EXPECT_EQ(bounding_rect(s, 64, 64).x1, 64);
}

// Along a line of sight: the whole segment projects to (nearly) one point; still ideally visible.
TEST(ClipSegment, AlongTheViewDirection) {
  const View v = make_view(150, 907, 907);
  const Vec3 dir{0.3, -0.2, -0.9};
  const ClippedSegment s = clip_segment(v, 0.1 * dir, 0.95 * dir);
  EXPECT_TRUE(ideally_visible(s));
  EXPECT_LT(s.window_length(), 1e-9);
  const Vec2 expect = closed_form_window(v, dir);
  EXPECT_NEAR(s.p0.x, expect.x, 1e-9);
  EXPECT_NEAR(s.p1.y, expect.y, 1e-9);
}

// NaN or infinite coordinates: a clear "invalid", never a number.
TEST(ClipSegment, NonFiniteIsInvalid) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(clip_segment(Vec4{nan, 0, 0, 1}, Vec4{0, 0, 0, 1}, 10, 10).status,
            ClipStatus::kInvalid);
  EXPECT_EQ(clip_segment(Vec4{0, 0, 0, 1}, Vec4{0, inf, 0, 1}, 10, 10).status,
            ClipStatus::kInvalid);
  const View v = make_view(30, 128, 128);
  EXPECT_EQ(clip_segment(v, {nan, 0, -1}, {0, 0, -1}).status, ClipStatus::kInvalid);
  EXPECT_EQ(clip_triangle(v, {0, 0, -1}, {inf, 0, -1}, {0, 1, -1}).status, ClipStatus::kInvalid);
  EXPECT_TRUE(
      bounding_rect(clip_triangle(v, {0, 0, -1}, {inf, 0, -1}, {0, 1, -1}), 128, 128, 2).empty());
}

// A degenerate matrix can put the homogeneous origin in the closed volume: no window position.
TEST(ClipSegment, HomogeneousOriginIsInvalid) {
  EXPECT_EQ(clip_segment(Vec4{0, 0, 0, 0}, Vec4{0, 0, 0, 1}, 10, 10).status, ClipStatus::kInvalid);
}

// Inside triangle: the polygon is the three projections, counter-clockwise; the facing of a
// clockwise triangle is reported, not lost.
TEST(ClipTriangle, InsideKeepsVerticesAndReportsFacing) {
  const Vec4 a{-0.5, -0.5, 0, 1}, b{0.5, -0.5, 0, 1}, c{0, 0.5, 0, 1};
  const ClippedPolygon ccw = clip_triangle(a, b, c, 100, 100);
  ASSERT_EQ(ccw.status, ClipStatus::kVisible);
  EXPECT_EQ(ccw.orientation, 1);
  ASSERT_EQ(ccw.vertices.size(), 3u);
  EXPECT_DOUBLE_EQ(ccw.area, 0.5 * 50 * 50);
  const ClippedPolygon cw = clip_triangle(a, c, b, 100, 100);
  EXPECT_EQ(cw.orientation, -1);
  EXPECT_GT(polygon_signed_area(cw.vertices), 0);  // still counter-clockwise
  EXPECT_DOUBLE_EQ(cw.area, ccw.area);
}

// Crossing the near plane with one vertex behind the camera: the visible part is the trapezoid
// between the two front vertices and the two near-plane intersections; closed-form area.
TEST(ClipTriangle, CrossingTheNearPlaneClosedForm) {
  const View v = make_view(90, 100, 100, 0.01, 10);
  const Vec3 a{-0.01, -0.01, -1}, b{0.01, -0.01, -1}, c{0, 0, 1};
  const ClippedPolygon p = clip_triangle(v, a, b, c);
  ASSERT_EQ(p.status, ClipStatus::kVisible);
  ASSERT_EQ(p.vertices.size(), 4u);
  // Near intersections at t = 0.495 on AC and BC: (-+0.00505, -0.00505, -0.01) -> ndc (-+0.505,
  // -0.505); A, B -> ndc (-+0.01, -0.01). Window = (ndc + 1) * 50.
  const double top = 49.5, bottom = 24.75;
  const double expect_area = 0.5 * ((50.5 - 49.5) + (75.25 - 24.75)) * (top - bottom);
  EXPECT_NEAR(p.area, expect_area, 1e-9);
  double ymin = 1e9;
  for (const Vec2& q : p.vertices) ymin = std::min(ymin, q.y);
  EXPECT_NEAR(ymin, bottom, 1e-9);
  EXPECT_FALSE(p.on_window_border[0] || p.on_window_border[1] || p.on_window_border[2] ||
               p.on_window_border[3]);
}

// Two triangles sharing an edge that crosses the near plane get bit-identical intersection
// points on it (computed from the inside vertex in both), so no crack can open between them.
TEST(ClipTriangle, SharedEdgeGivesIdenticalPoints) {
  const View v = make_view(150, 907, 907);
  const Vec3 p{0.02, 0.01, -0.6}, q{-0.01, 0.003, 0.4};  // shared edge, q behind the camera
  const ClippedPolygon t1 = clip_triangle(v, p, q, {0.3, -0.2, -0.7});
  const ClippedPolygon t2 = clip_triangle(v, q, p, {-0.3, 0.25, -0.8});
  ASSERT_EQ(t1.status, ClipStatus::kVisible);
  ASSERT_EQ(t2.status, ClipStatus::kVisible);
  int shared = 0;
  for (const Vec2& a : t1.vertices)
    for (const Vec2& b : t2.vertices) shared += a.x == b.x && a.y == b.y;
  EXPECT_EQ(shared, 2);  // the front vertex and the near-plane point
}

// A vertex exactly on the far plane (z_eye = -far) and two inside: the polygon is the whole
// projected triangle (the vertex is kept or cut at t ~ 1, the same point to rounding).
TEST(ClipTriangle, VertexOnTheFarPlane) {
  const View v = make_view(30, 128, 128, 0.01, 10);
  const Vec3 a{0.5, 0.2, -10}, b{-0.3, 0.1, -5}, c{0.1, -0.4, -5};
  const ClippedPolygon p = clip_triangle(v, a, b, c);
  ASSERT_EQ(p.status, ClipStatus::kVisible);
  const Vec2 wa = closed_form_window(v, a), wb = closed_form_window(v, b),
             wc = closed_form_window(v, c);
  const double expect = 0.5 * std::fabs(cross(wb - wa, wc - wa));
  EXPECT_NEAR(p.area, expect, 1e-9 * expect);
}

// A big triangle around the camera axis in a 150-degree view covers the whole window: the polygon
// is exactly the window rectangle (corners created by two planes), all of it border.
TEST(ClipTriangle, CoveringTheWindowInAWideView) {
  const View v = make_view(150, 907, 907);
  const ClippedPolygon p = clip_triangle(v, {-50, -30, -1}, {50, -30, -1}, {0, 60, -1});
  ASSERT_EQ(p.status, ClipStatus::kVisible);
  ASSERT_EQ(p.vertices.size(), 4u);
  EXPECT_EQ(p.area, 907.0 * 907.0);
  for (bool border : p.on_window_border) EXPECT_TRUE(border);
  const PixelRect r = bounding_rect(p, 907, 907, 2);
  EXPECT_EQ(r.x0, 0);
  EXPECT_EQ(r.y0, 0);
  EXPECT_EQ(r.x1, 907);
  EXPECT_EQ(r.y1, 907);
}

// A triangle reaching into a corner of a 150-degree view from outside, its vertices at different
// depths: the window corner (W, H) is a vertex, exactly, and both edges meeting there lie on the
// border (the corner comes from cutting a right-border edge by the top plane).
TEST(ClipTriangle, CornerOfAWideView) {
  const View v = make_view(150, 907, 907);
  const ClippedPolygon p = clip_triangle(v, {0.5, 0.5, -0.1}, {0.2, 1.0, -0.2}, {1.0, 0.2, -0.25});
  ASSERT_EQ(p.status, ClipStatus::kVisible);
  int corner = -1;
  for (size_t i = 0; i < p.vertices.size(); ++i)
    if (p.vertices[i].x == 907.0 && p.vertices[i].y == 907.0) corner = int(i);
  ASSERT_GE(corner, 0);
  const size_t n = p.vertices.size();
  EXPECT_TRUE(p.on_window_border[size_t(corner)]);
  EXPECT_TRUE(p.on_window_border[(size_t(corner) + n - 1) % n]);
}

// Degenerate triangles: repeated or exactly collinear vertices have zero area -> kDegenerate,
// not ideally visible, and the polygon is the segment (or point) they span.
TEST(ClipTriangle, DegenerateTriangles) {
  const Vec4 a{-0.5, -0.5, 0, 1}, b{0.5, 0.5, 0, 1}, m{0, 0, 0, 1};
  const ClippedPolygon collinear = clip_triangle(a, m, b, 100, 100);
  EXPECT_EQ(collinear.status, ClipStatus::kDegenerate);
  EXPECT_FALSE(ideally_visible(collinear));
  EXPECT_EQ(collinear.vertices.size(), 2u);
  EXPECT_EQ(collinear.area, 0.0);
  const ClippedPolygon repeated = clip_triangle(a, a, a, 100, 100);
  EXPECT_EQ(repeated.status, ClipStatus::kDegenerate);
  EXPECT_EQ(repeated.vertices.size(), 1u);
  const PixelRect r = bounding_rect(repeated, 100, 100);
  EXPECT_EQ(r.area(), 1);
}

// Edge-on: a triangle in a plane through the eye projects to a segment (zero or rounding-level
// area); it must not come out as a visible triangle of noticeable area.
TEST(ClipTriangle, EdgeOnToTheEye) {
  const View v = make_view(150, 907, 907);
  // Exactly in the plane y = 0, which holds the eye: a segment on screen, zero area.
  const ClippedPolygon exact = clip_triangle(v, Vec3{0.3, 0, -0.5}, Vec3{-0.2, 0, -0.7},
                                             Vec3{0.1, 0, -1.2});
  EXPECT_EQ(exact.status, ClipStatus::kDegenerate);
  EXPECT_EQ(exact.area, 0.0);
  // p + q rounds off the plane of p, q and the eye by about 1e-17: whatever status the exact
  // predicates give that input, its area must stay at rounding level.
  const Vec3 p{0.3, 0.1, -0.5}, q{-0.2, 0.05, -0.7};
  const ClippedPolygon t = clip_triangle(v, p, q, p + q);
  EXPECT_TRUE(t.status == ClipStatus::kDegenerate || t.status == ClipStatus::kVisible)
      << clip_status_name(t.status);
  EXPECT_LT(t.area, 1e-6);
}

// Touching the volume only along a face (the triangle lies in x = w): zero window area.
TEST(ClipTriangle, LyingInAFace) {
  const ClippedPolygon t =
      clip_triangle(Vec4{1, 0, 0, 1}, Vec4{1, 0.5, 0, 1}, Vec4{2, 0.5, 0.5, 2}, 50, 50);
  EXPECT_EQ(t.status, ClipStatus::kDegenerate);
}

// Wholly outside one plane: invisible, no vertices.
TEST(ClipTriangle, OutsideIsInvisible) {
  const ClippedPolygon t =
      clip_triangle(Vec4{2, 0, 0, 1}, Vec4{3, 0.5, 0, 1}, Vec4{2.5, -0.5, 0, 1}, 50, 50);
  EXPECT_EQ(t.status, ClipStatus::kInvisible);
  EXPECT_TRUE(t.vertices.empty());
}

// Bounding rectangles: floor of the minimum to floor of the maximum (an end exactly on x = 5
// includes column 5), grown by the margin, clamped to the window.
TEST(BoundingRect, ClosedBoxGrownAndClamped) {
  ClippedPolygon p;
  p.status = ClipStatus::kVisible;
  p.vertices = {{1.5, 2.5}, {5.0, 2.5}, {3.0, 7.25}};
  PixelRect r = bounding_rect(p, 10, 8);
  EXPECT_EQ(r.x0, 1);
  EXPECT_EQ(r.x1, 6);
  EXPECT_EQ(r.y0, 2);
  EXPECT_EQ(r.y1, 8);
  r = bounding_rect(p, 10, 8, 2);
  EXPECT_EQ(r.x0, 0);
  EXPECT_EQ(r.x1, 8);
  EXPECT_EQ(r.y1, 8);
}

// The hull drops repeats and collinear points and is counter-clockwise.
TEST(ConvexHull, DropsRepeatsAndCollinear) {
  const std::vector<Vec2> h =
      convex_hull({{0, 0}, {2, 0}, {1, 0}, {2, 2}, {0, 2}, {0, 0}, {1, 1}, {2, 1}});
  ASSERT_EQ(h.size(), 4u);
  EXPECT_EQ(polygon_signed_area(h), 4.0);
}

}  // namespace
}  // namespace ra::geometry
