// Exact signs of small polynomials in doubles, for the tie-breaking rules of the reference
// rasterizer (GL fill and diamond-exit rules) and for robust convex hulls of clipped polygons.
// Method: evaluate in double with a forward error bound (a "filter"); only when the value is
// within that bound, re-evaluate exactly with floating-point expansions (Shewchuk, "Adaptive
// Precision Floating-Point Arithmetic and Fast Robust Geometric Predicates", DCG 18, 1997: the
// TwoSum / TwoProduct error-free transformations and Grow-Expansion).
// Exact as long as no intermediate product overflows or underflows (|inputs| between about
// 1e-150 and 1e150, or exactly 0), which holds for every window coordinate of this project.
#pragma once

#include "geometry/vector_math.h"

namespace ra::geometry {

// Exact sign (-1, 0, +1) of terms[0] + ... + terms[n-1].
int exact_sign_of_sum(const double* terms, int n);

// Exact sign of sum_k a[k] * b[k] (k < n_products) + sum_k c[k] (k < n_terms).
int exact_sign_of_dot_plus(const double* a, const double* b, int n_products, const double* c,
                           int n_terms);

// Orientation of c relative to the directed line a -> b, all in the same 2D coordinates (here GL
// window coordinates, y up): +1 when c is to the left (a, b, c counter-clockwise), -1 to the
// right, 0 exactly collinear. Exact.
int orient2d(Vec2 a, Vec2 b, Vec2 c);

}  // namespace ra::geometry
