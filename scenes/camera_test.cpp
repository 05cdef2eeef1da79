// Tests of the study camera (camera.h): clipped alpha, its inverse and frustum culling, against
// closed forms.
#include "scenes/camera.h"

#include <gtest/gtest.h>

#include <cmath>

namespace ra::scenes {
namespace {

// A sphere straight ahead, wholly in view: the clipped alpha is the unclipped 2 asin(r / d).
TEST(Camera, ClippedAlphaOnAxis) {
  CameraSettings cam;
  const BoundingSphere s{{0, 0, 0}, 2.0};
  Viewpoint vp;
  vp.eye = {20, 0, 0};
  vp.target = {0, 0, 0};
  EXPECT_NEAR(clipped_alpha(look_at(vp), cam, s), 2 * std::asin(2.0 / 20.0), 1e-12);
  // eye inside the sphere: the whole window
  vp.eye = {1, 0, 0};
  EXPECT_NEAR(clipped_alpha(look_at(vp), cam, s), max_clipped_alpha(cam), 1e-12);
  // behind the camera: not in view
  vp.eye = {20, 0, 0};
  vp.target = {40, 0, 0};
  EXPECT_EQ(clipped_alpha(look_at(vp), cam, s), 0.0);
}

// viewpoint_for is the inverse of clipped_alpha on the axis, for small and window-filling sizes.
TEST(Camera, ViewpointForRoundTrips) {
  CameraSettings cam;
  const BoundingSphere s{{100, 50, 10}, 7.5};
  for (double alpha : {0.01, 0.2, 0.9, 1.1, max_clipped_alpha(cam) * 0.999})
    for (double gamma : {0.0, 2.0, 5.5})
      for (double phi : {-0.3, 0.0, 1.2}) {
        const Viewpoint vp = viewpoint_for(s, cam, alpha, gamma, phi);
        EXPECT_NEAR(clipped_alpha(look_at(vp), cam, s), alpha, 1e-6 * alpha + 1e-9)
            << alpha << " " << gamma << " " << phi;
        double g, p;
        view_direction_angles(vp.eye, s.centre, &g, &p);
        EXPECT_NEAR(g, gamma, 1e-9);
        EXPECT_NEAR(p, phi, 1e-9);
      }
}

// Frustum culling of bounding spheres: in front kept, behind / beyond far / far aside dropped,
// straddling a side plane kept.
TEST(Camera, FrustumCulling) {
  CameraSettings cam;
  cam.near = 1, cam.far = 1000;
  Viewpoint vp;
  vp.eye = {0, 0, 0};
  vp.target = {1, 0, 0};
  const Frustum f = frustum_of(projection_of(cam) * look_at(vp));
  EXPECT_TRUE(f.intersects({{50, 0, 0}, 1}));
  EXPECT_FALSE(f.intersects({{-50, 0, 0}, 1}));
  EXPECT_FALSE(f.intersects({{1100, 0, 0}, 10}));
  EXPECT_FALSE(f.intersects({{10, 100, 0}, 1}));
  // the left plane at 10 m ahead is at y = 10 * tan(half fov x); a sphere centred 1 m outside it
  // with radius 2 crosses it
  const double edge = 10 * std::tan(cam.half_fov_x());
  EXPECT_TRUE(f.intersects({{10, edge + 1, 0}, 2}));
  EXPECT_FALSE(f.intersects({{10, edge + 5, 0}, 2}));
}

}  // namespace
}  // namespace ra::scenes
