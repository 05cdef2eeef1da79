// The study camera (camera.h; Wimmer & Wonka 2003, 5.2).
#include "scenes/camera.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "geometry/view.h"

namespace ra::scenes {
namespace {

geometry::Vec3 cross3(geometry::Vec3 a, geometry::Vec3 b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
double len3(geometry::Vec3 a) { return std::sqrt(geometry::dot(a, a)); }
geometry::Vec3 unit(geometry::Vec3 a) { return (1.0 / len3(a)) * a; }

}  // namespace

double CameraSettings::half_fov_y() const { return 0.5 * fov_y_deg * M_PI / 180.0; }
double CameraSettings::half_fov_x() const {
  return std::atan(std::tan(half_fov_y()) * double(width) / double(height));
}

geometry::Mat4 look_at(const Viewpoint& vp) {
  const geometry::Vec3 f = unit(vp.target - vp.eye);
  geometry::Vec3 up = vp.up;
  for (geometry::Vec3 alt : {geometry::Vec3{0, 1, 0}, geometry::Vec3{1, 0, 0}}) {
    if (len3(cross3(f, up)) > 1e-9 * len3(up)) break;
    up = alt;
  }
  const geometry::Vec3 s = unit(cross3(f, up));
  const geometry::Vec3 u = cross3(s, f);
  geometry::Mat4 m = geometry::Mat4::identity();
  m.at(0, 0) = s.x, m.at(0, 1) = s.y, m.at(0, 2) = s.z;
  m.at(1, 0) = u.x, m.at(1, 1) = u.y, m.at(1, 2) = u.z;
  m.at(2, 0) = -f.x, m.at(2, 1) = -f.y, m.at(2, 2) = -f.z;
  m.at(0, 3) = -geometry::dot(s, vp.eye);
  m.at(1, 3) = -geometry::dot(u, vp.eye);
  m.at(2, 3) = geometry::dot(f, vp.eye);
  return m;
}

geometry::Mat4 projection_of(const CameraSettings& cam) {
  return geometry::perspective_matrix(cam.fov_y_deg, double(cam.width) / double(cam.height),
                                      cam.near, cam.far);
}

Frustum frustum_of(const geometry::Mat4& m) {
  Frustum f;
  auto row = [&](int r) { return geometry::Vec4{m.at(r, 0), m.at(r, 1), m.at(r, 2), m.at(r, 3)}; };
  const geometry::Vec4 r0 = row(0), r1 = row(1), r2 = row(2), r3 = row(3);
  const geometry::Vec4 raw[6] = {r3 + r0, r3 - r0, r3 + r1, r3 - r1, r3 + r2, r3 - r2};
  for (int i = 0; i < 6; ++i) {
    const double n = std::sqrt(raw[i].x * raw[i].x + raw[i].y * raw[i].y + raw[i].z * raw[i].z);
    f.planes[i] = (1.0 / n) * raw[i];
  }
  return f;
}

bool Frustum::intersects(const BoundingSphere& s) const {
  for (const geometry::Vec4& p : planes)
    if (p.x * s.centre.x + p.y * s.centre.y + p.z * s.centre.z + p.w < -s.radius) return false;
  return true;
}

void view_direction_angles(geometry::Vec3 eye, geometry::Vec3 centre, double* gamma, double* phi) {
  const geometry::Vec3 d = eye - centre;
  const double l = len3(d);
  if (l == 0) {
    *gamma = 0, *phi = 0;
    return;
  }
  double g = std::atan2(d.y, d.x);
  if (g < 0) g += 2 * M_PI;
  if (g >= 2 * M_PI) g = 0;
  *gamma = g;
  *phi = std::asin(std::clamp(d.z / l, -1.0, 1.0));
}

double max_clipped_alpha(const CameraSettings& cam) {
  return std::sqrt(4 * cam.half_fov_x() * cam.half_fov_y());
}

double clipped_alpha(const geometry::Mat4& view, const CameraSettings& cam,
                     const BoundingSphere& s) {
  const geometry::Vec4 c = view * geometry::Vec4{s.centre.x, s.centre.y, s.centre.z, 1.0};
  const double d = std::sqrt(c.x * c.x + c.y * c.y + c.z * c.z);
  const double hx = cam.half_fov_x(), hy = cam.half_fov_y();
  if (d <= s.radius) return max_clipped_alpha(cam);
  const double rho = std::asin(s.radius / d);
  const double tx = std::atan2(c.x, -c.z), ty = std::atan2(c.y, -c.z);
  const double wx = std::min(tx + rho, hx) - std::max(tx - rho, -hx);
  const double wy = std::min(ty + rho, hy) - std::max(ty - rho, -hy);
  if (wx <= 0 || wy <= 0) return 0;
  return std::sqrt(wx * wy);
}

Viewpoint viewpoint_for(const BoundingSphere& s, const CameraSettings& cam, double alpha,
                        double gamma, double phi) {
  const double lo = std::min(cam.half_fov_x(), cam.half_fov_y());
  const double hi = std::max(cam.half_fov_x(), cam.half_fov_y());
  if (!(alpha > 0)) throw std::invalid_argument("viewpoint_for: alpha must be > 0");
  // On the axis: alpha = sqrt(min(2 rho, 2 lo) * min(2 rho, 2 hi)).
  double rho = alpha <= 2 * lo ? 0.5 * alpha : alpha * alpha / (4 * lo);
  rho = std::min(rho, hi);
  const double dist = rho >= 0.5 * M_PI - 1e-9 ? s.radius * 1.0001 : s.radius / std::sin(rho);
  const geometry::Vec3 dir{std::cos(phi) * std::cos(gamma), std::cos(phi) * std::sin(gamma),
                           std::sin(phi)};
  Viewpoint vp;
  vp.eye = s.centre + dist * dir;
  vp.target = s.centre;
  vp.up = {0, 0, 1};
  return vp;
}

}  // namespace ra::scenes
