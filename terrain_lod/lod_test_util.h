// Small terrains and viewpoints shared by the terrain_lod tests.
#pragma once

#include <cmath>
#include <vector>

#include "util/counter_rng.h"
#include "scenes/scene.h"
#include "terrain_lod/height_field.h"
#include "scenes/camera.h"

namespace ra::lod::testing {

// A fractal terrain of tiles_x x tiles_y tiles of `tile` vertices, 10 m spacing, heights 0..150 m
// with features of 160 m (rough at this size, so every level of the hierarchy has error).
inline HeightField test_field(int tile, int tiles_x, int tiles_y, uint64_t seed = 3) {
  scenes::TerrainParams p;
  p.seed = seed;
  p.spacing = 10;
  p.height_scale = 150;
  p.feature_size = 160;
  p.octaves = 5;
  return generate_height_field(p, tiles_x * (tile - 1) + 1, tiles_y * (tile - 1) + 1);
}

inline scenes::CameraSettings test_camera() {
  scenes::CameraSettings cam;
  cam.width = 320;
  cam.height = 240;
  cam.fov_y_deg = 60;
  cam.near = 1;
  cam.far = 100000;
  return cam;
}

// Random viewpoints over (and a little outside) the terrain, 5..400 m above its top, looking at
// a random point of it.
inline std::vector<scenes::Viewpoint> random_viewpoints(const HeightField& f, int count,
                                                        uint64_t seed) {
  // CounterRng: the same viewpoints with every standard library (std distributions are not)
  util::CounterRng rng(seed, uint64_t(0x4c4f44), 0);  // stream tag "LOD"
  const double ex = (f.nx - 1) * f.spacing, ey = (f.ny - 1) * f.spacing;
  double top = 0;
  for (double z : f.z) top = std::max(top, z);
  std::vector<scenes::Viewpoint> out;
  for (int k = 0; k < count; ++k) {
    scenes::Viewpoint vp;
    vp.eye = {-0.2 * ex + 1.4 * ex * rng.uniform01(), -0.2 * ey + 1.4 * ey * rng.uniform01(),
              top + 5 + 395 * rng.uniform01() * rng.uniform01()};
    vp.target = {ex * rng.uniform01(), ey * rng.uniform01(), top * rng.uniform01()};
    out.push_back(vp);
  }
  return out;
}

}  // namespace ra::lod::testing
