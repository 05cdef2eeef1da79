// The floating-point allowance of window coordinates (window_error.h) against an independent
// computation: Python's exact rationals (fractions) evaluate the GL pipeline with every result
// perturbed by its relative error, find the worst placement of the perturbations (to first order
// the error is linear in them: each one's sign is taken from its own effect, measured exactly),
// and the derived bound must hold it (sound) without exceeding it fourfold (tight). Cases near the
// near plane, where the rule of "eps times the largest window coordinate" and this one disagree.
#include "metrics/window_error.h"

#include <gtest/gtest.h>

#include <cmath>

#include "geometry/clipping.h"
#include "stats/stats_testing.h"

namespace ra::metrics {
namespace {

// The pipeline in rationals. Each rounding is one named perturbation: a result r of an operation
// with terms t_i becomes r + d * sum |t_i| (a dot product, one result) or r * (1 + d) (one
// operation), d in [-eps, eps]. `order` "two-stage": eye = V v, clip = P eye; "premultiplied":
// M = P V, clip = M v. Returns the worst |dX| and |dY| (px) of the near clip of a -> b (or of a
// alone when b is None).
const char* kWorstCase = R"PY(
from fractions import Fraction as F
eps = F(inp['eps'])
V = [F(x) for x in inp['V']]; P = [F(x) for x in inp['P']]   # column-major 4x4
W, H = inp['W'], inp['H']
def at(M, r, c): return M[c * 4 + r]
def pipeline(d, order, a, b):
    n = [0]
    def rnd(value, scale):   # one rounding: the next perturbation times its scale
        k = n[0]; n[0] += 1
        return value + d.get(k, 0) * scale
    def dot(row, vec):
        terms = [x * y for x, y in zip(row, vec)]
        return rnd(sum(terms), sum(abs(t) for t in terms))
    def clip(p):
        v = [F(p[0]), F(p[1]), F(p[2]), F(1)]
        if order == 'two-stage':
            eye = [dot([at(V, i, j) for j in range(4)], v) for i in range(4)]
            return [dot([at(P, k, i) for i in range(4)], eye) for k in range(4)]
        M = [[dot([at(P, k, i) for i in range(4)], [at(V, i, j) for i in range(4)])
              for j in range(4)] for k in range(4)]
        return [dot(M[k], v) for k in range(4)]
    def op(value): return rnd(value, abs(value))
    ca = clip(a)
    if b is None:
        q = ca
    else:
        cb = clip(b)
        da = op(ca[2] + ca[3]); db = op(cb[2] + cb[3])
        t = op(da / op(da - db))
        q = [op(ca[k] + op(t * op(cb[k] - ca[k]))) for k in range(4)]
    nx = op(q[0] / q[3]); ny = op(q[1] / q[3])
    X = op(op(nx + 1) * F(W, 2)); Y = op(op(ny + 1) * F(H, 2))
    return X, Y, n[0]
def worst(order, a, b):
    X0, Y0, count = pipeline({}, order, a, b)
    out = []
    for axis in (0, 1):
        signs = {}
        for k in range(count):   # each perturbation's own effect, exactly
            moved = pipeline({k: eps}, order, a, b)[axis] - (X0, Y0)[axis]
            signs[k] = eps if moved >= 0 else -eps
        out.append(float(abs(pipeline(signs, order, a, b)[axis] - (X0, Y0)[axis])))
    return out
out = {}
for name, case in inp['cases'].items():
    out[name] = {o: worst(o, case['a'], case.get('b')) for o in ('two-stage', 'premultiplied')}
)PY";

std::vector<double> column_major(const geometry::Mat4& m) { return {m.m.begin(), m.m.end()}; }

struct Case {
  const char* name;
  const geometry::View* view;
  geometry::Vec3 a, b;
  bool clipped;  // b behind the near plane: the vertex is a's edge's near intersection
};

TEST(WindowError, TheDerivedBoundHoldsTheWorstCaseOfARationalPipelineAndIsTight) {
  // Near planes at 10^-3 and at the paper's 0.01; edges crossing them near the axis (a cut vertex
  // inside the window) and far from it (a cut vertex far outside); unclipped vertices, one just in
  // front of a near plane at 10^-5 (window x ~ 4e7 px).
  const geometry::View close = geometry::make_view(30, 907, 907, 1e-3, 10.0);
  const geometry::View paper =
      geometry::make_view(150, 128, 128, 0.01, 10.0, geometry::rotation_from_euler_deg(20, -10, 5));
  const geometry::View tiny = geometry::make_view(30, 907, 907, 1e-5, 10.0);
  const std::vector<Case> cases = {
      {"axis_close_near", &close, {0.02, -0.01, -2.0}, {-0.01, 0.005, 1.0}, true},
      {"far_close_near", &close, {-0.2, -0.2, -2.0}, {0.5, 0.5, 1.0}, true},
      {"paper_near", &paper, {0.3, 0.2, -0.9}, {-0.1, 0.4, 0.8}, true},
      {"unclipped_paper", &paper, {-0.4, 0.3, -0.7}, {}, false},
      {"unclipped_in_window", &tiny, {0.3, -0.2, -1.5}, {}, false},
      {"unclipped_far_outside", &tiny, {0.5, 0.3, -2e-5}, {}, false},
  };
  for (const geometry::View* v : {&close, &paper, &tiny}) {
    nlohmann::json in;
    in["eps"] = kFloatRelativeError;
    in["W"] = v->width;
    in["H"] = v->height;
    in["V"] = column_major(v->view_matrix);
    in["P"] = column_major(v->projection);
    for (const Case& c : cases) {
      if (c.view != v) continue;
      nlohmann::json one = {{"a", {c.a.x, c.a.y, c.a.z}}};
      if (c.clipped) one["b"] = {c.b.x, c.b.y, c.b.z};
      in["cases"][c.name] = one;
    }
    const nlohmann::json out = stats::testing::run_scipy(kWorstCase, in);
    for (const Case& c : cases) {
      if (c.view != v) continue;
      const ClipWithError a = clip_with_error(*v, c.a);
      ASSERT_GT(a.c.w, 0) << c.name;
      const ClipWithError q = c.clipped ? near_intersection_with_error(a, clip_with_error(*v, c.b))
                                        : a;
      const AllowedVertex ours = window_vertex(q, v->width, v->height);
      const double bound = ours.allowance - kSnapAllowancePx;
      double worst = 0;
      for (const char* order : {"two-stage", "premultiplied"})
        for (int axis = 0; axis < 2; ++axis)
          worst = std::max(worst, out[c.name][order][axis].get<double>());
      SCOPED_TRACE(std::string(c.name) + ": bound " + std::to_string(bound) + " px, worst " +
                   std::to_string(worst) + " px, at window (" + std::to_string(ours.p.x) + ", " +
                   std::to_string(ours.p.y) + ")");
      EXPECT_GT(worst, 0);
      EXPECT_GE(bound, worst);      // sound
      EXPECT_LE(bound, 4 * worst);  // and not loose (t moves x and w together; the bound adds them)
    }
  }
}

TEST(WindowError, ACutVertexNearTheAxisMovesFarMoreThanEpsTimesItsCoordinate) {
  // The rule this replaces allowed eps * max(|X|, W): 0.009 px here. The near clip of a long
  // edge at 10^-3 computes w from a difference of numbers a thousand times larger: the cut vertex
  // may move by pixels although it lies near the window's centre.
  const geometry::View view = geometry::make_view(30, 907, 907, 1e-3, 10.0);
  const ClipWithError a = clip_with_error(view, {0.02, -0.01, -2.0});
  const ClipWithError b = clip_with_error(view, {-0.01, 0.005, 1.0});
  const AllowedVertex q = window_vertex(near_intersection_with_error(a, b), 907, 907);
  EXPECT_NEAR(q.p.x, 453.5, 30);  // near the window's centre
  EXPECT_NEAR(q.p.y, 453.5, 30);
  EXPECT_GT(q.allowance, 20 * conformance_allowance(0, 907, 907));
  EXPECT_TRUE(std::isfinite(q.allowance));
  // At 10^-5 the error of w at the cut exceeds w itself: nothing bounds the vertex.
  const geometry::View tiny = geometry::make_view(30, 907, 907, 1e-5, 10.0);
  const AllowedVertex t = window_vertex(
      near_intersection_with_error(clip_with_error(tiny, {0.02, -0.01, -2.0}),
                                   clip_with_error(tiny, {-0.01, 0.005, 1.0})),
      907, 907);
  EXPECT_TRUE(std::isinf(t.allowance));
}

TEST(WindowError, AVertexInsideTheWindowKeepsASmallAllowanceWhateverItsEdgesReach) {
  // The third vertex lies just in front of a near plane at 10^-5, ~4e7 px to the right. The old
  // rule gave every vertex eps * 4e7 = 400 px; the vertices inside the window keep ~0.1 px.
  const geometry::View view = geometry::make_view(30, 907, 907, 1e-5, 10.0);
  geometry::Primitive t;
  t.kind = geometry::Kind::kTriangle;
  t.v = {geometry::Vec3{-0.02, -0.02, -0.5}, geometry::Vec3{0.02, -0.02, -0.5},
         geometry::Vec3{0.5, 0.3, -2e-5}};
  const std::vector<AllowedVertex> v = near_clipped_vertices(view, t);
  ASSERT_EQ(v.size(), 3u);  // nothing crosses the near plane
  EXPECT_LT(v[0].allowance, 0.1);
  EXPECT_LT(v[1].allowance, 0.1);
  EXPECT_GT(v[2].p.x, 1e7);
  EXPECT_GT(v[2].allowance, 10);
  EXPECT_TRUE(std::isfinite(v[2].allowance));
}

TEST(WindowError, NothingInFrontOfTheNearPlaneGivesNoVertexAndNonFiniteInputNone) {
  const geometry::View view = geometry::make_view(60, 64, 64);
  geometry::Primitive behind;
  behind.kind = geometry::Kind::kLine;
  behind.v = {geometry::Vec3{0, 0, 1}, geometry::Vec3{0.1, 0, 2}, geometry::Vec3{}};
  EXPECT_TRUE(near_clipped_vertices(view, behind).empty());
  geometry::Primitive bad = behind;
  bad.v[0] = {NAN, 0, -1};
  EXPECT_TRUE(near_clipped_vertices(view, bad).empty());
}

}  // namespace
}  // namespace ra::metrics
