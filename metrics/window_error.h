// How far from the exact position a conforming GL implementation may compute a vertex's window
// coordinates: the subpixel snap plus GL's floating-point allowance, propagated through the stages
// where the error arises. Coordinates: GL window coordinates in pixels (as clipping.h), which for
// a vertex made by the near clip may lie far outside the window; allowances in pixels, per axis.
//
// GL asks that "individual results of floating-point operations are accurate to about 1 part in
// 10^5" (OpenGL 4.6 section 2.3.4.1; 2.1 section 2.1.1): eps = kFloatRelativeError. A result that
// combines terms (a sum, a dot product as a vertex shader's DP4 computes it) may be off by eps
// times the sum of its terms' magnitudes; a product or quotient by eps times its own magnitude.
// A dot product is taken as one result, as a vertex shader's DP4 (or a fused multiply-add chain)
// computes it; rounding each addition apart would multiply stage 1's term by up to 4. The
// conversion of the inputs to the implementation's format (doubles to float: 6e-8) is far below
// eps. The stages:
//  1. Clip coordinates c = P (V v): the modelview product, or the matrix product P V that an
//     implementation forms first, then one transform; either way two results, so
//     |dc_k| <= 2 eps (1 + eps) S_k with S_k = sum_j sum_i |P_ki| |V_ij| |v_j| (v_3 = 1).
//  2. The near clip (only the near plane can cut a vertex that then lies inside the window; the
//     side planes cut where the window discards the fragments, and a guard-band rasterizer does
//     not cut there at all). For the edge from a (inside, d_a = z_a + w_a > 0) to b (d_b < 0):
//        d = z + w                 |dd|   <= |dz| + |dw| + eps (|z| + |w|)
//        t = d_a / (d_a - d_b)     |dt|   <= ((1 - t) |dd_a| + t |dd_b| + t eps |D|)
//                                            / (D - |dD|) + eps t,
//                                  D = d_a - d_b, |dD| <= |dd_a| + |dd_b| + eps (|d_a| + |d_b|)
//        q = a + t (b - a)         |dq_k| <= (1 - t + |dt|) |da_k| + (t + |dt|) |db_k| + |dt| |B|
//                                            + eps (|a_k| + 2 t |B|) + ...,  B = b_k - a_k
//     (a's error enters through a and through b - a and partly cancels; "..." are the roundings
//     applied to the errors themselves, in window_error.cpp).
//     Where the edge is long and the near plane close, |dt| |B| dominates: w at the cut is a
//     difference of numbers far larger than itself, and the cut vertex can move by far more than
//     eps times its own window coordinate. Where |dD| >= D, or |dq_w| >= q_w below, nothing
//     bounds the cut (the implementation's w may reach 0): the allowance is infinite, as it is at
//     a near plane of 10^-5 for edges of length 1 (eps / near = 1).
//  3. The divide n = q_x / q_w:     |dn| <= (|dq_x| + |n| |dq_w|) / (q_w - |dq_w|) + eps |n|
//  4. The viewport X = (n + 1) W/2: |dX| <= |dn| W/2 + eps (|n| + 1) W/2 + eps |X|
// Quotients are bounded for their operands at the worst end of their ranges, and each rounding
// also applies to the error it is handed, so the bounds hold beyond first order.
// The allowance of an axis is kSnapAllowancePx + |dX|; where |dq_w| >= q_w the implementation's w
// may reach 0 and nothing bounds the position: the allowance is infinite.
#pragma once

#include <vector>

#include "geometry/primitive.h"
#include "geometry/vector_math.h"
#include "geometry/view.h"

namespace ra::metrics {

// The least subpixel grid GL allows, 4 bits: a truncating snap moves a coordinate by < 2^-4 px.
constexpr int kLeastSubpixelBits = 4;
constexpr double kSnapAllowancePx = 0.0625;
// GL's "about 1 part in 10^5" for the results of floating-point operations.
constexpr double kFloatRelativeError = 1e-5;

// A vertex as GL may place it: its exact window position and how far (px, in x and in y each)
// a conforming implementation's position may lie from it.
struct AllowedVertex {
  geometry::Vec2 p;        // exact GL window position, px
  double allowance = 0;    // px per axis: snap + floating-point error (may be +infinity)
};

// A clip-space point with a bound on the floating-point error of each of its components.
struct ClipWithError {
  geometry::Vec4 c;    // exact clip coordinates
  geometry::Vec4 err;  // |error| bound of each component, clip units
};

// Stage 1: the clip coordinates of world point p under `view` and their error bound.
ClipWithError clip_with_error(const geometry::View& view, geometry::Vec3 p);
// Stage 2: the near clip of the edge from a (z + w > 0) to b (z + w < 0).
ClipWithError near_intersection_with_error(const ClipWithError& a, const ClipWithError& b);
// Stages 3 and 4 plus the snap: the vertex's window position and allowance (q.c.w > 0).
AllowedVertex window_vertex(const ClipWithError& q, int width, int height);

// The primitive clipped to the near plane only, in vertex order (for a triangle the polygon's
// order; 0 to 4 vertices), each with its allowance; a point gives its one vertex when it lies in
// front of the near plane. Empty when nothing of it lies in front of the near plane or a
// coordinate is not finite.
std::vector<AllowedVertex> near_clipped_vertices(const geometry::View& view,
                                                 const geometry::Primitive& prim);

// The uniform allowance of a vertex whose window coordinates have magnitude up to `magnitude` in a
// width x height window: the snap plus eps times the larger of the magnitude and the window's
// size (the rule for vertices that no clip moved, used by hand-made cases with no view).
double conformance_allowance(double magnitude, int width, int height);

// Each window position with the uniform allowance conformance_allowance(0, width, height).
std::vector<AllowedVertex> uniform_allowance(const std::vector<geometry::Vec2>& points, int width,
                                             int height);

}  // namespace ra::metrics
