// The floating-point allowance of GL window coordinates, stage by stage (see window_error.h).
#include "metrics/window_error.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ra::metrics {

namespace {

constexpr double kEps = kFloatRelativeError;
constexpr double kInf = std::numeric_limits<double>::infinity();

double component(geometry::Vec4 v, int k) {
  return k == 0 ? v.x : k == 1 ? v.y : k == 2 ? v.z : v.w;
}
void set_component(geometry::Vec4& v, int k, double x) {
  (k == 0 ? v.x : k == 1 ? v.y : k == 2 ? v.z : v.w) = x;
}

bool finite(geometry::Vec4 v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z) && std::isfinite(v.w);
}

// Stage 3 + 4 for one axis: |error| (px) of the window coordinate from q_k / q_w. The quotient's
// bound is exact for perturbed operands (the denominator at its smallest), not only first order.
double window_axis_error(double qk, double ek, double qw, double ew, int size) {
  if (!(ew < qw)) return kInf;  // the implementation's w may reach 0
  const double n = qk / qw;
  double dn = (ek + std::fabs(n) * ew) / (qw - ew);
  dn += kEps * (std::fabs(n) + dn);  // the divide's rounding
  const double half = 0.5 * size;
  const double sum = std::fabs(n) + 1.0 + dn;
  double dx = (dn + kEps * sum) * half;     // the add's rounding, scaled
  dx += kEps * (sum * half + dx);           // the multiply's rounding
  return std::isfinite(dx) ? dx : kInf;
}

}  // namespace

ClipWithError clip_with_error(const geometry::View& view, geometry::Vec3 p) {
  ClipWithError out;
  out.c = view.to_clip(p);
  const double v[4] = {std::fabs(p.x), std::fabs(p.y), std::fabs(p.z), 1.0};
  // |V| |v|, then |P| (|V| |v|): the magnitudes every product in either order is made of.
  double eye[4];
  for (int i = 0; i < 4; ++i) {
    eye[i] = 0;
    for (int j = 0; j < 4; ++j) eye[i] += std::fabs(view.view_matrix.at(i, j)) * v[j];
  }
  for (int k = 0; k < 4; ++k) {
    double s = 0;
    for (int i = 0; i < 4; ++i) s += std::fabs(view.projection.at(k, i)) * eye[i];
    set_component(out.err, k, 2 * kEps * (1 + kEps) * s);  // two results; the second rounds the first's error too
  }
  return out;
}

ClipWithError near_intersection_with_error(const ClipWithError& a, const ClipWithError& b) {
  const double da = a.c.z + a.c.w, db = b.c.z + b.c.w;
  const double dda = a.err.z + a.err.w + kEps * (std::fabs(a.c.z) + std::fabs(a.c.w) + a.err.z + a.err.w);
  const double ddb = b.err.z + b.err.w + kEps * (std::fabs(b.c.z) + std::fabs(b.c.w) + b.err.z + b.err.w);
  const double den = da - db;  // > 0: da > 0 > db
  const double dden = dda + ddb + kEps * (std::fabs(da) + std::fabs(db) + dda + ddb);  // |dD|
  ClipWithError q;
  if (!(dden < den)) {  // the cut may lie anywhere on the edge's line
    q.c = a.c;
    q.err = {kInf, kInf, kInf, kInf};
    return q;
  }
  const double t = da / den;
  // t' - t = (e_a (-d_b) + d_a e_b - d_a e_D) / (D D'): the errors of d_a in the numerator and
  // the denominator partly cancel.
  double dt = ((1 - t) * dda + t * ddb + t * kEps * (den + dden)) / (den - dden);
  dt += kEps * (t + dt);
  for (int k = 0; k < 4; ++k) {
    const double ak = component(a.c, k), bk = component(b.c, k);
    const double eak = component(a.err, k), ebk = component(b.err, k);
    // q' - q = (1 - t') e_a + t' e_b + (t' - t) (b - a): a's error enters twice and partly cancels.
    const double diff = std::fabs(bk - ak);
    const double dround = kEps * (diff + eak + ebk);  // the subtraction's rounding
    const double prod = t * diff;
    const double dprod = dt * diff + (t + dt) * (eak + ebk + dround);
    const double dsum = (1 - t + dt) * eak + (t + dt) * ebk + dt * diff + (t + dt) * dround +
                        kEps * (prod + dprod);  // the product's rounding
    set_component(q.c, k, ak + t * (bk - ak));
    set_component(q.err, k, dsum + kEps * (std::fabs(ak) + eak + prod + dprod));  // the sum's
  }
  return q;
}

AllowedVertex window_vertex(const ClipWithError& q, int width, int height) {
  AllowedVertex v;
  v.p = {(q.c.x / q.c.w + 1.0) * 0.5 * width, (q.c.y / q.c.w + 1.0) * 0.5 * height};
  const double ex = window_axis_error(q.c.x, q.err.x, q.c.w, q.err.w, width);
  const double ey = window_axis_error(q.c.y, q.err.y, q.c.w, q.err.w, height);
  v.allowance = kSnapAllowancePx + std::max(ex, ey);
  return v;
}

std::vector<AllowedVertex> near_clipped_vertices(const geometry::View& view,
                                                 const geometry::Primitive& prim) {
  const int n = geometry::vertex_count(prim.kind);
  ClipWithError c[3];
  for (int i = 0; i < n; ++i) {
    c[i] = clip_with_error(view, prim.v[i]);
    if (!finite(c[i].c)) return {};
  }
  auto inside = [](const ClipWithError& q) { return q.c.z + q.c.w > 0 && q.c.w > 0; };
  std::vector<ClipWithError> kept;
  // Sutherland-Hodgman against the near plane alone; a segment is a polygon of two vertices
  // whose closing edge is not walked.
  const int edges = n == 1 ? 0 : n == 2 ? 1 : 3;
  if (n == 1 && inside(c[0])) kept.push_back(c[0]);
  for (int i = 0; i < edges; ++i) {
    const int j = (i + 1) % n;
    const bool in_i = c[i].c.z + c[i].c.w > 0, in_j = c[j].c.z + c[j].c.w > 0;
    if (in_i) kept.push_back(c[i]);
    if (in_i && !in_j) kept.push_back(near_intersection_with_error(c[i], c[j]));
    if (!in_i && in_j) kept.push_back(near_intersection_with_error(c[j], c[i]));
    if (n == 2 && in_j) kept.push_back(c[j]);
  }
  std::vector<AllowedVertex> out;
  for (const ClipWithError& q : kept) {
    if (!(q.c.w > 0)) return {};  // in front of the near plane w > 0 unless the matrix is odd
    out.push_back(window_vertex(q, view.width, view.height));
  }
  return out;
}

double conformance_allowance(double magnitude, int width, int height) {
  return kSnapAllowancePx + kEps * std::max({magnitude, double(width), double(height)});
}

std::vector<AllowedVertex> uniform_allowance(const std::vector<geometry::Vec2>& points, int width,
                                             int height) {
  std::vector<AllowedVertex> out;
  for (const geometry::Vec2& p : points)
    out.push_back({p, conformance_allowance(0, width, height)});
  return out;
}

}  // namespace ra::metrics
