// Whether a view's projection is finite where it is computed (the experiment validator and the
// studies' camera reader refuse views whose projection is not).
#pragma once

#include <string>

namespace ra::geometry {

// Whether the projection of a view can be computed where it is: in double here (the ideal side, and
// the matrices handed to GL), in float in the drivers (GL transforms in float; the Vulkan back end
// hands its shader a float matrix). perspective_matrix has four entries besides the -1 that makes
// clip w = -z_eye: f/aspect and f (f = 1/tan(fov/2)), A = (far+near)/(near-far) and
// B = 2*far*near/(near-far), so that clip x = f/aspect*x, clip y = f*y, clip z = A*z + B.
// For eye coordinates x, y, z within `extent` of 0 (the audit's primitives lie in the unit sphere
// around the camera: extent 1) the clip coordinates are at most f/aspect*extent, f*extent,
// |A|*extent + |B| and extent. So a view is usable when every entry is finite in double (B
// multiplies 2*far*near first, which overflows once far*near passes DBL_MAX/2, or 2*far once far
// passes DBL_MAX/2, though B itself is near -2*near) and each of those bounds, with the entries
// themselves, is at most FLT_MAX (3.4e38). The checks return "" when so, else why not, naming the
// entry and its value.
std::string depth_projection_problem(double near, double far, double extent);
std::string lateral_projection_problem(double fov_deg, double aspect, double extent);

}  // namespace ra::geometry
