// Exact predicate signs (see exact_predicates.h; Shewchuk 1997, sections 2.3-2.5).
#include "geometry/exact_predicates.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace ra::geometry {
namespace {

constexpr double kEps = 0x1.0p-53;  // unit roundoff of double
constexpr int kMaxComponents = 64;

// a + b = x + y exactly, with x = fl(a + b) (Knuth's TwoSum, no precondition on magnitudes).
inline void two_sum(double a, double b, double& x, double& y) {
  x = a + b;
  const double bv = x - a;
  const double av = x - bv;
  y = (a - av) + (b - bv);
}

// Adds b to the nonoverlapping expansion e[0..m) (increasing magnitude), in place; returns the
// new length m + 1. The result is nonoverlapping, so its sign is that of its last nonzero part.
inline int grow_expansion(double* e, int m, double b) {
  double q = b;
  for (int i = 0; i < m; ++i) {
    double sum, err;
    two_sum(q, e[i], sum, err);
    e[i] = err;
    q = sum;
  }
  e[m] = q;
  return m + 1;
}

inline int expansion_sign(const double* e, int m) {
  for (int i = m - 1; i >= 0; --i) {
    if (e[i] > 0) return 1;
    if (e[i] < 0) return -1;
  }
  return 0;
}

inline int sign(double v) { return (v > 0) - (v < 0); }

[[noreturn]] void too_many_terms(int n) {
  std::fprintf(stderr, "exact_predicates: %d terms exceed the fixed limit %d\n", n, kMaxComponents);
  std::abort();
}

}  // namespace

int exact_sign_of_sum(const double* terms, int n) {
  if (n > kMaxComponents) too_many_terms(n);
  // Filter: recursive summation errs by at most (n - 1) eps sum|t| (Higham, eq. 4.4).
  double s = 0, mag = 0;
  for (int i = 0; i < n; ++i) {
    s += terms[i];
    mag += std::fabs(terms[i]);
  }
  if (std::fabs(s) > 2.0 * (n + 1) * kEps * mag) return sign(s);
  double e[kMaxComponents];
  int m = 0;
  for (int i = 0; i < n; ++i) m = grow_expansion(e, m, terms[i]);
  return expansion_sign(e, m);
}

int exact_sign_of_dot_plus(const double* a, const double* b, int n_products, const double* c,
                           int n_terms) {
  if (2 * n_products + n_terms > kMaxComponents) too_many_terms(2 * n_products + n_terms);
  double s = 0, mag = 0;
  for (int i = 0; i < n_products; ++i) {
    const double p = a[i] * b[i];
    s += p;
    mag += std::fabs(p);
  }
  for (int i = 0; i < n_terms; ++i) {
    s += c[i];
    mag += std::fabs(c[i]);
  }
  if (std::fabs(s) > 2.0 * (n_products + n_terms + 2) * kEps * mag) return sign(s);
  // Exact: each product is split into its rounded value and its exact error (TwoProduct by FMA).
  double e[kMaxComponents];
  int m = 0;
  for (int i = 0; i < n_products; ++i) {
    const double p = a[i] * b[i];
    const double err = std::fma(a[i], b[i], -p);
    m = grow_expansion(e, m, p);
    m = grow_expansion(e, m, err);
  }
  for (int i = 0; i < n_terms; ++i) m = grow_expansion(e, m, c[i]);
  return expansion_sign(e, m);
}

int orient2d(Vec2 a, Vec2 b, Vec2 c) {
  const double left = (b.x - a.x) * (c.y - a.y);
  const double right = (b.y - a.y) * (c.x - a.x);
  const double det = left - right;
  // Shewchuk's ccwerrboundA = (3 + 16 eps) eps.
  const double bound = (3.0 + 16.0 * kEps) * kEps * (std::fabs(left) + std::fabs(right));
  if (std::fabs(det) > bound) return sign(det);
  // (bx-ax)(cy-ay) - (by-ay)(cx-ax) expanded; the ax*ay terms cancel.
  const double pa[6] = {b.x, -b.x, -a.x, -b.y, b.y, a.y};
  const double pb[6] = {c.y, a.y, c.y, c.x, a.x, c.x};
  return exact_sign_of_dot_plus(pa, pb, 6, nullptr, 0);
}

}  // namespace ra::geometry
