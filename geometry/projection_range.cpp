// The projection's range checks (see the header).
#include "geometry/projection_range.h"

#include <cmath>
#include <cstdio>
#include <limits>

#include "geometry/view.h"

namespace ra::geometry {
namespace {

// "" when |v| is finite in double and at most FLT_MAX, else what `what` is.
std::string out_of_float(const char* what, double v) {
  if (std::isfinite(v) && std::fabs(v) <= double(std::numeric_limits<float>::max())) return "";
  char text[64];
  std::snprintf(text, sizeof text, "%.6g", v);
  return std::string(what) + " is " + text +
         (std::isfinite(v) ? ", beyond the float range (3.40282e+38)" : ", not a finite double");
}

}  // namespace

std::string depth_projection_problem(double near, double far, double extent) {
  const Mat4 p = perspective_matrix(90, 1, near, far);
  const double a = p.at(2, 2), b = p.at(2, 3);
  for (const std::string& why :
       {out_of_float("(far+near)/(near-far)", a), out_of_float("2*far*near/(near-far)", b),
        out_of_float("the largest clip z, |(far+near)/(near-far)|*extent + "
                     "|2*far*near/(near-far)|",
                     std::fabs(a) * extent + std::fabs(b)),
        out_of_float("the largest clip w", extent)})
    if (!why.empty()) return why;
  return "";
}

std::string lateral_projection_problem(double fov_deg, double aspect, double extent) {
  const Mat4 p = perspective_matrix(fov_deg, aspect, 1, 2);
  for (const std::string& why :
       {out_of_float("1/tan(fov/2)/aspect", p.at(0, 0)), out_of_float("1/tan(fov/2)", p.at(1, 1)),
        out_of_float("the largest clip x", p.at(0, 0) * extent),
        out_of_float("the largest clip y", p.at(1, 1) * extent)})
    if (!why.empty()) return why;
  return "";
}

}  // namespace ra::geometry
