// A view: camera at the origin with a rotation, a perspective projection and a viewport.
// Coordinates: world units -> clip coordinates (P * V * p) -> GL window coordinates in pixels, where
// x_w = (x_ndc + 1) * W / 2 and y_w = (y_ndc + 1) * H / 2 (pixel (i, j) covers [i, i+1) x [j, j+1)).
// The matrices here are the ones handed to GL (glLoadMatrixd), so the ideal projection is computed
// in double precision from exactly what the renderer is given.
#pragma once

#include <cstdint>
#include <string>

#include "geometry/vector_math.h"

namespace ra::geometry {

struct View {
  int id = 1;              // 1-based, in the order of the paper's Table 1
  int group = 0;           // views that differ only by orientation share a group (0 = 'A')
  int orientation = 1;     // 1-based orientation number (CO-1, CO-2, ...)
  double fov_deg = 30;     // vertical angular field of view, degrees, in (0, 180)
  int width = 128;         // window, pixels
  int height = 128;
  double near = 0.01;      // clip plane distances from the camera, world units
  double far = 10.0;
  Mat4 rotation;           // camera-to-world rotation (camera looks down its -Z axis)
  Mat4 view_matrix;        // world-to-camera (GL_MODELVIEW)
  Mat4 projection;         // camera-to-clip (GL_PROJECTION), gluPerspective's matrix
  Mat4 view_projection;    // projection * view_matrix

  Vec4 to_clip(Vec3 p) const { return view_projection * Vec4{p.x, p.y, p.z, 1.0}; }
  // Perspective divide and viewport; only meaningful for w > 0.
  Vec2 clip_to_window(Vec4 c) const {
    return {(c.x / c.w + 1.0) * 0.5 * width, (c.y / c.w + 1.0) * 0.5 * height};
  }
  // Strictly inside the clip volume -w < x, y, z < w (what GL keeps of a point).
  static bool inside_clip_volume(Vec4 c) {
    return c.w > 0 && -c.w < c.x && c.x < c.w && -c.w < c.y && c.y < c.w && -c.w < c.z &&
           c.z < c.w;
  }
  // A point strictly inside the view volume: x and y against w in clip coordinates, depth as
  // -far < z_eye < -near in camera coordinates (world units). The clip-space depth test -w < z < w
  // is the same in exact arithmetic but not in doubles once far / near passes about 1e15 (z then
  // rounds to w, and every point would be judged outside); the eye-space one holds for every ratio.
  bool point_inside(Vec3 p) const {
    const Vec4 c = to_clip(p);
    const double z_eye = (view_matrix * Vec4{p.x, p.y, p.z, 1.0}).z;
    return c.w > 0 && -c.w < c.x && c.x < c.w && -c.w < c.y && c.y < c.w && -far < z_eye &&
           z_eye < -near;
  }
  double norm_length() const;  // sqrt(W * H): one normalised window unit, in pixels
  std::string group_name() const;  // "A", "B", ...
};

// gluPerspective(fov_deg, aspect, near, far) as a column-major matrix.
Mat4 perspective_matrix(double fov_deg, double aspect, double near, double far);
// Rotation from yaw (about world +Y), pitch (about +X), roll (about the view axis), degrees:
// R = Ry(yaw) * Rx(pitch) * Rz(roll).
Mat4 rotation_from_euler_deg(double yaw, double pitch, double roll);
// A rotation uniform over SO(3) (Shoemake's subgroup algorithm), drawn from (seed, number).
Mat4 random_rotation(uint64_t seed, int orientation_number);
// Fills view_matrix, projection and view_projection from rotation, fov, window and planes.
void finish_view(View& v);

// A complete view: `fov_deg` degrees, width x height pixels, clip planes in world units, camera at
// the origin looking down -Z unless `rotation` (camera-to-world) turns it.
View make_view(double fov_deg, int width, int height, double near = 0.01, double far = 10.0,
               const Mat4& rotation = Mat4::identity());

}  // namespace ra::geometry
