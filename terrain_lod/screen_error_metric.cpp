// Screen-space error of a vertex (screen_error_metric.h; Lindstrom & Pascucci 2001, equations (3)-(5)).
#include "terrain_lod/screen_error_metric.h"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace ra::lod {

const char* lambda_kind_name(LambdaKind kind) {
  switch (kind) {
    case LambdaKind::kPlanar: return "planar";
    case LambdaKind::kSpherical: return "spherical";
    case LambdaKind::kWindow: return "window";
  }
  return "?";
}

LambdaKind parse_lambda_kind(const std::string& name) {
  if (name == "planar") return LambdaKind::kPlanar;
  if (name == "spherical") return LambdaKind::kSpherical;
  if (name == "window") return LambdaKind::kWindow;
  throw std::invalid_argument("unknown lambda '" + name + "' (allowed: window, planar, spherical)");
}

double lambda_for(LambdaKind kind, const scenes::CameraSettings& cam) {
  const double w = cam.width, h = cam.height;
  const double f = 0.5 * h / std::tan(cam.half_fov_y());  // focal length, pixels
  const double phi_x = 2 * std::atan(0.5 * w / f);          // horizontal field of view, radians
  switch (kind) {
    case LambdaKind::kPlanar: return w / (2 * std::tan(phi_x / 2));  // = f
    case LambdaKind::kSpherical: return w / phi_x;
    case LambdaKind::kWindow: return (f * f + 0.25 * w * w + 0.25 * h * h) / f;
  }
  return f;
}

double ScreenErrorMetric::rho(double eps, double radius, geometry::Vec3 p) const {
  const geometry::Vec3 v = p - eye;
  const double d = std::sqrt(geometry::dot(v, v));
  constexpr double kInf = std::numeric_limits<double>::infinity();
  if (eps <= 0) return 0;  // the coarser surface is exact there: never worth a vertex (flat land)
  if (kind == LambdaKind::kWindow) {
    const double gap = d - radius - eps;  // nearest distance of any point of the error segment
    if (gap <= 0) return kInf;
    return lambda * 2 * std::asin(std::min(1.0, eps / (2 * gap)));
  }
  if (d <= radius) return kInf;  // the eye inside the ball: active by convention (paper, (5))
  return lambda * eps / (d - radius);
}

ScreenErrorMetric make_metric(LambdaKind kind, const scenes::CameraSettings& cam, double tau,
                              geometry::Vec3 eye) {
  ScreenErrorMetric m;
  m.kind = kind;
  m.lambda = lambda_for(kind, cam);
  m.tau = tau;
  m.eye = eye;
  return m;
}

}  // namespace ra::lod
