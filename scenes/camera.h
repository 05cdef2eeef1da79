// The camera the studies share (timing/, terrain_lod/, regulation/): the perspective camera of a
// viewpoint, view-frustum culling of bounding spheres, and the angles that parameterise per-object sampling (Wimmer &
// Wonka 2003, section 5.2, Figure 5): alpha (the angle between the two supporting lines of the
// bounding sphere seen from the eye, clipped to the view frustum), gamma and phi (the direction
// the object is seen from).
// Units: metres, radians; world coordinates +Z up (scenes/scene.h).
#pragma once

#include "geometry/vector_math.h"
#include "scenes/scene.h"

namespace ra::scenes {

struct CameraSettings {
  int width = 640, height = 480;  // window, pixels
  double fov_y_deg = 60;          // vertical field of view, degrees, (0, 180)
  double near = 0.5, far = 20000;  // clip planes, metres
  double half_fov_y() const;      // radians
  double half_fov_x() const;      // radians, from the aspect ratio
};

// gluLookAt(eye, target, up) as a column-major matrix (world -> camera). When up is parallel to
// the viewing direction another up (world +Y, then +X) is used.
geometry::Mat4 look_at(const Viewpoint& vp);
geometry::Mat4 projection_of(const CameraSettings& cam);  // gluPerspective

// The six planes of the frustum of projection * view (Gribb & Hartmann), normalised, inside >= 0.
struct Frustum {
  geometry::Vec4 planes[6];
  // True when the sphere is at least partly inside (conservative: may keep a sphere just outside
  // a frustum corner, never drops a visible one).
  bool intersects(const BoundingSphere& s) const;
};
Frustum frustum_of(const geometry::Mat4& view_projection);

// Direction the eye sees the object from: gamma = atan2(dy, dx) in [0, 2 pi), phi = asin(dz / |d|)
// in [-pi/2, pi/2], d = eye - centre. (0, 0) when the eye is at the centre.
void view_direction_angles(geometry::Vec3 eye, geometry::Vec3 centre, double* gamma, double* phi);

// The paper's alpha clipped to the view frustum: with rho the sphere's angular radius seen from
// the eye (asin(r / d); pi/2 when the eye is inside it) and (tx, ty) the angles of its centre
// from the viewing axis in the camera's horizontal and vertical planes, the angular intervals
// [tx - rho, tx + rho] and [ty - rho, ty + rho] are intersected with [-hx, hx] and [-hy, hy]
// (the half fields of view); alpha = sqrt(wx * wy), the geometric mean of the two clipped widths,
// so a sphere wholly in view gets 2 rho, the unclipped angle, and one filling the window gets
// sqrt(4 hx hy). 0 when it is not in view. `view` is world -> camera.
double clipped_alpha(const geometry::Mat4& view, const CameraSettings& cam,
                     const BoundingSphere& s);

// The largest clipped alpha (the sphere covers the whole window): sqrt(4 hx hy).
double max_clipped_alpha(const CameraSettings& cam);

// A viewpoint looking at the sphere's centre from direction (gamma, phi) at the distance where its
// clipped alpha is `alpha` (0 < alpha <= max_clipped_alpha; the inverse of clipped_alpha on the
// viewing axis, in closed form). Up is world +Z.
Viewpoint viewpoint_for(const BoundingSphere& s, const CameraSettings& cam, double alpha,
                        double gamma, double phi);

}  // namespace ra::scenes
