#include "geometry/view.h"

#include <cmath>

#include "util/counter_rng.h"

namespace ra::geometry {

double View::norm_length() const { return std::sqrt(double(width) * double(height)); }

std::string View::group_name() const {
  std::string name;
  int g = group;
  do {  // A..Z, then AA, AB, ...
    name.insert(name.begin(), char('A' + g % 26));
    g = g / 26 - 1;
  } while (g >= 0);
  return name;
}

Mat4 perspective_matrix(double fov_deg, double aspect, double near, double far) {
  const double f = 1.0 / std::tan(fov_deg * M_PI / 360.0);
  Mat4 p;
  p.at(0, 0) = f / aspect;
  p.at(1, 1) = f;
  p.at(2, 2) = (far + near) / (near - far);
  p.at(2, 3) = 2.0 * far * near / (near - far);
  p.at(3, 2) = -1.0;
  return p;
}

static Mat4 axis_rotation(int axis, double deg) {
  const double c = std::cos(deg * M_PI / 180.0), s = std::sin(deg * M_PI / 180.0);
  Mat4 r = Mat4::identity();
  const int a = (axis + 1) % 3, b = (axis + 2) % 3;  // the plane rotated, right-handed
  r.at(a, a) = c;
  r.at(a, b) = -s;
  r.at(b, a) = s;
  r.at(b, b) = c;
  return r;
}

Mat4 rotation_from_euler_deg(double yaw, double pitch, double roll) {
  return axis_rotation(1, yaw) * axis_rotation(0, pitch) * axis_rotation(2, roll);
}

Mat4 random_rotation(uint64_t seed, int orientation_number) {
  // Shoemake, "Uniform random rotations", Graphics Gems III (1992): a unit quaternion from three
  // uniforms is uniform on S^3, hence the rotation is uniform (Haar) on SO(3).
  CounterRng rng(seed, RngStream::kOrientation, static_cast<uint64_t>(orientation_number));
  const double u1 = rng.uniform01(), u2 = rng.uniform01(), u3 = rng.uniform01();
  const double a = std::sqrt(1 - u1), b = std::sqrt(u1);
  const double x = a * std::sin(2 * M_PI * u2), y = a * std::cos(2 * M_PI * u2);
  const double z = b * std::sin(2 * M_PI * u3), w = b * std::cos(2 * M_PI * u3);
  Mat4 r = Mat4::identity();
  r.at(0, 0) = 1 - 2 * (y * y + z * z);
  r.at(0, 1) = 2 * (x * y - z * w);
  r.at(0, 2) = 2 * (x * z + y * w);
  r.at(1, 0) = 2 * (x * y + z * w);
  r.at(1, 1) = 1 - 2 * (x * x + z * z);
  r.at(1, 2) = 2 * (y * z - x * w);
  r.at(2, 0) = 2 * (x * z - y * w);
  r.at(2, 1) = 2 * (y * z + x * w);
  r.at(2, 2) = 1 - 2 * (x * x + y * y);
  return r;
}

void finish_view(View& v) {
  // The camera sits at the origin, so world-to-camera is the transpose of the rotation.
  v.view_matrix = Mat4::identity();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) v.view_matrix.at(r, c) = v.rotation.at(c, r);
  v.projection = perspective_matrix(v.fov_deg, double(v.width) / double(v.height), v.near, v.far);
  v.view_projection = v.projection * v.view_matrix;
}

View make_view(double fov_deg, int width, int height, double near, double far,
               const Mat4& rotation) {
  View v;
  v.fov_deg = fov_deg;
  v.width = width;
  v.height = height;
  v.near = near;
  v.far = far;
  v.rotation = rotation;
  finish_view(v);
  return v;
}

}  // namespace ra::geometry
