// The view-dependent screen-space error ("Screen Error Metric"; Lindstrom & Pascucci
// 2001, section 3): a vertex with nested error eps and ball radius r at p is active, i.e. kept in
// the mesh, when the eye e is inside its ball (d = |e - p| <= r) or rho > tau.
//
// The paper's rho = lambda * eps / (d - r) with
//   planar:    lambda = w / (2 tan(phi / 2))  (w pixels across the field of view phi; equation (3))
//   spherical: lambda = w / phi               ("a projection onto a sphere and not a plane").
// We take w and phi horizontally (the window's width and horizontal field of view); planar lambda
// is then the focal length f in pixels, the pixels per radian on the viewing axis only.
//
// Measured (lod_study): both can let the on-screen deviation exceed tau. In a perspective
// (gnomonic) projection the image of an angle of alpha radians is at most alpha * f / cos^2(theta)
// pixels, theta the angle off the axis: the stretch grows to f / cos^2(theta_corner) at the
// window's corners (1.93 f for 1024 x 768 at 60 degrees vertical). And a segment of length eps
// whose nearest point is D away subtends up to 2 asin(eps / (2 D)) > eps / D radians, where the
// segment's far end may be eps nearer than the ball: D = d - r - eps.
//   window (the default): lambda = f / cos^2(theta_corner) = (f^2 + (w/2)^2 + (h/2)^2) / f,
//     rho = lambda * 2 asin(min(1, eps / (2 (d - r - eps)))), active when d <= r + eps or
//     rho > tau. An upper bound of the pixel length of the image of any vertical error segment
//     lying in the window (great circles map to straight lines, so the image of the arc between
//     the segment's ends stays between them, where the stretch is <= lambda).
// All three are monotone in eps (increasing) and d - r (decreasing), so nested eps and balls give
// nested rho: an active vertex's DAG parents are active, which makes the refinement conforming.
// Units: metres, pixels, radians.
#pragma once

#include <string>

#include "geometry/vector_math.h"
#include "scenes/camera.h"

namespace ra::lod {

enum class LambdaKind { kPlanar, kSpherical, kWindow };

const char* lambda_kind_name(LambdaKind kind);  // "planar", "spherical", "window"
// Throws std::invalid_argument for another name.
LambdaKind parse_lambda_kind(const std::string& name);

// Pixels per radian of `kind` for the camera (vertical fov cam.fov_y_deg, window width x height).
double lambda_for(LambdaKind kind, const scenes::CameraSettings& cam);

struct ScreenErrorMetric {
  LambdaKind kind = LambdaKind::kWindow;
  double lambda = 1;  // pixels per radian (lambda_for)
  double tau = 1;     // pixels, > 0
  geometry::Vec3 eye;  // metres

  // rho of a vertex (pixels); 0 when eps = 0; +infinity when the eye is inside the ball (or within eps of it for
  // kWindow).
  double rho(double eps, double radius, geometry::Vec3 p) const;
  bool active(double eps, double radius, geometry::Vec3 p) const {
    return rho(eps, radius, p) > tau;
  }
};

ScreenErrorMetric make_metric(LambdaKind kind, const scenes::CameraSettings& cam, double tau,
                              geometry::Vec3 eye);

}  // namespace ra::lod
