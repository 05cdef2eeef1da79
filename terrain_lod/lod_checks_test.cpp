// Tests of the refinement, the strips and the verification checks (lod_refinement.h,
// lod_checks.h): the checks pass on the real LOD and fail on deliberately broken ones.
#include "terrain_lod/lod_checks.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "terrain_lod/lod_test_util.h"

namespace ra::lod {
namespace {

using testing::random_viewpoints;
using testing::test_camera;
using testing::test_field;

struct FrameCheck {
  bool conforming = false, seams_ok = false;
  double max_px = 0;
  size_t triangles = 0;
};

FrameCheck check_frame(const TerrainHierarchy& h, LambdaKind kind, double tau,
                       const scenes::Viewpoint& vp) {
  const scenes::CameraSettings cam = test_camera();
  const LodMesh mesh = refine(h, make_metric(kind, cam, tau, vp.eye));
  FrameCheck c;
  c.conforming = check_conformity(all_triangles(mesh), h.field().nx, h.field().ny).conforming;
  c.seams_ok = check_seams(mesh, h).ok;
  c.max_px = measure_screen_error(lod_surface_heights(mesh, h.field()), h.field(), cam, vp).max_px;
  c.triangles = mesh.triangle_count();
  return c;
}

TEST(LambdaFor, AnalyticValues) {
  scenes::CameraSettings cam;
  cam.width = 1024;
  cam.height = 768;
  cam.fov_y_deg = 60;
  const double f = 384 / std::tan(M_PI / 6);  // 665.1 pixels
  EXPECT_NEAR(lambda_for(LambdaKind::kPlanar, cam), f, 1e-9);
  EXPECT_NEAR(lambda_for(LambdaKind::kSpherical, cam), 1024 / (2 * std::atan(512 / f)), 1e-9);
  EXPECT_NEAR(lambda_for(LambdaKind::kWindow, cam), (f * f + 512 * 512 + 384 * 384) / f, 1e-9);
  EXPECT_NEAR(lambda_for(LambdaKind::kWindow, cam) / f, 1.926, 1e-3);
  cam.width = cam.height = 100;  // square window, 90 degrees: f = 50, the planar lambda is w / 2
  cam.fov_y_deg = 90;
  EXPECT_NEAR(lambda_for(LambdaKind::kPlanar, cam), 50, 1e-9);
  EXPECT_NEAR(lambda_for(LambdaKind::kSpherical, cam), 100 / (M_PI / 2), 1e-9);
  EXPECT_NEAR(lambda_for(LambdaKind::kWindow, cam), 150, 1e-9);
}

TEST(ScreenErrorMetric, ActiveInsideTheBallAndMonotone) {
  const ScreenErrorMetric m = make_metric(LambdaKind::kPlanar, test_camera(), 1, {0, 0, 0});
  EXPECT_TRUE(m.active(0.1, 10, {5, 0, 0}));       // eye inside the ball
  EXPECT_FALSE(m.active(0.0, 10, {5, 0, 0}));      // but nothing to gain where eps = 0
  EXPECT_NEAR(m.rho(2, 10, {110, 0, 0}), m.lambda * 2 / 100, 1e-12);
  const ScreenErrorMetric w = make_metric(LambdaKind::kWindow, test_camera(), 1, {0, 0, 0});
  EXPECT_TRUE(w.active(2, 10, {11.5, 0, 0}));  // within eps of the ball: the segment may touch the eye
  EXPECT_NEAR(w.rho(2, 10, {112, 0, 0}), w.lambda * 2 * std::asin(0.01), 1e-12);
  EXPECT_GT(w.rho(2, 10, {112, 0, 0}), w.lambda * 2 / 100);  // more conservative than eps / D
}

TEST(Refinement, FlatTerrainIsTwoTrianglesPerTileAtAnyTau) {
  HeightField f;
  f.nx = f.ny = 2 * 32 + 1;
  f.spacing = 5;
  f.z.assign(size_t(f.nx) * f.ny, 42.0);
  TerrainHierarchy h(f, 33, ErrorPropagation::kNested);
  for (double tau : {1e-6, 1.0, 8.0})
    for (const geometry::Vec3 eye : {geometry::Vec3{160, 160, 42.5},
                                     geometry::Vec3{-100, 50, 300}}) {  // also inside every ball
      const LodMesh mesh = refine(h, make_metric(LambdaKind::kWindow, test_camera(), tau, eye));
      EXPECT_EQ(mesh.triangle_count(), 8u);
      EXPECT_TRUE(check_conformity(all_triangles(mesh), f.nx, f.ny).conforming);
    }
}

TEST(Refinement, TinyTauGivesTheFullGridAndEqualsFullResolution) {
  const HeightField f = test_field(33, 2, 1);
  TerrainHierarchy h(f, 33, ErrorPropagation::kNested);
  const LodMesh fine = refine(h, make_metric(LambdaKind::kPlanar, test_camera(), 1e-12, {100, 100, 2000}));
  EXPECT_EQ(fine.triangle_count(), size_t(2 * 2 * 32 * 32));
  EXPECT_EQ(fine.vertex_count(), size_t(f.nx) * f.ny);
  const LodMesh full = full_resolution(h);
  EXPECT_EQ(full.triangle_count(), size_t(2 * 2 * 32 * 32));
  EXPECT_TRUE(check_conformity(all_triangles(full), f.nx, f.ny).conforming);
  // the LOD surface of the full grid is the grid itself: no screen error at all
  const std::vector<double> z = lod_surface_heights(full, f);
  for (size_t g = 0; g < z.size(); ++g) ASSERT_NEAR(z[g], f.z[g], 1e-9);
}

TEST(Strip, DecodesToExactlyTheRefinedTriangles) {
  const HeightField f = test_field(65, 1, 1);
  TerrainHierarchy h(f, 65, ErrorPropagation::kNested);
  for (double tau : {0.5, 4.0, 1e-9}) {
    const LodMesh mesh = refine(h, make_metric(LambdaKind::kWindow, test_camera(), tau, {50, 80, 400}));
    const TileMesh& t = mesh.tiles[0];
    const std::vector<Triangle> decoded = decode_strip(t.strip);
    ASSERT_EQ(decoded.size(), t.triangles.size()) << "tau " << tau;
    auto canonical = [](Triangle x) {  // the rotation starting at the smallest vertex
      while (x[0] > x[1] || x[0] > x[2]) x = {x[1], x[2], x[0]};
      return x;
    };
    for (size_t k = 0; k < decoded.size(); ++k) EXPECT_EQ(canonical(decoded[k]), canonical(t.triangles[k])) << k;
    // strips earn their keep: well under 3 indices per triangle
    EXPECT_LT(double(t.strip.size()), 2.2 * double(t.triangles.size()) + 8) << "tau " << tau;
  }
}

TEST(Conformity, HandMadeTJunctionFails) {
  // a 3 x 3 grid (nx = ny = 3): left half two triangles, right half split at (2, 1) only on its
  // own side: vertex (2, 1)... is on the boundary; use the centre instead: the left pair keeps the
  // edge (1, 0)-(1, 2) whole while the right side uses vertex (1, 1) on it.
  const int nx = 3;
  auto g = [](int i, int j) { return uint32_t(j * 3 + i); };
  std::vector<Triangle> tris = {
      {g(0, 0), g(1, 0), g(1, 2)}, {g(0, 0), g(1, 2), g(0, 2)},           // left: edge (1,0)-(1,2) whole
      {g(1, 0), g(2, 0), g(1, 1)}, {g(2, 0), g(2, 2), g(1, 1)}, {g(2, 2), g(1, 2), g(1, 1)}};  // right: fan at (1,1)
  const ConformityResult bad = check_conformity(tris, nx, 3);
  EXPECT_FALSE(bad.conforming);
  EXPECT_EQ(bad.t_junctions, 1u);
  EXPECT_GE(bad.open_edges, 2u);
  EXPECT_TRUE(bad.area_matches);  // the area alone cannot see it
  // the same with the left side split at (1, 1) too conforms
  tris[0] = {g(0, 0), g(1, 0), g(1, 1)};
  tris[1] = {g(0, 0), g(1, 1), g(0, 2)};
  tris.push_back({g(0, 2), g(1, 1), g(1, 2)});
  const ConformityResult good = check_conformity(tris, nx, 3);
  EXPECT_TRUE(good.conforming) << good.first_problem;
  // a hole (a triangle left out) and a flipped triangle fail
  std::vector<Triangle> hole(tris.begin(), tris.end() - 1);
  EXPECT_FALSE(check_conformity(hole, nx, 3).conforming);
  std::vector<Triangle> flipped = tris;
  std::swap(flipped[2][0], flipped[2][1]);
  EXPECT_FALSE(check_conformity(flipped, nx, 3).conforming);
}

TEST(Checks, PassOnTheRealLodForManyViewpointsAndTau) {
  const HeightField f = test_field(33, 2, 2);
  TerrainHierarchy h(f, 33, ErrorPropagation::kNested);
  const size_t full = size_t(f.nx - 1) * (f.ny - 1) * 2;
  size_t reduced = 0;
  double worst_ratio = 0;
  for (const scenes::Viewpoint& vp : random_viewpoints(f, 40, 11))
    for (double tau : {0.5, 1.0, 3.0}) {
      const FrameCheck c = check_frame(h, LambdaKind::kWindow, tau, vp);
      EXPECT_TRUE(c.conforming);
      EXPECT_TRUE(c.seams_ok);
      EXPECT_LE(c.max_px, tau) << "eye " << vp.eye.x << " " << vp.eye.y << " " << vp.eye.z;
      worst_ratio = std::max(worst_ratio, c.max_px / tau);
      reduced += c.triangles < full;
    }
  EXPECT_GT(reduced, 60u);        // the LOD does drop triangles (not trivially the full grid)
  EXPECT_GT(worst_ratio, 0.2);    // and the check measures real deviations
}

TEST(Checks, ViewpointVeryCloseToTheSurfacePasses) {
  const HeightField f = test_field(33, 2, 2);
  TerrainHierarchy h(f, 33, ErrorPropagation::kNested);
  const int gi = 20, gj = 37;
  scenes::Viewpoint vp;
  vp.eye = {gi * f.spacing, gj * f.spacing, f.at(gi, gj) + 0.5};  // half a metre above a vertex
  vp.target = {vp.eye.x + 200, vp.eye.y + 50, vp.eye.z - 20};
  const FrameCheck c = check_frame(h, LambdaKind::kWindow, 1.0, vp);
  EXPECT_TRUE(c.conforming);
  EXPECT_TRUE(c.seams_ok);
  EXPECT_LE(c.max_px, 1.0);
}

TEST(Checks, FailOnUnnestedErrors) {
  const HeightField f = test_field(33, 2, 2);
  TerrainHierarchy h(f, 33, ErrorPropagation::kUnnested);
  int not_conforming = 0, over_tau = 0;
  for (const scenes::Viewpoint& vp : random_viewpoints(f, 20, 5)) {
    const FrameCheck c = check_frame(h, LambdaKind::kWindow, 1.0, vp);
    not_conforming += !c.conforming;
    over_tau += c.max_px > 1.0;
  }
  EXPECT_GT(not_conforming, 5);
  EXPECT_GT(over_tau, 5);
}

TEST(Checks, SeamCheckFailsWithoutEqualisedSeams) {
  // west tile flat (no error anywhere, so on its own it stays two triangles), east tile rough
  // away from the seam: only equalised seam errors make the west tile split along the seam
  HeightField f = test_field(33, 2, 1);
  for (int j = 0; j < f.ny; ++j)
    for (int i = 0; i <= 32; ++i) f.z[size_t(j * f.nx + i)] = 0;
  scenes::Viewpoint vp;
  vp.eye = {320, 160, 300};
  vp.target = {330, 170, 0};
  TerrainHierarchy raw(f, 33, ErrorPropagation::kNested, false);
  const FrameCheck broken = check_frame(raw, LambdaKind::kWindow, 1.0, vp);
  EXPECT_FALSE(broken.seams_ok);
  EXPECT_FALSE(broken.conforming);  // a seam crack is a crack of the whole mesh as well
  TerrainHierarchy h(f, 33, ErrorPropagation::kNested);
  const FrameCheck fixed = check_frame(h, LambdaKind::kWindow, 1.0, vp);
  EXPECT_TRUE(fixed.seams_ok);
  EXPECT_TRUE(fixed.conforming);
  EXPECT_LE(fixed.max_px, 1.0);
  // random viewpoints over the same terrain: the broken variant cracks, the real one never
  int bad = 0;
  for (const scenes::Viewpoint& v : random_viewpoints(f, 12, 9)) {
    bad += !check_frame(raw, LambdaKind::kWindow, 1.0, v).seams_ok;
    const FrameCheck c = check_frame(h, LambdaKind::kWindow, 1.0, v);
    EXPECT_TRUE(c.seams_ok && c.conforming);
  }
  EXPECT_GT(bad, 6);
}

TEST(ScreenError, ExcludesVerticesBehindTheNearPlane) {
  const HeightField f = test_field(33, 1, 1);
  TerrainHierarchy h(f, 33, ErrorPropagation::kNested);
  scenes::Viewpoint vp;
  vp.eye = {160, 160, 400};
  vp.target = {160, 400, 400};  // looking north, level: the southern half is behind the camera
  const LodMesh mesh = refine(h, make_metric(LambdaKind::kWindow, test_camera(), 1, vp.eye));
  const ScreenErrorResult r = measure_screen_error(lod_surface_heights(mesh, f), f, test_camera(), vp);
  EXPECT_GT(r.excluded, size_t(33 * 16));
  EXPECT_EQ(r.checked + r.excluded, size_t(33 * 33));
}

TEST(ScreenError, MeasuresTheVisiblePartOfASegmentCrossingTheWindowEdge) {
  // 100 x 100 window, 90 degrees: f = 50 px. The eye 100 m south of vertex 0, level, looking north
  // at it: a point at height z on the axis is at window y = 50 + 50 z / 100 px, so the window's
  // top edge is z = 100 m there.
  HeightField f;
  f.nx = 3;
  f.ny = 1;
  f.spacing = 10;
  f.z = {0, 150, 0};
  std::vector<double> z_lod = {200, 200, std::nan("")};
  scenes::CameraSettings cam;
  cam.width = cam.height = 100;
  cam.fov_y_deg = 90;
  cam.near = 1;
  cam.far = 1000;
  scenes::Viewpoint vp;
  vp.eye = {0, -100, 0};
  vp.target = {0, 0, 0};
  // vertex 0: z 0..200 crosses the top edge: the visible part z 0..100 is 50 px long
  // vertex 1 (10 m east): z 150..200 lies wholly above the window: excluded
  z_lod[2] = 0;
  ScreenErrorResult r = measure_screen_error(z_lod, f, cam, vp);
  EXPECT_EQ(r.checked, 2u);  // vertex 2: no error, fully visible
  EXPECT_EQ(r.partially_visible, 1u);
  EXPECT_EQ(r.excluded, 1u);
  EXPECT_EQ(r.holes, 0u);
  EXPECT_NEAR(r.max_px, 50, 1e-9);
  EXPECT_EQ(r.worst_vertex, 0);
  EXPECT_NEAR(r.worst_x, 50, 1e-9);
  EXPECT_NEAR(r.worst_y, 50, 1e-9);
  // the old rule (both ends inside) would have skipped vertex 0 and reported 0
  // a hole (no LOD surface over vertex 2) is counted and is the worst vertex
  z_lod[2] = std::nan("");
  r = measure_screen_error(z_lod, f, cam, vp);
  EXPECT_EQ(r.holes, 1u);
  EXPECT_TRUE(std::isinf(r.max_px));
  EXPECT_EQ(r.worst_vertex, 2);
  EXPECT_NEAR(r.worst_x, 50 + 50 * 20.0 / 100, 1e-9);  // x = 20 m at 100 m: right of the centre
  // a segment through the near plane: only the part in front is measured
  double t0 = -1, t1 = -1;
  EXPECT_TRUE(clip_segment({0, 0, -2, 1}, {0, 0, 0, 1}, &t0, &t1));
  EXPECT_NEAR(t0, 0.5, 1e-12);
  EXPECT_NEAR(t1, 1, 1e-12);
  EXPECT_FALSE(clip_segment({2, 0, 0, 1}, {3, 0, 0, 1}, &t0, &t1));
}

TEST(Checks, ThreeByThreeTilesConformAndSeamsAgree) {
  // the centre tile flat (two triangles on its own), the eight around it rough: with independent
  // seams its four seams crack, with equalised ones they agree
  HeightField f = test_field(17, 3, 3, 11);
  for (int j = 16; j <= 32; ++j)
    for (int i = 16; i <= 32; ++i) f.z[size_t(j * f.nx + i)] = 0;
  TerrainHierarchy h(f, 17, ErrorPropagation::kNested);
  TerrainHierarchy raw(f, 17, ErrorPropagation::kNested, false);
  int raw_bad = 0;
  std::vector<scenes::Viewpoint> views = random_viewpoints(f, 16, 21);
  scenes::Viewpoint centre;
  centre.eye = {240, 240, 300};
  centre.target = {245, 250, 0};
  views.push_back(centre);
  for (const scenes::Viewpoint& vp : views) {
    const FrameCheck c = check_frame(h, LambdaKind::kWindow, 1.0, vp);
    EXPECT_TRUE(c.conforming);
    EXPECT_TRUE(c.seams_ok);
    EXPECT_LE(c.max_px, 1.0);
    raw_bad += !check_frame(raw, LambdaKind::kWindow, 1.0, vp).seams_ok;
  }
  const LodMesh full = full_resolution(h);
  const SeamResult s = check_seams(full, h);
  EXPECT_TRUE(s.ok);
  EXPECT_EQ(s.seams, 12u);  // 2 x 3 east seams + 3 x 2 north seams
  EXPECT_GT(raw_bad, 0);    // the check does see cracks on this terrain
}

}  // namespace
}  // namespace ra::lod
