// The exact reference rasterizer: GL point, diamond-exit line and top-left polygon rules, against
// hand-derived cases and exact rational oracles (rational_oracle_test.h).
#include "geometry/reference_rasterizer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <map>
#include <random>

#include "geometry/rational_oracle_test.h"

namespace ra::geometry {
namespace {

View make_view(double fov, int size) { return ra::geometry::make_view(fov, size, size); }

// ---- Points ----

// A point lights the pixel containing it; on a pixel boundary, the pixel right of / above it
// (floor); outside the clip volume nothing, also behind the camera where x/w would land on screen.
TEST(ReferencePoint, PixelContainingThePoint) {
  // Window x = (x/w + 1) * 5 in a 10 x 10 window.
  EXPECT_EQ(rasterize_point(Vec4{0.05, -0.05, 0, 1}, 10, 10), (PixelSet{{5, 4}}));
  EXPECT_EQ(rasterize_point(Vec4{-0.4, 0.2, 0, 1}, 10, 10), (PixelSet{{3, 6}}));  // x = 3.0
  EXPECT_TRUE(rasterize_point(Vec4{1.2, 0, 0, 1}, 10, 10).empty());
  EXPECT_TRUE(rasterize_point(Vec4{0, 0, 0.5, -1}, 10, 10).empty());  // behind the camera
  EXPECT_TRUE(rasterize_point(Vec4{1, 0, 0, 1}, 10, 10).empty());     // on the plane: GL drops it
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(rasterize_point(Vec4{nan, 0, 0, 1}, 10, 10).empty());
}

// ---- Lines: the diamond-exit rule ----

// Centre to centre: the start pixel is lit, the end pixel is not (it ends inside its diamond).
TEST(ReferenceLine, CentreToCentre) {
  EXPECT_EQ(rasterize_segment({0.5, 0.5}, {4.5, 0.5}, 10, 10),
            (PixelSet{{0, 0}, {1, 0}, {2, 0}, {3, 0}}));
  EXPECT_EQ(rasterize_segment({4.5, 0.5}, {0.5, 0.5}, 10, 10),
            (PixelSet{{1, 0}, {2, 0}, {3, 0}, {4, 0}}));
}

// Along the boundary y = 1 between two rows, through diamond corners: the spec's perturbation
// (-e, -e^2) moves it below, into row 0. Along x = 2 between two columns: into column 1.
TEST(ReferenceLine, AlongPixelBoundaries) {
  EXPECT_EQ(rasterize_segment({0.5, 1}, {4.5, 1}, 10, 10),
            (PixelSet{{0, 0}, {1, 0}, {2, 0}, {3, 0}}));
  EXPECT_EQ(rasterize_segment({2, 0.5}, {2, 4.5}, 10, 10),
            (PixelSet{{1, 0}, {1, 1}, {1, 2}, {1, 3}}));
}

// A 45-degree segment running exactly along diamond sides (y = x - 1/2): the perturbation lifts it
// into the diamonds above-left, (k, k); the same pixels in both directions.
TEST(ReferenceLine, AlongDiamondSides) {
  const PixelSet expect = {{0, 0}, {1, 1}, {2, 2}, {3, 3}};
  EXPECT_EQ(rasterize_segment({0.5, 0}, {4.5, 4}, 10, 10), expect);
  EXPECT_EQ(rasterize_segment({4.5, 4}, {0.5, 0}, 10, 10), expect);
}

// A zero-length segment exits no diamond: nothing. A segment wholly inside one diamond: nothing.
TEST(ReferenceLine, ZeroLengthAndInsideOneDiamond) {
  EXPECT_TRUE(rasterize_segment({3.3, 3.4}, {3.3, 3.4}, 10, 10).empty());
  EXPECT_TRUE(rasterize_segment({3.4, 3.5}, {3.6, 3.5}, 10, 10).empty());
  // Starting inside a diamond and leaving it for the next one, where it ends: the first only.
  EXPECT_EQ(rasterize_segment({3.4, 3.5}, {4.05, 3.5}, 10, 10), (PixelSet{{3, 3}}));
}

// An x-major segment lights one pixel per column it exits: centre to centre over dx = 7 columns
// gives 7 pixels, one in each of the columns 0..6.
TEST(ReferenceLine, XMajorOnePixelPerColumn) {
  const PixelSet s = rasterize_segment({0.5, 0.5}, {7.5, 3.5}, 10, 10);
  ASSERT_EQ(s.size(), 7u);
  std::map<int, int> per_column;
  for (const Pixel& p : s) ++per_column[p.x];
  for (int x = 0; x < 7; ++x) EXPECT_EQ(per_column[x], 1);
}

// The rule against a literal rational evaluation with a concrete tiny perturbation (2^-30, far
// below the 1/8 grid of the coordinates, so it stands for the infinitesimal), on coordinates full
// of ties: ends on centres, diamond sides and corners, pixel edges. Every pixel of the window.
TEST(ReferenceLine, MatchesRationalOracleOnTies) {
  std::mt19937_64 rng(7);
  std::uniform_int_distribution<int> u(-8, 12 * 8);
  const oracle::Q eps = oracle::Q(1) / oracle::Q(1LL << 30);
  for (int t = 0; t < 150; ++t) {
    Vec2 a{u(rng) / 8.0, u(rng) / 8.0}, b{u(rng) / 8.0, u(rng) / 8.0};
    if (t % 4 == 0) b.y = a.y;                     // horizontal
    if (t % 4 == 1) b.x = a.x;                     // vertical
    if (t % 4 == 2) b = {a.x + (b.y - a.y), b.y};  // 45 degrees
    const PixelSet got = rasterize_segment(a, b, 12, 12);
    PixelSet expect;
    for (int y = 0; y < 12; ++y)
      for (int x = 0; x < 12; ++x)
        if (oracle::diamond_fragment(a, b, {x, y}, eps)) expect.append_run(y, x, x + 1);
    ASSERT_EQ(got, expect) << "segment (" << a.x << "," << a.y << ") -> (" << b.x << "," << b.y
                           << ")";
  }
}

// The column walk finds exactly the pixels of the exact predicate over the whole window, for
// random double segments (including clipped ones on the border).
TEST(ReferenceLine, WalkEqualsPredicateEverywhere) {
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(-3, 35);
  for (int t = 0; t < 300; ++t) {
    Vec2 a{u(rng), u(rng)}, b{u(rng), u(rng)};
    if (t % 5 == 0) a.x = 0;  // on the window border, as after clipping
    const PixelSet got = rasterize_segment(a, b, 32, 32);
    PixelSet expect;
    for (int y = 0; y < 32; ++y)
      for (int x = 0; x < 32; ++x)
        if (diamond_exit_fragment(a, b, {x, y})) expect.append_run(y, x, x + 1);
    ASSERT_EQ(got, expect);
  }
}

// ---- Polygons: centre sampling with the top-left rule ----

// Two triangles splitting a square along its diagonal through pixel centres: every centre of the
// square is lit exactly once, the diagonal's centres included.
TEST(ReferencePolygon, SharedDiagonalLitOnce) {
  const PixelSet lower = rasterize_convex_polygon({{0, 0}, {4, 0}, {4, 4}}, 10, 10);
  const PixelSet upper = rasterize_convex_polygon({{0, 0}, {4, 4}, {0, 4}}, 10, 10);
  EXPECT_EQ(symmetric_difference_size(lower, upper), int64_t(lower.size() + upper.size()));
  PixelSet all = lower;
  for (const Pixel& p : upper) all.insert(p);
  EXPECT_EQ(all.size(), 16u);
  EXPECT_EQ(lower.size() + upper.size(), 16u);
}

// Hand-derived top-left cases, y up: a square with edges through pixel centres lights the centres
// on its left and top edges, not those on its right and bottom edges.
TEST(ReferencePolygon, TopLeftRuleByHand) {
  // Square [0.5, 2.5] x [0.5, 2.5]: centres x, y in {0.5, 1.5, 2.5}.
  const PixelSet s =
      rasterize_convex_polygon({{0.5, 0.5}, {2.5, 0.5}, {2.5, 2.5}, {0.5, 2.5}}, 5, 5);
  // Left edge x = 0.5 is in, right edge x = 2.5 out; top y = 2.5 in, bottom y = 0.5 out.
  EXPECT_EQ(s, (PixelSet{{0, 1}, {1, 1}, {0, 2}, {1, 2}}));
  // A triangle whose top vertex is a centre: that centre is not lit (its right edge excludes it).
  const PixelSet t = rasterize_convex_polygon({{0.5, 0.5}, {4.5, 0.5}, {2.5, 2.5}}, 5, 5);
  EXPECT_EQ(std::count(t.begin(), t.end(), Pixel{2, 2}), 0);
  EXPECT_EQ(std::count(t.begin(), t.end(), Pixel{2, 1}), 1);
}

// A mesh of triangles with vertices on pixel centres and pixel edges (a 1.5-pixel grid with both
// diagonal directions): the triangles' pixel sets are disjoint and together equal the rasterization
// of the whole rectangle; no gaps, no double lighting, shared vertices on centres included.
TEST(ReferencePolygon, MeshLightsEveryCentreOnce) {
  std::mt19937_64 rng(1);
  const int n = 8;
  const double s = 1.5, o = 0.5;
  std::vector<int> count(40 * 40, 0);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const Vec2 p00{o + s * i, o + s * j}, p10{o + s * (i + 1), o + s * j};
      const Vec2 p01{o + s * i, o + s * (j + 1)}, p11{o + s * (i + 1), o + s * (j + 1)};
      std::vector<std::vector<Vec2>> tris;
      if (rng() % 2)
        tris = {{p00, p10, p11}, {p00, p11, p01}};
      else
        tris = {{p00, p10, p01}, {p10, p11, p01}};
      for (const auto& t : tris)
        for (const Pixel& p : rasterize_convex_polygon(t, 40, 40)) ++count[p.y * 40 + p.x];
    }
  const double hi = o + s * n;
  const PixelSet whole = rasterize_convex_polygon({{o, o}, {hi, o}, {hi, hi}, {o, hi}}, 40, 40);
  std::vector<int> expect(40 * 40, 0);
  for (const Pixel& p : whole) expect[p.y * 40 + p.x] = 1;
  EXPECT_EQ(count, expect);
}

// A fan of triangles around a vertex exactly on a pixel centre: that centre lit exactly once.
TEST(ReferencePolygon, FanAroundACentre) {
  const Vec2 c{10.5, 10.5};
  const std::vector<Vec2> ring = {{14.5, 10.5}, {13, 14}, {10.5, 14.5}, {7, 13},
                                  {6.5, 10.5},  {8, 7},   {10.5, 6.5},  {14, 7.5}};
  std::vector<int> count(20 * 20, 0);
  for (size_t k = 0; k < ring.size(); ++k)
    for (const Pixel& p :
         rasterize_convex_polygon({c, ring[k], ring[(k + 1) % ring.size()]}, 20, 20))
      ++count[p.y * 20 + p.x];
  EXPECT_EQ(count[10 * 20 + 10], 1);
  for (int v : count) EXPECT_LE(v, 1);
}

// Against the exact rational sampling oracle, every pixel of a 20 x 20 window: random triangles on
// a 1/4 grid (vertices on centres, edges through centres) and random double triangles.
TEST(ReferencePolygon, MatchesRationalOracle) {
  std::mt19937_64 rng(13);
  std::uniform_int_distribution<int> g(-4, 22 * 4);
  std::uniform_real_distribution<double> u(-2, 22);
  for (int t = 0; t < 120; ++t) {
    std::vector<Vec2> tri;
    for (int k = 0; k < 3; ++k)
      tri.push_back(t % 2 ? Vec2{g(rng) / 4.0, g(rng) / 4.0} : Vec2{u(rng), u(rng)});
    const PixelSet got = rasterize_convex_polygon(tri, 20, 20);
    const auto q = oracle::to_q(tri);
    PixelSet expect;
    for (int y = 0; y < 20; ++y)
      for (int x = 0; x < 20; ++x)
        if (oracle::covers_centre(
                q, {oracle::Q(x) + oracle::Q(1) / 2, oracle::Q(y) + oracle::Q(1) / 2}))
          expect.append_run(y, x, x + 1);
    ASSERT_EQ(got, expect) << "triangle " << t;
  }
}

// Slivers (area < 1e-6 px^2) and degenerate triangles: exactly the centres the oracle covers
// (usually none); collinear or repeated vertices: nothing.
TEST(ReferencePolygon, SliversAndDegenerates) {
  const std::vector<Vec2> sliver = {{0.5, 0.5}, {15.5, 10.5}, {15.5 + 1e-9, 10.5}};
  const auto q = oracle::to_q(sliver);
  PixelSet expect;
  for (int y = 0; y < 20; ++y)
    for (int x = 0; x < 20; ++x)
      if (oracle::covers_centre(q,
                                {oracle::Q(x) + oracle::Q(1) / 2, oracle::Q(y) + oracle::Q(1) / 2}))
        expect.append_run(y, x, x + 1);
  EXPECT_EQ(rasterize_convex_polygon(sliver, 20, 20), expect);
  EXPECT_TRUE(rasterize_convex_polygon({{0.5, 0.5}, {2.5, 2.5}, {4.5, 4.5}}, 10, 10).empty());
  EXPECT_TRUE(rasterize_convex_polygon({{1, 1}, {1, 1}, {4, 2}}, 10, 10).empty());
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(rasterize_convex_polygon({{1, 1}, {nan, 1}, {4, 2}}, 10, 10).empty());
}

// The row walk decides most pixels in double arithmetic, with a certified error bound, and only
// near-ties exactly. Against the exact test at every pixel centre (polygon_covers_sample on the
// hull): vertices within a few ulp of centres and of pixel edges, edges a ulp from passing through
// a centre, near-horizontal edges (dy 1e-12), and vertices far outside the window (1e7 px).
TEST(ReferencePolygon, CertifiedRowsEqualExactTestNearTies) {
  std::mt19937_64 rng(5);
  std::uniform_int_distribution<int> cell(-2, 42), ulps(-3, 3), pick(0, 4);
  std::uniform_real_distribution<double> u(-5, 45), far(-1e7, 1e7);
  auto near_tie = [&](double v) {  // v moved by a few ulp, or by 1e-12, or not at all
    switch (pick(rng)) {
      case 0: return v;
      case 1: return v + 1e-12 * ulps(rng);
      default: {
        int k = ulps(rng);
        while (k > 0) v = std::nextafter(v, INFINITY), --k;
        while (k < 0) v = std::nextafter(v, -INFINITY), ++k;
        return v;
      }
    }
  };
  int polygons = 0, lit = 0;
  for (int t = 0; t < 600; ++t) {
    std::vector<Vec2> poly;
    const int n = 3 + t % 3;
    for (int k = 0; k < n; ++k) {
      const double half = pick(rng) < 3 ? 0.5 : 0.0;  // a centre or a pixel corner
      Vec2 v{near_tie(cell(rng) + half), near_tie(cell(rng) + half)};
      if (t % 7 == 0) v = {u(rng), u(rng)};
      if (t % 11 == 0 && k == 0) v = {far(rng), far(rng)};
      poly.push_back(v);
    }
    if (t % 5 == 0) poly[1] = {poly[0].x + 17.25, near_tie(poly[0].y + 1e-12)};  // nearly flat
    const std::vector<Vec2> hull = convex_hull(poly);
    if (hull.size() < 3) continue;
    ++polygons;
    PixelSet expect;
    for (int y = 0; y < 40; ++y)
      for (int x = 0; x < 40; ++x)
        if (polygon_covers_sample(hull, {x + 0.5, y + 0.5})) expect.append_run(y, x, x + 1);
    lit += int(expect.size());
    ASSERT_EQ(rasterize_convex_polygon(poly, 40, 40), expect) << "polygon " << t;
  }
  EXPECT_GT(polygons, 500);
  EXPECT_GT(lit, 10000);  // the cases light pixels, not only empty windows
  // Edges so flat that their slope overflows (dy = 5e-324, the smallest double), through a
  // centre row: the exact test decides those rows.
  const double tiny = std::numeric_limits<double>::denorm_min();
  for (const std::vector<Vec2>& poly : std::vector<std::vector<Vec2>>{
           {{0, 0}, {30, tiny}, {15, 20}},
           {{2, 0.5}, {30, 0.5 - tiny}, {15, 20}},
           {{30, 0.5}, {2, 0.5 + tiny}, {15, -20}}}) {
    const std::vector<Vec2> hull = convex_hull(poly);
    PixelSet expect;
    for (int y = 0; y < 40; ++y)
      for (int x = 0; x < 40; ++x)
        if (polygon_covers_sample(hull, {x + 0.5, y + 0.5})) expect.append_run(y, x, x + 1);
    EXPECT_FALSE(expect.empty());
    EXPECT_EQ(rasterize_convex_polygon(poly, 40, 40), expect);
  }
}

// Both faces: the orientation of the input does not change the pixels.
TEST(ReferencePolygon, BothFaces) {
  const View v = make_view(30, 128);
  const Vec3 a{0.05, 0.02, -0.5}, b{-0.04, 0.03, -0.6}, c{0.01, -0.05, -0.4};
  const ClippedPolygon front = clip_triangle(v, a, b, c), back = clip_triangle(v, a, c, b);
  EXPECT_EQ(front.orientation, -back.orientation);
  const PixelSet f = rasterize_polygon(front, 128, 128);
  EXPECT_FALSE(f.empty());
  EXPECT_EQ(f, rasterize_polygon(back, 128, 128));
}

// Triangles crossing the near plane in a 150-degree view, against the rational oracle applied to
// the clipped polygon over the whole 128 x 128 window.
TEST(ReferencePolygon, ClippedTrianglesMatchOracle) {
  const View v = make_view(150, 128);
  std::mt19937_64 rng(21);
  std::uniform_real_distribution<double> u(-1, 1);
  int tested = 0;
  for (int t = 0; t < 200 && tested < 4; ++t) {
    const Vec3 a{u(rng), u(rng), -0.3}, b{u(rng), u(rng), 0.3}, c{u(rng), u(rng), u(rng)};
    const ClippedPolygon p = clip_triangle(v, a, b, c);
    if (p.status != ClipStatus::kVisible || p.area < 50) continue;
    ++tested;
    const auto q = oracle::to_q(p.vertices);
    PixelSet expect;
    for (int y = 0; y < 128; ++y)
      for (int x = 0; x < 128; ++x)
        if (oracle::covers_centre(
                q, {oracle::Q(x) + oracle::Q(1) / 2, oracle::Q(y) + oracle::Q(1) / 2}))
          expect.append_run(y, x, x + 1);
    EXPECT_EQ(rasterize_polygon(p, 128, 128), expect);
  }
  EXPECT_EQ(tested, 4);
}

// A triangle covering the window of a 150-degree view lights every pixel, in (y, x) order.
TEST(ReferencePolygon, FullWindow) {
  const View v = make_view(150, 128);
  Primitive prim;
  prim.kind = Kind::kTriangle;
  prim.v = {Vec3{-50, -30, -1}, Vec3{50, -30, -1}, Vec3{0, 60, -1}};
  const PixelSet s = rasterize_reference(v, prim);
  ASSERT_EQ(s.size(), 128u * 128u);
  EXPECT_TRUE(std::is_sorted(s.begin(), s.end()));
}

// Subpixel snapping: round to the 2^-b grid, ties to even; rasterizing with b bits equals
// rasterizing the snapped vertices exactly.
TEST(ReferenceSnap, SnapsToTheGrid) {
  EXPECT_EQ(snap_to_subpixel(0.49, 4), 0.5);
  EXPECT_EQ(snap_to_subpixel(0.03125, 4), 0.0);    // 0.5 / 16: tie to even
  EXPECT_EQ(snap_to_subpixel(0.09375, 4), 0.125);  // 1.5 / 16: tie to even
  EXPECT_EQ(snap_to_subpixel(0.49, 0), 0.49);
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> u(0, 30);
  for (int t = 0; t < 50; ++t) {
    const std::vector<Vec2> tri = {{u(rng), u(rng)}, {u(rng), u(rng)}, {u(rng), u(rng)}};
    std::vector<Vec2> snapped;
    for (const Vec2& p : tri)
      snapped.push_back({snap_to_subpixel(p.x, 4), snap_to_subpixel(p.y, 4)});
    EXPECT_EQ(rasterize_convex_polygon(tri, 32, 32, 4), rasterize_convex_polygon(snapped, 32, 32));
    EXPECT_EQ(rasterize_segment(tri[0], tri[1], 32, 32, 4),
              rasterize_segment(snapped[0], snapped[1], 32, 32));
  }
}

// The Primitive entry point is clip + project + the rules above.
TEST(ReferencePrimitive, DispatchesByKind) {
  const View v = make_view(30, 128);
  std::mt19937_64 rng(8);
  std::uniform_real_distribution<double> u(-0.2, 0.2);
  for (int t = 0; t < 20; ++t) {
    Primitive line;
    line.kind = Kind::kLine;
    line.v = {Vec3{u(rng), u(rng), -0.5}, Vec3{u(rng), u(rng), -0.8}, Vec3{}};
    EXPECT_EQ(rasterize_reference(v, line),
              rasterize_segment(clip_segment(v, line.v[0], line.v[1]), 128, 128));
    Primitive point;
    point.kind = Kind::kPoint;
    point.v[0] = {0.5 * line.v[0].x, 0.5 * line.v[0].y, -0.5};  // inside the view
    EXPECT_EQ(rasterize_reference(v, point).size(), 1u);
  }
}

}  // namespace
}  // namespace ra::geometry
